// Every file in scenes/invalid/ must be rejected, by the reader or by the inclusion tree that
// building a Scene computes next, at the line and with the message its first line announces:
//
//   # expect: LINE: SUBSTRING

#include <catch2/catch.hpp>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "glint/io/scene_reader.hpp"
#include "glint/scene/inclusion_tree.hpp"

namespace {

struct Expectation {
  int line = -1;
  std::string substring;
};

Expectation read_expectation(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string first;
  std::getline(in, first);
  if (!first.empty() && first.back() == '\r') first.pop_back();
  const std::string prefix = "# expect: ";
  Expectation e;
  if (first.rfind(prefix, 0) != 0) return e;
  const char* begin = first.data() + prefix.size();
  const char* end = first.data() + first.size();
  const auto [ptr, ec] = std::from_chars(begin, end, e.line);
  if (ec != std::errc{} || end - ptr < 2 || ptr[0] != ':' || ptr[1] != ' ') return {};
  e.substring.assign(ptr + 2, end);
  return e;
}

}  // namespace

TEST_CASE("invalid scenes are rejected at the announced line", "[scene_reader][invalid]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GLINT_SOURCE_DIR) / "scenes" / "invalid";
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".scene") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 12);

  for (const fs::path& path : files) {
    DYNAMIC_SECTION(path.filename().string()) {
      const Expectation expected = read_expectation(path);
      INFO("first line must be '# expect: LINE: SUBSTRING'");
      REQUIRE(expected.line > 1);
      REQUIRE_FALSE(expected.substring.empty());
      try {
        (void)glint::build_inclusion_tree(glint::read_scene_file(path));
        FAIL("the scene was accepted");
      } catch (const glint::SceneError& error) {
        CHECK(error.source() == path.string());
        CHECK(error.line() == expected.line);
        CHECK_THAT(error.what(),
                   Catch::Matchers::StartsWith(path.string() + ":" + std::to_string(expected.line) +
                                               ": error: "));
        CHECK_THAT(error.what(), Catch::Matchers::Contains(expected.substring));
      }
    }
  }
}
