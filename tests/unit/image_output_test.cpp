// Image output: the sRGB transfer function, PFM layout and round trip, PNG contents decoded
// with stb_image (whose implementation Debian's libstb already contains), and failed writes.

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "../support/scratch_directory.hpp"
#include "glint/io/image_reader.hpp"
#include "glint/io/image_writer.hpp"
#include "stb_image.h"

namespace fs = std::filesystem;

namespace {

using glint_test::ScratchDirectory;

/// IEC 61966-2-1 in double precision.
double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

std::vector<unsigned char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t bits(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

glint::Film test_film(int width, int height) {
  glint::Film film(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      film.at(x, y) = glint::Color(float(x) / float(width), float(y) / float(height),
                                   0.5f + 0.01f * float(x * y));
  return film;
}

}  // namespace

TEST_CASE("linear_to_srgb8: the sRGB transfer function", "[image]") {
  CHECK(glint::linear_to_srgb8(0.0f) == 0);
  CHECK(glint::linear_to_srgb8(1.0f) == 255);
  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188.
  CHECK(srgb_encode(0.5) * 255.0 == Approx(187.5).margin(0.1));
  CHECK(glint::linear_to_srgb8(0.5f) == 188);
  // 18% grey: 0.4614 -> 117.7 -> 118.
  CHECK(glint::linear_to_srgb8(0.18f) == 118);
  // The linear segment ends at 0.0031308, where 12.92 x = 0.04045 -> 10.3 -> 10; both pieces
  // agree there.
  CHECK(glint::linear_to_srgb8(0.0031308f) == 10);
  CHECK(glint::linear_to_srgb8(std::nextafter(0.0031308f, 1.0f)) == 10);
  CHECK(glint::linear_to_srgb8(0.001f) == 3);  // 12.92e-3 * 255 = 3.29
  // Out of range and invalid values.
  CHECK(glint::linear_to_srgb8(-0.5f) == 0);
  CHECK(glint::linear_to_srgb8(std::numeric_limits<float>::quiet_NaN()) == 0);
  CHECK(glint::linear_to_srgb8(1.5f) == 255);
  CHECK(glint::linear_to_srgb8(std::numeric_limits<float>::infinity()) == 255);
  CHECK(glint::linear_to_srgb8(-std::numeric_limits<float>::infinity()) == 0);

  SECTION("matches the double-precision formula over [0, 1]") {
    int previous = 0, mismatches = 0, decreases = 0;
    for (int i = 0; i <= 200000; ++i) {
      const float x = float(i) / 200000.0f;
      const int code = glint::linear_to_srgb8(x);
      const double exact = srgb_encode(double(x)) * 255.0;
      const bool near_half = std::abs(exact - std::floor(exact) - 0.5) < 1e-3;
      if (code != int(std::lround(exact)) && !(near_half && std::abs(code - exact) < 0.51))
        ++mismatches;
      if (code < previous) ++decreases;
      previous = code;
    }
    CHECK(mismatches == 0);
    CHECK(decreases == 0);  // monotonic
  }
}

TEST_CASE("PFM: layout and bit-exact round trip", "[image]") {
  ScratchDirectory dir("pfm-test");
  glint::Film film = test_film(7, 3);
  film.at(0, 0) = glint::Color(-1.0f, 1e-40f, 3.4e38f);  // negative, subnormal, huge
  film.at(6, 2) = glint::Color(std::numeric_limits<float>::infinity(), 0.1f, -0.0f);
  film.at(3, 1) = glint::Color(std::numeric_limits<float>::quiet_NaN(), 1.0f / 3.0f, 1e-7f);
  const fs::path path = dir.path() / "film.pfm";
  glint::write_pfm(film, path);

  SECTION("header, size and bottom-to-top little-endian rows") {
    const std::vector<unsigned char> bytes = read_bytes(path);
    const std::string header = "PF\n7 3\n-1.0\n";
    REQUIRE(bytes.size() == header.size() + 7 * 3 * 3 * 4);
    CHECK(std::string(bytes.begin(), bytes.begin() + std::ptrdiff_t(header.size())) == header);
    const auto float_at = [&](std::size_t index) {
      const std::size_t o = header.size() + 4 * index;
      const std::uint32_t b = std::uint32_t(bytes[o]) | std::uint32_t(bytes[o + 1]) << 8 |
                              std::uint32_t(bytes[o + 2]) << 16 | std::uint32_t(bytes[o + 3]) << 24;
      return b;
    };
    // The first pixel in the file is the bottom-left one, film.at(0, 2).
    CHECK(float_at(0) == bits(film.at(0, 2).x));
    CHECK(float_at(1) == bits(film.at(0, 2).y));
    // The last row in the file is the top row, film.at(x, 0).
    CHECK(float_at(2 * 7 * 3) == bits(film.at(0, 0).x));
    CHECK(float_at(2 * 7 * 3 + 2) == bits(film.at(0, 0).z));
  }
  SECTION("read_pfm gives back the same bits") {
    const glint::Film back = glint::read_pfm(path);
    REQUIRE(back.width() == 7);
    REQUIRE(back.height() == 3);
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 7; ++x)
        for (int c = 0; c < 3; ++c) {
          INFO("pixel " << x << ", " << y << ", channel " << c);
          CHECK(bits(back.at(x, y)[c]) == bits(film.at(x, y)[c]));
        }
  }
  CHECK_FALSE(fs::exists(dir.path() / "film.pfm.glint-partial"));
}

TEST_CASE("PNG: decodes to the sRGB-encoded film", "[image]") {
  ScratchDirectory dir("png-test");
  glint::Film film = test_film(5, 4);
  film.at(0, 0) = glint::Color(0.5f, 0.0f, 1.0f);
  film.at(4, 3) = glint::Color(2.0f, -1.0f, 0.0031308f);
  const fs::path path = dir.path() / "film.png";
  glint::write_png(film, path);

  int width = 0, height = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 3);
  REQUIRE(data != nullptr);
  CHECK(width == 5);
  CHECK(height == 4);
  CHECK(channels == 3);
  // Row-major from the top-left.
  CHECK(data[0] == 188);
  CHECK(data[1] == 0);
  CHECK(data[2] == 255);
  const unsigned char* last = data + 3 * (3 * 5 + 4);
  CHECK(last[0] == 255);
  CHECK(last[1] == 0);
  CHECK(last[2] == 10);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c)
        CHECK(data[3 * (y * 5 + x) + c] == glint::linear_to_srgb8(film.at(x, y)[c]));
  stbi_image_free(data);
  CHECK_FALSE(fs::exists(dir.path() / "film.png.glint-partial"));
}

TEST_CASE("writing into a missing directory throws and leaves no file", "[image]") {
  ScratchDirectory dir("missing-dir-test");
  const glint::Film film = test_film(3, 2);
  const fs::path missing = dir.path() / "no" / "such" / "dir";
  CHECK_THROWS_AS(glint::write_png(film, missing / "out.png"), glint::ImageWriteError);
  CHECK_THROWS_AS(glint::write_pfm(film, missing / "out.pfm"), glint::ImageWriteError);
  CHECK_FALSE(fs::exists(missing));
  // Nothing at all was created in the scratch directory.
  CHECK(fs::is_empty(dir.path()));
  // The message names the target.
  try {
    glint::write_png(film, missing / "out.png");
  } catch (const glint::ImageWriteError& e) {
    CHECK(std::string(e.what()).find("out.png") != std::string::npos);
  }
  // Writing over a directory fails too, and leaves the directory alone.
  fs::create_directory(dir.path() / "taken.png");
  CHECK_THROWS_AS(glint::write_png(film, dir.path() / "taken.png"), glint::ImageWriteError);
  CHECK(fs::is_directory(dir.path() / "taken.png"));
  CHECK_FALSE(fs::exists(dir.path() / "taken.png.glint-partial"));
}
