// Safe output (io/image_writer.hpp): StagedFile's unique O_EXCL temporaries beside the target,
// write_files' all-or-nothing, check_output_path's refusals, and links never written through.

#include <catch2/catch.hpp>

#include <climits>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "glint/io/image_writer.hpp"

namespace fs = std::filesystem;

namespace {

/// An empty directory under the build tree, removed with its contents afterwards.
class Scratch {
 public:
  explicit Scratch(const std::string& name)
      : path_(fs::path(GLINT_BINARY_DIR) / "unit-scratch" / name) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }
  /// The names in the directory.
  std::vector<std::string> names() const {
    std::vector<std::string> result;
    for (const fs::directory_entry& e : fs::directory_iterator(path_))
      result.push_back(e.path().filename().string());
    std::sort(result.begin(), result.end());
    return result;
  }

 private:
  fs::path path_;
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::vector<char> bytes_of(const std::string& text) {
  return {text.begin(), text.end()};
}

}  // namespace

TEST_CASE("a staged file is a new, unpredictable file beside its target until commit",
          "[image][output]") {
  Scratch dir("staged");
  const fs::path target = dir.path() / "out.png";
  write_text(target, "old");
  {
    glint::StagedFile a(target);
    glint::StagedFile b(target);  // two writers of one target never share a temporary
    CHECK(a.temporary() != b.temporary());
    CHECK(a.temporary().parent_path() == target.parent_path());
    const std::regex name(R"(out\.png\.[0-9a-f]{12}\.glint-partial)");
    CHECK(std::regex_match(a.temporary().filename().string(), name));
    CHECK(fs::is_regular_file(a.temporary()));
    a.write(bytes_of("new"));
    CHECK(read_text(target) == "old");
    CHECK(read_text(a.temporary()) == "new");
    a.commit();
    CHECK(read_text(target) == "new");
    CHECK_FALSE(fs::exists(a.temporary()));
  }  // b, never committed, removes its temporary
  CHECK(dir.names() == std::vector<std::string>{"out.png"});
}

TEST_CASE("a staged file gets the permissions of any new file", "[image][output]") {
  Scratch dir("staged-mode");
  write_text(dir.path() / "reference", "");
  glint::StagedFile file(dir.path() / "out.pfm");
  file.write(bytes_of("x"));
  file.commit();
  struct stat made {
  }, reference{};
  REQUIRE(::stat((dir.path() / "out.pfm").c_str(), &made) == 0);
  REQUIRE(::stat((dir.path() / "reference").c_str(), &reference) == 0);
  CHECK((made.st_mode & 07777) == (reference.st_mode & 07777));
}

TEST_CASE("a symbolic link at the target is replaced, never written through", "[image][output]") {
  Scratch dir("staged-link");
  write_text(dir.path() / "victim", "precious");
  fs::create_symlink("victim", dir.path() / "out.png");
  // An older glint-render's fixed temporary name, planted as a link.
  fs::create_symlink("victim", dir.path() / "out.png.glint-partial");
  glint::write_files({{dir.path() / "out.png", bytes_of("image")}});
  CHECK(read_text(dir.path() / "victim") == "precious");
  CHECK_FALSE(fs::is_symlink(dir.path() / "out.png"));
  CHECK(read_text(dir.path() / "out.png") == "image");
  CHECK(fs::read_symlink(dir.path() / "out.png.glint-partial") == "victim");
}

TEST_CASE("write_files writes all files or none", "[image][output]") {
  Scratch dir("write-files");
  write_text(dir.path() / "a.png", "old a");
  SECTION("a file that cannot be created: the others stay as they were") {
    CHECK_THROWS_WITH(glint::write_files({{dir.path() / "a.png", bytes_of("new a")},
                                          {dir.path() / "missing" / "b.pfm", bytes_of("b")}}),
                      Catch::Contains("missing/b.pfm"));
    CHECK(read_text(dir.path() / "a.png") == "old a");
    CHECK(dir.names() == std::vector<std::string>{"a.png"});
  }
  SECTION("all written") {
    glint::write_files(
        {{dir.path() / "a.png", bytes_of("new a")}, {dir.path() / "b.pfm", bytes_of("b")}});
    CHECK(read_text(dir.path() / "a.png") == "new a");
    CHECK(read_text(dir.path() / "b.pfm") == "b");
    CHECK(dir.names() == std::vector<std::string>{"a.png", "b.pfm"});
  }
}

TEST_CASE("check_output_path refuses what cannot be written, naming it", "[image][output]") {
  Scratch dir("check-output");
  const auto problem = [](const fs::path& target) -> std::string {
    try {
      glint::check_output_path(target);
      return "";
    } catch (const glint::ImageWriteError& e) {
      return e.what();
    }
  };
  fs::create_directory(dir.path() / "taken.png");
  write_text(dir.path() / "file", "");
  const std::string base = dir.path().string();
  CHECK(problem(dir.path() / "out.png").empty());
  CHECK(problem(dir.path() / "no" / "out.png") ==
        "cannot write " + base + "/no/out.png: directory " + base + "/no does not exist");
  CHECK(problem(dir.path() / "file" / "out.png") ==
        "cannot write " + base + "/file/out.png: " + base + "/file is not a directory");
  CHECK(problem(dir.path() / "taken.png") ==
        "cannot write " + base + "/taken.png: it is a directory");
  CHECK(problem(dir.path() / "sub/") == "cannot write " + base + "/sub/: the name is a directory");
  // A name one byte beyond NAME_MAX (255 on Linux's file systems), and a path beyond PATH_MAX.
  const std::string long_name = std::string(252, 'n') + ".pfm";
  CHECK(problem(dir.path() / long_name) ==
        "cannot write " + base + "/" + long_name +
            ": the file name is 256 bytes long, more than the 255 its file system allows");
  CHECK(problem(dir.path() / (std::string(251, 'n') + ".pfm")).empty());
  fs::path deep = dir.path();
  while (deep.native().size() < PATH_MAX)
    deep /= std::string(200, 'd');
  CHECK_THAT(problem(deep / "out.png"), Catch::Contains("the path is "));
  // The temporaries that showed the directory writable are gone.
  CHECK(dir.names() == std::vector<std::string>{"file", "taken.png"});
}

TEST_CASE("remove_stale_temporaries removes a target's own temporaries only", "[image][output]") {
  Scratch dir("stale-temporaries");
  const fs::path target = dir.path() / "out.png";
  // Temporaries as StagedFile names them, one for a name so long that its prefix is cut.
  const fs::path long_target = dir.path() / (std::string(250, 'x') + ".pfm");
  const std::string long_temporary = std::string(228, 'x') + ".00000000abcd.glint-partial";
  REQUIRE(long_temporary.size() == 255);
  write_text(dir.path() / "out.png.0123456789ab.glint-partial", "stale");
  write_text(dir.path() / long_temporary, "stale");
  // Not temporaries of the target, or not files.
  write_text(dir.path() / "out.png.0123456789AB.glint-partial", "keep");
  write_text(dir.path() / "out.png.0123456789a.glint-partial", "keep");
  write_text(dir.path() / "out.pn.0123456789ab.glint-partial", "keep");
  write_text(dir.path() / "victim", "precious");
  fs::create_symlink("victim", dir.path() / "out.png.fedcba987654.glint-partial");
  fs::create_directory(dir.path() / "out.png.aaaaaaaaaaaa.glint-partial");
  CHECK(glint::remove_stale_temporaries(target) == 1);
  CHECK(glint::remove_stale_temporaries(long_target) == 1);
  CHECK(glint::remove_stale_temporaries(target) == 0);
  CHECK(read_text(dir.path() / "victim") == "precious");
  CHECK(dir.names() == std::vector<std::string>{"out.pn.0123456789ab.glint-partial",
                                                "out.png.0123456789AB.glint-partial",
                                                "out.png.0123456789a.glint-partial",
                                                "out.png.aaaaaaaaaaaa.glint-partial",
                                                "out.png.fedcba987654.glint-partial", "victim"});
  // What StagedFile itself makes is recognised.
  const glint::StagedFile staged(long_target);
  CHECK(glint::StagedFile::is_temporary_of(long_target, staged.temporary().filename().string()));
}
