// Checkpoint files (io/checkpoint.hpp): a round trip keeps every bit, and every damaged,
// truncated or foreign file is refused with a message naming the file and the problem, never
// read past its end nor trusted for a size.

#include <sys/stat.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "glint/io/checkpoint.hpp"
#include "peak_memory.hpp"

namespace fs = std::filesystem;

namespace {

glint::CheckpointKey sample_key() {
  glint::RenderSettings settings;
  settings.width = 5;
  settings.height = 3;
  settings.samples_per_pixel = 100;
  settings.max_depth = 7;
  settings.seed = 0x0123456789abcdefULL;
  settings.antialias_sigma = 0.4f;
  settings.max_pass_samples = 32;
  return glint::CheckpointKey::of(0xfeedfacecafebeefULL, "report", settings);
}

/// A checkpoint after pass 7 of 100 spp in passes of at most 32: 1, 2, 4, 8, 16, 32, 64.
glint::Checkpoint sample_checkpoint() {
  glint::Checkpoint c;
  c.key = sample_key();
  c.passes_done = 7;
  c.samples_per_pixel_done = 64;
  c.sums = glint::PixelSums(5, 3);
  double v = 0.25;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x, v *= 1.7)
      c.sums.at(x, y) =
          glint::ColorSum(v, -0.0, std::numeric_limits<double>::denorm_min() * double(x));
  return c;
}

bool same_bits(const glint::PixelSums& a, const glint::PixelSums& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.pixels().data(), b.pixels().data(),
                     a.pixels().size() * sizeof(glint::ColorSum)) == 0;
}

/// The message of the CheckpointError that decoding `bytes` throws, or "" if none.
std::string decode_error(const std::vector<char>& bytes) {
  try {
    glint::decode_checkpoint(bytes, "ck.bin");
  } catch (const glint::CheckpointError& error) {
    return error.what();
  }
  return "";
}

/// The bytes with the content hash at the end recomputed, as a file damaged or forged with
/// care would have it: the checks behind the hash must still catch it.
std::vector<char> rehashed(std::vector<char> bytes) {
  const std::uint64_t hash = glint::fnv1a(bytes.data(), bytes.size() - 8);
  for (int i = 0; i < 8; ++i)
    bytes[bytes.size() - 8 + std::size_t(i)] = static_cast<char>(hash >> (8 * i));
  return bytes;
}

void put32(std::vector<char>& bytes, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    bytes[at + std::size_t(i)] = static_cast<char>(v >> (8 * i));
}

// Offsets in the sample checkpoint (variant "report", 6 bytes).
constexpr std::size_t kVersionAt = 8, kNameSizeAt = 20, kWidthAt = 30, kPassesAt = 62,
                      kLayersAt = 70, kSumsAt = 74;

/// sample_checkpoint with a splat layer: in pixel (x, y), channel c, coarse words of x + 3y + c
/// units and fine words of alternating sign (as the rounding of each splat leaves them).
glint::Checkpoint sample_checkpoint_with_splats() {
  glint::Checkpoint c = sample_checkpoint();
  const glint::PixelSums plain = c.sums;
  c.sums = glint::PixelSums(5, 3, true);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      c.sums.at(x, y) = plain.at(x, y);
  std::vector<std::int64_t>& words = c.sums.splats().words();
  for (std::size_t i = 0; i < words.size(); i += 2) {
    const auto pixel = std::int64_t(i / glint::SplatSums::kWordsPerPixel);
    const auto channel = std::int64_t(i % glint::SplatSums::kWordsPerPixel / 2);
    words[i] = pixel + channel;
    words[i + 1] = words[i] == 0 ? 12345 : (i % 4 == 0 ? 1 : -1) * (std::int64_t{1} << 39);
  }
  return c;
}

/// The message with which read_checkpoint refuses `path`, or "" if it reads it.
std::string refusal(const fs::path& path) {
  try {
    glint::read_checkpoint(path);
  } catch (const glint::CheckpointError& error) {
    return std::string(error.what());
  }
  return std::string();
}

}  // namespace

TEST_CASE("a checkpoint round trip keeps every field and every bit of the sums", "[checkpoint]") {
  const glint::Checkpoint c = sample_checkpoint();
  const std::vector<char> bytes = glint::encode_checkpoint(c);
  CHECK(bytes.size() == kSumsAt + 5 * 3 * 24 + 8);
  CHECK(std::string(bytes.data(), 8) == "GLINTCKP");
  const glint::Checkpoint back = glint::decode_checkpoint(bytes, "ck.bin");
  CHECK(back.key.scene_hash == c.key.scene_hash);
  CHECK(back.key.variant == "report");
  CHECK(back.key.width == 5);
  CHECK(back.key.height == 3);
  CHECK(back.key.samples_per_pixel == 100);
  CHECK(back.key.max_depth == 7);
  CHECK(back.key.max_pass_samples == 32);
  CHECK(back.key.seed == c.key.seed);
  CHECK(back.key.antialias_sigma == 0.4f);
  CHECK(back.passes_done == 7);
  CHECK(back.samples_per_pixel_done == 64);
  CHECK(same_bits(back.sums, c.sums));
  CHECK(glint::encode_checkpoint(back) == bytes);
  CHECK_NOTHROW(glint::check_checkpoint_matches(back, sample_key(), "ck.bin"));
}

TEST_CASE("the format is little-endian with explicit sizes", "[checkpoint]") {
  const std::vector<char> bytes = glint::encode_checkpoint(sample_checkpoint());
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
      v |= std::uint32_t(static_cast<unsigned char>(bytes[at + std::size_t(i)])) << (8 * i);
    return v;
  };
  CHECK(u32(kVersionAt) == glint::kCheckpointVersion);
  CHECK(u32(kNameSizeAt) == 6);
  CHECK(std::string(bytes.data() + 24, 6) == "report");
  CHECK(u32(kWidthAt) == 5);
  CHECK(u32(kWidthAt + 4) == 3);
  CHECK(u32(kPassesAt) == 7);
  CHECK(u32(kPassesAt + 4) == 64);
  CHECK(u32(kLayersAt) == 0);
  double first = 0.0;
  const std::uint64_t bits = u32(kSumsAt) | std::uint64_t(u32(kSumsAt + 4)) << 32;
  std::memcpy(&first, &bits, 8);
  CHECK(first == 0.25);
}

TEST_CASE("a checkpoint whose sums are not finite is refused", "[checkpoint]") {
  for (const double bad :
       {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::quiet_NaN()}) {
    glint::Checkpoint c = sample_checkpoint();
    c.sums.at(2, 1).y = bad;
    CHECK_THAT(decode_error(glint::encode_checkpoint(c)),
               Catch::Contains("pixel (2, 1) holds a sum that is not finite"));
  }
}

TEST_CASE("a checkpoint whose sums are negative is refused", "[checkpoint]") {
  // Forged with care: the content hash matches. A render's samples are never negative.
  for (const double bad : {-1e-300, -0.25, -std::numeric_limits<double>::max()}) {
    glint::Checkpoint c = sample_checkpoint();
    c.sums.at(4, 2).z = bad;
    CHECK_THAT(decode_error(glint::encode_checkpoint(c)),
               Catch::EndsWith("pixel (4, 2) holds a negative sum, which no render makes"));
  }
  // -0.0 is zero: accepted (sample_checkpoint has it in every pixel).
  CHECK(decode_error(glint::encode_checkpoint(sample_checkpoint())).empty());
}

TEST_CASE("a truncated checkpoint is refused at any length", "[checkpoint]") {
  const std::vector<char> bytes = glint::encode_checkpoint(sample_checkpoint());
  for (const std::size_t size : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(8),
                                 std::size_t(12), std::size_t(23), std::size_t(29), kSumsAt - 1,
                                 kSumsAt, kSumsAt + 13, bytes.size() - 8, bytes.size() - 1}) {
    INFO(size << " of " << bytes.size() << " bytes");
    const std::string message =
        decode_error(std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(size)));
    CHECK_THAT(message, Catch::StartsWith("cannot resume from ck.bin: "));
    // The first 8 bytes decide whether it is a checkpoint at all.
    if (size >= 8) CHECK_THAT(message, Catch::Contains("truncated"));
  }
  std::vector<char> longer = bytes;
  longer.push_back('x');
  CHECK_THAT(decode_error(longer), Catch::Contains("too long"));
}

TEST_CASE("a checkpoint with a bad magic, version or header is refused", "[checkpoint]") {
  const std::vector<char> good = glint::encode_checkpoint(sample_checkpoint());
  std::vector<char> bytes = good;

  SECTION("magic") {
    bytes[3] = 'X';
    CHECK(decode_error(bytes) ==
          "cannot resume from ck.bin: it is not a glint checkpoint (no GLINTCKP magic)");
  }
  SECTION("version") {
    put32(bytes, kVersionAt, 1);  // float sums, before glint summed in double
    CHECK(decode_error(bytes) ==
          "cannot resume from ck.bin: format version 1, this glint reads version 3");
    put32(bytes, kVersionAt, 2);  // no count of layers, no splats
    CHECK(decode_error(bytes) ==
          "cannot resume from ck.bin: format version 2, this glint reads version 3");
  }
  SECTION("a variant name longer than any") {
    put32(bytes, kNameSizeAt, 0xffffffffu);
    CHECK_THAT(decode_error(bytes), Catch::Contains("a variant name of 4294967295 bytes"));
  }
  SECTION("a size beyond the limits, which must not be allocated") {
    put32(bytes, kWidthAt, 1u << 15);
    put32(bytes, kWidthAt + 4, 1u << 15);
    CHECK_THAT(decode_error(rehashed(bytes)), Catch::Contains("an image size of 32768x32768"));
    put32(bytes, kWidthAt, 0);
    CHECK_THAT(decode_error(rehashed(bytes)), Catch::Contains("an image size of 0x"));
  }
  SECTION("a size within the limits that the file does not hold") {
    put32(bytes, kWidthAt, 4096);
    put32(bytes, kWidthAt + 4, 4096);
    CHECK_THAT(decode_error(rehashed(bytes)),
               Catch::Contains("truncated (" + std::to_string(good.size()) +
                               " bytes, the header promises " +
                               std::to_string(kSumsAt + 4096 * 4096 * 24 + 8) + ")"));
    put32(bytes, kWidthAt, 4);
    put32(bytes, kWidthAt + 4, 3);
    CHECK_THAT(decode_error(rehashed(bytes)), Catch::Contains("too long"));
  }
  SECTION("layers beyond the sums and their splats") {
    put32(bytes, kLayersAt, 2);
    CHECK_THAT(decode_error(rehashed(bytes)), Catch::Contains("2 layers of sums"));
  }
  SECTION("a splat layer that the file does not hold") {
    put32(bytes, kLayersAt, 1);
    CHECK_THAT(decode_error(rehashed(bytes)),
               Catch::Contains("truncated (" + std::to_string(good.size()) +
                               " bytes, the header promises " +
                               std::to_string(kSumsAt + 5 * 3 * (24 + 48) + 8) + ")"));
  }
  SECTION("passes that end at no pass boundary") {
    put32(bytes, kPassesAt + 4, 63);
    CHECK_THAT(decode_error(rehashed(bytes)),
               Catch::Contains("7 passes of 63 samples per pixel, which is no pass boundary"));
    put32(bytes, kPassesAt, 0);
    CHECK_THAT(decode_error(rehashed(bytes)), Catch::Contains("0 passes"));
    put32(bytes, kPassesAt, 10);
    CHECK_THAT(decode_error(rehashed(bytes)), Catch::Contains("10 passes"));
  }
}

TEST_CASE("a checkpoint keeps the splat layer of a light-traced render, bit for bit",
          "[checkpoint]") {
  const glint::Checkpoint c = sample_checkpoint_with_splats();
  const std::vector<char> bytes = glint::encode_checkpoint(c);
  REQUIRE(bytes.size() == kSumsAt + 5 * 3 * (24 + 48) + 8);
  const auto word = [&](std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i)
      v |= std::uint64_t(static_cast<unsigned char>(bytes[at + std::size_t(i)])) << (8 * i);
    return std::int64_t(v);
  };
  CHECK((std::uint64_t(word(kLayersAt)) & 0xffffffffu) == 1);
  // The splat words follow the sums, pixel by pixel: pixel 1's red coarse word is 1.
  CHECK(word(kSumsAt + 5 * 3 * 24 + 48) == 1);
  const glint::Checkpoint back = glint::decode_checkpoint(bytes, "ck.bin");
  REQUIRE(back.sums.has_splats());
  CHECK(same_bits(back.sums, c.sums));
  CHECK(back.sums.splats().words() == c.sums.splats().words());
  CHECK(glint::encode_checkpoint(back) == bytes);

  // Read from a file in pieces, as --resume does.
  const fs::path dir = fs::temp_directory_path() / "glint-checkpoint-splats-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "ck.bin";
  std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  const glint::Checkpoint read = glint::read_checkpoint(file);
  CHECK(read.sums.splats().words() == c.sums.splats().words());
  CHECK(same_bits(read.sums, c.sums));
  fs::remove_all(dir);
}

TEST_CASE("a checkpoint whose splat sums are negative is refused", "[checkpoint]") {
  // A splat sum is coarse 2^-16 + fine 2^-56 per channel, the sum of light: never below zero.
  // Forged with care (the content hash matches), each of these is.
  const std::int64_t kFineUnitsPerCoarse = std::int64_t{1} << 40;
  for (const auto& [coarse, fine] : std::vector<std::pair<std::int64_t, std::int64_t>>{
           {-1, 0},
           {0, -1},
           {1, -kFineUnitsPerCoarse - 1},
           {3, std::numeric_limits<std::int64_t>::min()}}) {
    INFO("coarse " << coarse << ", fine " << fine);
    glint::Checkpoint c = sample_checkpoint_with_splats();
    std::int64_t* green = c.sums.splats().words().data() + (2 * 5 + 3) * 6 + 2;
    green[0] = coarse;
    green[1] = fine;
    CHECK_THAT(decode_error(glint::encode_checkpoint(c)),
               Catch::EndsWith("pixel (3, 2) holds a negative splat sum, which no render makes"));
  }
  // Exactly zero, and the smallest fine part a coarse unit carries, are sound.
  for (const auto& [coarse, fine] : std::vector<std::pair<std::int64_t, std::int64_t>>{
           {1, -kFineUnitsPerCoarse}, {0, 0}, {std::int64_t{1} << 23, -(std::int64_t{1} << 62)}}) {
    glint::Checkpoint c = sample_checkpoint_with_splats();
    std::int64_t* green = c.sums.splats().words().data() + (2 * 5 + 3) * 6 + 2;
    green[0] = coarse;
    green[1] = fine;
    CHECK(decode_error(glint::encode_checkpoint(c)).empty());
  }
}

TEST_CASE("a damaged checkpoint is refused by its content hash", "[checkpoint]") {
  const std::vector<char> good = glint::encode_checkpoint(sample_checkpoint());
  for (const std::size_t at :
       {std::size_t(12), kWidthAt + 8, kSumsAt, good.size() - 9, good.size() - 1}) {
    INFO("byte " << at << " changed");
    std::vector<char> bytes = good;
    bytes[at] = static_cast<char>(bytes[at] ^ 0x10);
    CHECK(decode_error(bytes) ==
          "cannot resume from ck.bin: it is damaged (its content hash does not match)");
  }
}

TEST_CASE("a checkpoint of another render is refused, naming the difference", "[checkpoint]") {
  const glint::Checkpoint c = sample_checkpoint();
  const auto refusal = [&](const glint::CheckpointKey& key) {
    try {
      glint::check_checkpoint_matches(c, key, "ck.bin");
    } catch (const glint::CheckpointError& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  glint::CheckpointKey key = sample_key();
  key.scene_hash ^= 1;
  CHECK(refusal(key) ==
        "cannot resume from ck.bin: it was made from another scene (the scene file's bytes or its "
        "images differ)");
  key = sample_key();
  key.variant = "fast";
  CHECK(refusal(key) ==
        "cannot resume from ck.bin: it was made by variant 'report', this is variant 'fast'");
  key = sample_key();
  key.samples_per_pixel = 128;
  CHECK(refusal(key) ==
        "cannot resume from ck.bin: it was made with samples per pixel 100, this render has 128");
  key = sample_key();
  key.width = 6;
  CHECK_THAT(refusal(key), Catch::Contains("width 5, this render has 6"));
  key = sample_key();
  key.height = 2;
  CHECK_THAT(refusal(key), Catch::Contains("height 3, this render has 2"));
  key = sample_key();
  key.max_depth = 3;
  CHECK_THAT(refusal(key), Catch::Contains("max depth 7, this render has 3"));
  key = sample_key();
  key.seed = 1;
  CHECK_THAT(refusal(key), Catch::Contains("seed 81985529216486895, this render has 1"));
  key = sample_key();
  key.max_pass_samples = 4;
  CHECK_THAT(refusal(key), Catch::Contains("samples per pass at most 32, this render has 4"));
  key = sample_key();
  key.antialias_sigma = std::nextafter(0.4f, 1.0f);
  CHECK_THAT(refusal(key), Catch::Contains("antialias sigma"));
}

TEST_CASE("read_checkpoint reads a file, and refuses what is no checkpoint", "[checkpoint]") {
  const fs::path dir = fs::path(GLINT_BINARY_DIR) / "unit-scratch" / "checkpoint";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto write = [&](const std::string& name, const std::vector<char>& bytes) {
    std::ofstream(dir / name, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return dir / name;
  };
  const glint::Checkpoint c = sample_checkpoint();
  const std::vector<char> bytes = glint::encode_checkpoint(c);
  const glint::Checkpoint back = glint::read_checkpoint(write("good.ck", bytes));
  CHECK(same_bits(back.sums, c.sums));
  CHECK(back.passes_done == 7);

  CHECK_THAT(
      refusal(dir / "missing.ck"),
      Catch::StartsWith("cannot resume from " + (dir / "missing.ck").string() + ": No such"));
  CHECK_THAT(refusal(dir), Catch::EndsWith("it is a directory"));
  CHECK_THAT(refusal(write("empty.ck", {})), Catch::Contains("truncated (0 bytes)"));
  CHECK_THAT(refusal(write("short.ck", std::vector<char>(bytes.begin(), bytes.begin() + 40))),
             Catch::Contains("truncated (40 bytes)"));
  // A large file that is no checkpoint: refused from its first bytes.
  CHECK_THAT(refusal(write("other.ck", std::vector<char>(1 << 20, 'P'))),
             Catch::Contains("no GLINTCKP magic"));
  // A negative sum, forged with its hash, read from a file as from memory.
  glint::Checkpoint negative = sample_checkpoint();
  negative.sums.at(1, 1).x = -2.0;
  CHECK_THAT(refusal(write("negative.ck", glint::encode_checkpoint(negative))),
             Catch::EndsWith("pixel (1, 1) holds a negative sum, which no render makes"));
  // Devices that never end.
  CHECK_THAT(refusal("/dev/zero"),
             Catch::EndsWith("it is not a glint checkpoint (no GLINTCKP magic)"));
  CHECK_THAT(refusal("/dev/urandom"), Catch::Contains("cannot resume from /dev/urandom: "));
  fs::remove_all(dir);
}

TEST_CASE("read_checkpoint reads in pieces, and checks a header's size before allocating",
          "[checkpoint][hostile]") {
  const fs::path dir = fs::path(GLINT_BINARY_DIR) / "unit-scratch" / "checkpoint-sizes";
  // A reader that refuses early closes the pipe under its writer: EPIPE, not the signal.
  std::signal(SIGPIPE, SIG_IGN);
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A checkpoint of more pixels than one piece of the reader (2^14), and sums of every kind.
  glint::RenderSettings settings;
  settings.width = 300;
  settings.height = 200;
  settings.samples_per_pixel = 4;
  glint::Checkpoint big;
  big.key = glint::CheckpointKey::of(42, "report", settings);
  big.passes_done = 1;
  big.samples_per_pixel_done = 1;
  big.sums = glint::PixelSums(300, 200);
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 300; ++x)
      big.sums.at(x, y) = glint::ColorSum(x, y * 1e-3, 1e300 / (x + 1));
  const std::vector<char> bytes = glint::encode_checkpoint(big);
  const fs::path path = dir / "big.ck";
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  CHECK(same_bits(glint::read_checkpoint(path).sums, big.sums));
  // The same bytes through a pipe.
  const fs::path fifo = dir / "fifo.ck";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  std::thread writer([&] {
    std::ofstream(fifo, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  });
  CHECK(same_bits(glint::read_checkpoint(fifo).sums, big.sums));
  writer.join();
  // A negative sum in the last piece, a damaged byte in a middle one.
  big.sums.at(299, 199).y = -1.0;
  std::vector<char> forged = glint::encode_checkpoint(big);
  std::ofstream(path, std::ios::binary).write(forged.data(), std::streamsize(forged.size()));
  CHECK_THAT(refusal(path),
             Catch::EndsWith("pixel (299, 199) holds a negative sum, which no render makes"));
  forged[forged.size() / 2] ^= 1;
  std::ofstream(path, std::ios::binary).write(forged.data(), std::streamsize(forged.size()));
  CHECK_THAT(refusal(path), Catch::EndsWith("it is damaged (its content hash does not match)"));

  // Headers claiming 32768x32768 (beyond glint's limits) and 8192x8192 (within them, 1.6 GB of
  // sums) over a few bytes, from a file and from a pipe: refused before the sums are allocated.
  struct Claim {
    std::uint32_t width, height;
    std::string message;
  };
  for (const Claim& size : {Claim{32768, 32768, "an image size of 32768x32768"},
                            Claim{8192, 8192, "it is truncated"}}) {
    const std::uint32_t width = size.width, height = size.height;
    const std::string& message = size.message;
    CAPTURE(width);
    std::vector<char> claim = bytes;
    put32(claim, kWidthAt, width);
    put32(claim, kWidthAt + 4, height);
    claim.resize(4096);
    std::ofstream(path, std::ios::binary).write(claim.data(), std::streamsize(claim.size()));
    const glint_test::ChildRun from_file = glint_test::run_in_child_above_baseline(
        [&] { return refusal(path).find(message) != std::string::npos ? 0 : 3; });
    CHECK(from_file.status == 0);
    CHECK(from_file.peak_kb < 64 * 1024);
    const glint_test::ChildRun from_pipe = glint_test::run_in_child_above_baseline([&] {
      std::thread pipe_writer([&] {
        std::ofstream(fifo, std::ios::binary).write(claim.data(), std::streamsize(claim.size()));
      });
      const bool refused = refusal(fifo).find(message) != std::string::npos;
      pipe_writer.join();
      return refused ? 0 : 3;
    });
    CHECK(from_pipe.status == 0);
    CHECK(from_pipe.peak_kb < 64 * 1024);
  }
  fs::remove_all(dir);
}
