// Reading images from files nobody vouches for (io/image_reader.hpp): a header that claims more
// than the file holds, or more than glint's limits, is refused before the image is allocated;
// binary data and endless devices are refused from their first bytes; a pipe is read as far as
// its data arrives. Memory is measured as a child process's peak (peak_memory.hpp), against a
// bound far below what the headers claim (805 MB for 8192x8192, 12.9 GB for 32768x32768).

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/scratch_directory.hpp"
#include "glint/error.hpp"
#include "glint/io/image_reader.hpp"
#include "glint/io/image_writer.hpp"
#include "peak_memory.hpp"

namespace fs = std::filesystem;

namespace {

/// Far below any image the test files claim, and far above what reading a header takes.
constexpr long kBoundKb = 64 * 1024;

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

/// read_pfm's message for `path`, or "" if it reads.
std::string pfm_refusal(const fs::path& path) {
  try {
    glint::read_pfm(path);
  } catch (const glint::ImageReadError& error) {
    return error.what();
  }
  return "";
}

/// Reads `path` with read_pfm in a child: its peak memory above an idle child's, and whether
/// the refusal's message contained `expected` (status 0), was another (3) or did not come (4).
glint_test::ChildRun refused_in_child(const fs::path& path, const std::string& expected) {
  return glint_test::run_in_child_above_baseline([&] {
    const std::string message = pfm_refusal(path);
    if (message.empty()) return 4;
    if (message.find(expected) == std::string::npos) {
      std::fprintf(stderr, "unexpected message: %s\n", message.c_str());
      return 3;
    }
    return 0;
  });
}

}  // namespace

TEST_CASE("read_pfm: a header claiming more than the file holds is refused before allocating",
          "[image][hostile]") {
  const glint_test::ScratchDirectory scratch("image-reader");
  // 34 bytes claiming 32768x32768 (beyond glint's limits), and a header claiming 8192x8192
  // (within them) followed by one row.
  const fs::path huge = scratch.path() / "huge.pfm", short_file = scratch.path() / "short.pfm";
  write_bytes(huge, "PF\n32768 32768\n-1.0\n" + std::string(13, '\0'));
  write_bytes(short_file, "PF\n8192 8192\n-1.0\n" + std::string(8192 * 12, '\0'));
  CHECK(pfm_refusal(huge) == huge.string() +
                                 ": its header claims 32768x32768 pixels, beyond glint's limits "
                                 "(32768 pixels a side, 67108864 in all)");
  CHECK(pfm_refusal(short_file) ==
        short_file.string() +
            ": truncated PFM file: its header claims 8192x8192 pixels (805306368 bytes), the "
            "file holds 98304 bytes after the header");
  for (const fs::path& path : {huge, short_file}) {
    CAPTURE(path);
    const glint_test::ChildRun run = refused_in_child(path, "its header claims");
    CHECK(run.status == 0);
    CHECK(run.peak_kb < kBoundKb);
  }
}

TEST_CASE("read_pfm: a PNG, binary data and endless devices are refused from their first bytes",
          "[image][hostile]") {
  const glint_test::ScratchDirectory scratch("image-reader");
  // A PNG's signature and an IHDR chunk claiming 32768x32768 RGB: glint reads no PNG, and
  // its bytes are no PFM header.
  const fs::path png = scratch.path() / "huge.png";
  write_bytes(png,
              std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\x80\0\0\0\x80\0\x08\x02\0\0\0", 29) +
                  std::string(4, '\0'));
  const glint_test::ChildRun from_png = refused_in_child(png, "not a colour PFM file");
  CHECK(from_png.status == 0);
  CHECK(from_png.peak_kb < kBoundKb);
  // Devices that never end: a header parsed from an unbounded stream would read for ever.
  for (const char* device : {"/dev/zero", "/dev/urandom"}) {
    CAPTURE(device);
    const glint_test::ChildRun run = refused_in_child(device, "not a colour PFM file");
    CHECK(run.status == 0);
    CHECK(run.peak_kb < kBoundKb);
  }
  // A header of words too long for one: refused within kMaxPfmHeader bytes.
  const fs::path spaces = scratch.path() / "spaces.pfm";
  write_bytes(spaces, "PF" + std::string(1 << 20, ' ') + "1 1 -1\n");
  CHECK(pfm_refusal(spaces).find("not a colour PFM file") != std::string::npos);
  CHECK(pfm_refusal(scratch.path()) ==
        "cannot read " + scratch.path().string() + ": it is a directory");
  CHECK(pfm_refusal(scratch.path() / "missing.pfm") ==
        "cannot read " + (scratch.path() / "missing.pfm").string() + ": No such file or directory");
}

TEST_CASE("read_pfm: a pipe is read as far as its data arrives", "[image][hostile]") {
  const glint_test::ScratchDirectory scratch("image-reader");
  const fs::path fifo = scratch.path() / "fifo.pfm";
  // A reader that refuses early closes the pipe under its writer: EPIPE, not the signal.
  std::signal(SIGPIPE, SIG_IGN);
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  // A whole PFM through the pipe reads as from a file.
  glint::Film film(3, 2);
  film.at(2, 0) = glint::Color(1.0f, 2.0f, 3.0f);
  const std::vector<char> pfm = glint::encode_pfm(film);
  std::thread writer([&] {
    std::ofstream(fifo, std::ios::binary).write(pfm.data(), std::streamsize(pfm.size()));
  });
  const glint::Film back = glint::read_pfm(fifo);
  writer.join();
  REQUIRE(back.width() == 3);
  CHECK(back.at(2, 0) == glint::Color(1.0f, 2.0f, 3.0f));
  // A header claiming 8192x8192 and one row, then the end: the film is never allocated.
  const glint_test::ChildRun run = glint_test::run_in_child_above_baseline([&] {
    std::thread short_writer([&] {
      std::ofstream(fifo, std::ios::binary) << "PF\n8192 8192\n-1.0\n"
                                            << std::string(8192 * 12, 'x');
    });
    const std::string message = pfm_refusal(fifo);
    short_writer.join();
    return message.find("the file held 98304 after the header") != std::string::npos ? 0 : 3;
  });
  CHECK(run.status == 0);
  CHECK(run.peak_kb < kBoundKb);
}
