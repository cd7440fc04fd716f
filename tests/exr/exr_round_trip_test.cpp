// EXR output read back with the same library (OpenEXR): float32 bit for bit, float16 within
// half precision with values beyond the largest half clamped and counted, the attributes with
// their types, odd sizes, and files written through glint's staged writer.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "exr_test_support.hpp"
#include "glint/error.hpp"
#include "glint/exr/exr_image.hpp"

using namespace glint;
using exr_test::bits;
using exr_test::film_of;
using exr_test::same_bits;
using exr_test::varied_film;

namespace {

ExrImage round_trip(const Film& film, const ExrWriteOptions& options = {}) {
  const ExrEncoded encoded = encode_exr(film, options);
  return decode_exr(encoded.bytes.data(), encoded.bytes.size(), "memory.exr");
}

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kFloatMax = std::numeric_limits<float>::max();

}  // namespace

TEST_CASE("EXR float32: ordinary, tiny, zero and large values read back bit for bit", "[exr]") {
  const std::vector<float> ordinary = {0.18f, 1.0f, 0.5f, 3.25f, 1e-3f, 123.456f, 0.1f, -2.5f};
  const std::vector<float> tiny = {1e-30f, 1e-40f, std::numeric_limits<float>::min(),
                                   std::numeric_limits<float>::denorm_min()};  // 1e-40: subnormal
  const std::vector<float> zeros = {0.0f, -0.0f};
  const std::vector<float> large = {65504.0f, 65520.0f, 1e6f, 3e38f, kFloatMax};
  const std::vector<float> special = {kInf, -kInf, kNaN, 1.0f / 3.0f};
  std::vector<float> values;
  for (const auto* group : {&ordinary, &tiny, &zeros, &large, &special})
    values.insert(values.end(), group->begin(), group->end());
  const Film film = film_of(4, 6, values);  // 72 channel values: each of the 23 at least thrice
  const ExrEncoded encoded = encode_exr(film);
  CHECK(encoded.clamped_values == 0);
  const ExrImage back = decode_exr(encoded.bytes.data(), encoded.bytes.size(), "memory.exr");
  CHECK(back.pixel_type == ExrPixelType::float32);
  CHECK(back.film.width() == 4);
  CHECK(back.film.height() == 6);
  CHECK(same_bits(back.film, film));
  CHECK(back.attributes.empty());
}

TEST_CASE("EXR float32: odd sizes keep every pixel in place", "[exr]") {
  for (const auto& [width, height] : {std::pair{1, 1}, {3, 7}, {7, 3}, {1, 33}, {257, 2}}) {
    CAPTURE(width, height);
    const Film film = varied_film(width, height);
    const ExrImage back = round_trip(film);
    CHECK(same_bits(back.film, film));
  }
}

TEST_CASE("EXR float32: a rendered-size film, and the same bytes every time", "[exr]") {
  const Film film = varied_film(160, 96);
  const ExrEncoded first = encode_exr(film);
  const ExrEncoded second = encode_exr(film);
  CHECK(first.bytes == second.bytes);
  CHECK(same_bits(round_trip(film).film, film));
}

TEST_CASE("EXR float16: values within half precision", "[exr]") {
  // Normal halves, 2^-14 to 65504: relative error at most 2^-11 (round to nearest, 11
  // significant bits).
  // Binary exponents -27 to 14: subnormal halves, those below them, and normal ones.
  Film film = varied_film(41, 17, -27, 14);
  std::vector<float> extra = {0.0f,      -0.0f,    1.0f,  0.5f,    65504.0f,
                              -65504.0f, 0x1p-14f, 1e-4f, 2047.0f, 2049.0f};
  for (std::size_t i = 0; i < extra.size(); ++i)
    film.at(int(i), 0) = Color(extra[i], -extra[i], extra[i] * 0.75f);
  const ExrEncoded encoded = encode_exr(film, {ExrPixelType::float16, {}});
  CHECK(encoded.clamped_values == 0);
  // Half the size of float32's (ZIP sizes vary, but not by a factor of 1.5).
  CHECK(encoded.bytes.size() * 3 < encode_exr(film).bytes.size() * 2);
  const ExrImage back = decode_exr(encoded.bytes.data(), encoded.bytes.size(), "memory.exr");
  CHECK(back.pixel_type == ExrPixelType::float16);
  REQUIRE(back.film.width() == film.width());
  REQUIRE(back.film.height() == film.height());
  int normal = 0, below = 0;
  for (std::size_t i = 0; i < film.pixels().size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const float original = film.pixels()[i][c], read = back.film.pixels()[i][c];
      CAPTURE(i, c, original, read);
      if (std::fabs(original) >= 0x1p-14f) {
        ++normal;
        REQUIRE(std::fabs(read - original) <= 0x1p-11f * std::fabs(original));
      } else {
        // Subnormal halves: steps of 2^-24, so at most half a step off.
        ++below;
        REQUIRE(std::fabs(read - original) <= 0x1p-25f);
      }
    }
  }
  CHECK(normal > 1000);
  CHECK(below > 100);
  // Exactly representable values stay exact.
  CHECK(back.film.at(2, 0).x == 1.0f);
  CHECK(back.film.at(4, 0).x == 65504.0f);
  CHECK(back.film.at(8, 0).x == 2047.0f);
  CHECK(bits(back.film.at(1, 0).x) == bits(-0.0f));
}

TEST_CASE("EXR float16: beyond the largest half is written as the largest half, and counted",
          "[exr]") {
  const Film film = film_of(3, 3,
                            {65504.0f, 65505.0f, 65519.0f, 65520.0f, 1e6f, kFloatMax, kInf, -1e6f,
                             -kInf, kNaN, 1.0f, -65504.0f, 70000.0f, 2.0f, 3.0f});
  const ExrEncoded encoded = encode_exr(film, {ExrPixelType::float16, {}});
  // The 27 values are the 15 above, then their first 12 again. Beyond 65504: 65505, 65519,
  // 65520, 1e6, FLT_MAX, inf, -1e6, -inf and 70000 (9), then the first eight of those again.
  CHECK(encoded.clamped_values == 9 + 8);
  const ExrImage back = decode_exr(encoded.bytes.data(), encoded.bytes.size(), "memory.exr");
  for (std::size_t i = 0; i < film.pixels().size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const float original = film.pixels()[i][c], read = back.film.pixels()[i][c];
      CAPTURE(i, c, original, read);
      if (std::isnan(original))
        CHECK(std::isnan(read));
      else if (std::fabs(original) >= 65504.0f)
        CHECK(read == std::copysign(65504.0f, original));
      else
        CHECK(read == original);
    }
  }
  // float32 keeps them all.
  CHECK(encode_exr(film).clamped_values == 0);
  CHECK(same_bits(round_trip(film).film, film));
}

TEST_CASE("EXR attributes: written with their types and read back", "[exr]") {
  const std::vector<ExrAttribute> attributes = {
      {"comments", std::string("glint-render 0.1.0 (default): tiny.scene")},
      {"glint/variant", std::string("default")},
      {"glint/seed", std::string("18446744073709551615")},
      {"glint/width", 3},
      {"glint/negative", -42},
      {"glint/samplesPerPixel", 1 << 20},
      {"glint/renderSeconds", 1234.000000125},
      {"glint/sigma", 0.35f},
      {"glint/empty", std::string()},
      {"glint/utf8", std::string("sc\xc3\xa8ne \xe2\x98\x80")},
      {"owner", std::string("someone")},
      {"utcOffset", -3600.0f},
      {"A long attribute name past the 31 bytes of old readers", 7},
  };
  for (const ExrPixelType type : {ExrPixelType::float32, ExrPixelType::float16}) {
    const ExrImage back = round_trip(varied_film(3, 7), {type, attributes});
    // Read back in name order, and nothing else: the file's structural attributes are not
    // reported.
    std::vector<ExrAttribute> sorted = attributes;
    std::sort(sorted.begin(), sorted.end(),
              [](const ExrAttribute& a, const ExrAttribute& b) { return a.name < b.name; });
    REQUIRE(back.attributes.size() == sorted.size());
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      CAPTURE(sorted[i].name);
      CHECK(back.attributes[i] == sorted[i]);
    }
    REQUIRE(back.find("glint/seed"));
    CHECK(std::get<std::string>(back.find("glint/seed")->value) == "18446744073709551615");
    REQUIRE(back.find("glint/renderSeconds"));
    CHECK(std::get<double>(back.find("glint/renderSeconds")->value) == 1234.000000125);
    CHECK(back.find("channels") == nullptr);
    CHECK(back.find("no such attribute") == nullptr);
  }
}

TEST_CASE("EXR attributes that would break the file are refused", "[exr]") {
  const Film film = varied_film(2, 2);
  const auto refused = [&](std::vector<ExrAttribute> attributes, const std::string& why) {
    CAPTURE(why);
    CHECK_THROWS_AS(encode_exr(film, {ExrPixelType::float32, attributes}), ImageWriteError);
    CHECK_THROWS_WITH(encode_exr(film, {ExrPixelType::float32, attributes}), Catch::Contains(why));
  };
  refused({{"", 1}}, "the name is empty");
  refused({{std::string(256, 'a'), 1}}, "longer than 255 bytes");
  refused({{std::string("a\0b", 3), 1}}, "holds a NUL");
  for (const char* name : {"channels", "compression", "dataWindow", "displayWindow", "lineOrder",
                           "pixelAspectRatio", "screenWindowCenter", "screenWindowWidth", "tiles",
                           "type", "name", "version", "chunkCount"})
    refused({{name, std::string("x")}}, "one of the file's structure");
  refused({{"glint/seed", 1}, {"glint/seed", 2}}, "given twice");
  refused({{"glint/seed", 1}, {"glint/seed", std::string("2")}}, "given twice");
  refused({{"comments", 1}}, "standard attribute of that name is a string");
  refused({{"utcOffset", 1.0}}, "standard attribute of that name is a float");
  // The message names the attribute.
  CHECK_THROWS_WITH(encode_exr(film, {ExrPixelType::float32, {{"comments", 2.0f}}}),
                    Catch::StartsWith("EXR attribute 'comments': "));
}

TEST_CASE("EXR: an empty film is refused", "[exr]") {
  CHECK_THROWS_AS(encode_exr(Film()), ImageWriteError);
  CHECK_THROWS_WITH(encode_exr(Film(0, 5)), Catch::Contains("empty 0x5 image"));
}

TEST_CASE("write_exr writes the file in place, read_exr reads it back", "[exr]") {
  const exr_test::ScratchDirectory scratch("write");
  const Film film = varied_film(9, 5);
  const std::filesystem::path path = scratch.path() / "out.exr";
  CHECK(write_exr(film, path, {ExrPixelType::float32, {{"glint/threads", 2}}}) == 0);
  const ExrImage back = read_exr(path);
  CHECK(same_bits(back.film, film));
  REQUIRE(back.attributes.size() == 1);
  CHECK(back.attributes[0] == ExrAttribute{"glint/threads", 2});

  // Half, over an existing file, with the clamped values counted.
  CHECK(write_exr(film_of(2, 1, {1e9f, 1.0f}), path, {ExrPixelType::float16, {}}) == 3);
  CHECK(read_exr(path).film.at(0, 0) == Color(65504.0f, 1.0f, 65504.0f));

  // Nothing is left behind by a failed write, and the message names the file.
  const std::filesystem::path missing = scratch.path() / "no-such-dir" / "out.exr";
  CHECK_THROWS_AS(write_exr(film, missing), ImageWriteError);
  CHECK_THROWS_WITH(write_exr(film, missing), Catch::Contains(missing.string()));
  CHECK_THROWS_WITH(write_exr(Film(), path), Catch::StartsWith("cannot write " + path.string()));
  CHECK(std::distance(std::filesystem::directory_iterator(scratch.path()),
                      std::filesystem::directory_iterator()) == 1);
}
