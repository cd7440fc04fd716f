// Image comparison (RMSE, the per-pixel relative squared error) against numbers worked out by
// hand on a 2x2 image, and the false-colour ramp of glint-compare's error maps.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "../support/float_values.hpp"
#include "glint/image/compare.hpp"
#include "glint/image/false_color.hpp"
#include "glint/io/image_writer.hpp"
#include "stb_image.h"

namespace {

using glint_test::kInf;
using glint_test::kNaN;

// Reference (row by row): grey 1, black, grey 2, grey 0.5. The test image differs by 0.25 in
// every channel of the black pixel and by -1 in the red channel of the grey-2 pixel. Every
// value is exact in float, so the sums are exact too.
glint::Film reference_2x2() {
  glint::Film film(2, 2);
  film.at(0, 0) = glint::Color(1.0f);
  film.at(1, 0) = glint::Color(0.0f);
  film.at(0, 1) = glint::Color(2.0f);
  film.at(1, 1) = glint::Color(0.5f);
  return film;
}
glint::Film test_2x2() {
  glint::Film film = reference_2x2();
  film.at(1, 0) = glint::Color(0.25f);
  film.at(0, 1) = glint::Color(1.0f, 2.0f, 2.0f);
  return film;
}

// Relative luminance of an sRGB-encoded colour (IEC 61966-2-1, Rec. 709 weights).
double luminance(const glint::Rgb8& c) {
  const auto linear = [](std::uint8_t v) {
    const double x = v / 255.0;
    return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * linear(c.r) + 0.7152 * linear(c.g) + 0.0722 * linear(c.b);
}

}  // namespace

TEST_CASE("compare_images: RMSE and relative RMSE of a 2x2 image", "[compare]") {
  const glint::ImageComparison result = glint::compare_images(test_2x2(), reference_2x2());
  // Squared errors: 3 * 0.25^2 + 1^2 = 1.1875 over 12 values.
  CHECK(result.rmse == Approx(std::sqrt(1.1875 / 12.0)).epsilon(1e-12));
  // Reference sum: 3 * (1 + 0 + 2 + 0.5) = 10.5 over 12 values.
  CHECK(result.mean_reference == Approx(0.875).epsilon(1e-12));
  CHECK(result.relative_rmse() == Approx(std::sqrt(1.1875 / 12.0) / 0.875).epsilon(1e-12));
  CHECK(result.non_finite == 0);
}

TEST_CASE("compare_images: identical images, a black reference, non-finite values", "[compare]") {
  const glint::ImageComparison same = glint::compare_images(reference_2x2(), reference_2x2());
  CHECK(same.rmse == 0.0);

  const glint::Film black(2, 2);
  const glint::ImageComparison against_black = glint::compare_images(test_2x2(), black);
  CHECK(against_black.mean_reference == 0.0);
  CHECK(std::isnan(against_black.relative_rmse()));  // no relative error, not infinity

  glint::Film with_nan = test_2x2();
  with_nan.at(0, 0) = glint::Color(kNaN, 1.0f, kInf);
  const glint::ImageComparison counted = glint::compare_images(with_nan, reference_2x2());
  CHECK(counted.non_finite == 2);
  // Left out of the sums, still counted in the mean's denominator: the other values' error is
  // the same as before.
  CHECK(counted.rmse == Approx(std::sqrt(1.1875 / 12.0)).epsilon(1e-12));
}

TEST_CASE("compare_images and relative_squared_error refuse images of different sizes",
          "[compare]") {
  CHECK_THROWS_AS(glint::compare_images(glint::Film(2, 2), glint::Film(2, 3)),
                  std::invalid_argument);
  CHECK_THROWS_AS(glint::relative_squared_error(glint::Film(3, 2), glint::Film(2, 2)),
                  std::invalid_argument);
}

TEST_CASE("relative_squared_error of a 2x2 image", "[compare]") {
  const std::vector<float> map = glint::relative_squared_error(test_2x2(), reference_2x2());
  REQUIRE(map.size() == 4);
  CHECK(map[0] == 0.0f);
  // Black reference: 0.25^2 / (0 + 0.01) = 6.25 in each channel.
  CHECK(map[1] == Approx(6.25).epsilon(1e-6));
  // Red only: 1 / (4 + 0.01), averaged over three channels.
  CHECK(map[2] == Approx(1.0 / 4.01 / 3.0).epsilon(1e-6));
  CHECK(map[3] == 0.0f);

  // A larger epsilon damps the dark pixel most: 0.0625 / 1 and 1 / 5 / 3.
  const std::vector<float> damped = glint::relative_squared_error(test_2x2(), reference_2x2(), 1.0);
  CHECK(damped[1] == Approx(0.0625).epsilon(1e-6));
  CHECK(damped[2] == Approx(1.0 / 15.0).epsilon(1e-6));
}

TEST_CASE("relative_squared_error marks non-finite pixels with NaN", "[compare]") {
  glint::Film test = test_2x2();
  test.at(0, 0) = glint::Color(1.0f, kNaN, 1.0f);
  test.at(1, 1) = glint::Color(kInf, 0.5f, 0.5f);
  glint::Film reference = reference_2x2();
  reference.at(0, 1) = glint::Color(2.0f, 2.0f, -kInf);
  const std::vector<float> map = glint::relative_squared_error(test, reference);
  CHECK(std::isnan(map[0]));
  CHECK(map[1] == Approx(6.25).epsilon(1e-6));
  CHECK(std::isnan(map[2]));
  CHECK(std::isnan(map[3]));
}

TEST_CASE("error_ramp: its control points, the ends, clamping and NaN", "[false-color]") {
  const auto& stops = glint::kErrorRamp;
  for (std::size_t i = 0; i < stops.size(); ++i)
    CHECK(glint::error_ramp(float(i) / float(stops.size() - 1)) == stops[i]);
  CHECK(glint::error_ramp(-0.5f) == stops.front());
  CHECK(glint::error_ramp(-kInf) == stops.front());
  CHECK(glint::error_ramp(1.5f) == stops.back());
  CHECK(glint::error_ramp(kInf) == stops.back());
  CHECK(glint::error_ramp(kNaN) == stops.back());  // unknown shows as the worst
  // Half way between the first two points.
  const glint::Rgb8 half = glint::error_ramp(0.1f);
  CHECK(half.r == 22);
  CHECK(half.g == 8);
  CHECK(half.b == 48);
}

TEST_CASE("error_ramp: luminance rises from black to near white", "[false-color]") {
  CHECK(luminance(glint::error_ramp(0.0f)) < 0.01);
  CHECK(luminance(glint::error_ramp(1.0f)) > 0.9);
  // Between control points, clearly: a tenth of the ramp apart, every step is brighter.
  for (int i = 0; i < 10; ++i) {
    INFO("t = " << i / 10.0);
    CHECK(luminance(glint::error_ramp(float(i + 1) / 10.0f)) >
          luminance(glint::error_ramp(float(i) / 10.0f)) + 0.005);
  }
  // At fine steps, up to 8-bit rounding: where blue falls while red and green rise, a step
  // can round blue down one code while the others stay, which dims the colour by less than
  // one blue code's luminance (0.0722 * 0.0033 at most in this ramp's range).
  double previous = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    const double y = luminance(glint::error_ramp(float(i) / 1000.0f));
    INFO("t = " << i / 1000.0);
    CHECK(y >= previous - 3e-4);
    previous = std::max(previous, y);
  }
}

TEST_CASE("log_scale_position: decades, the ends, zero, negative and NaN", "[false-color]") {
  CHECK(glint::log_scale_position(1e-4, 1e-4, 1.0) == 0.0f);
  CHECK(glint::log_scale_position(1e-2, 1e-4, 1.0) == Approx(0.5).epsilon(1e-6));
  CHECK(glint::log_scale_position(1e-3, 1e-4, 1.0) == Approx(0.25).epsilon(1e-6));
  CHECK(glint::log_scale_position(1.0, 1e-4, 1.0) == 1.0f);
  CHECK(glint::log_scale_position(50.0, 1e-4, 1.0) == 1.0f);
  CHECK(glint::log_scale_position(1e-9, 1e-4, 1.0) == 0.0f);
  CHECK(glint::log_scale_position(0.0, 1e-4, 1.0) == 0.0f);
  CHECK(glint::log_scale_position(-3.0, 1e-4, 1.0) == 0.0f);
  CHECK(glint::log_scale_position(kInf, 1e-4, 1.0) == 1.0f);
  CHECK(glint::log_scale_position(kNaN, 1e-4, 1.0) == 1.0f);
}

TEST_CASE("false_color_rgb8 through encode_png_rgb8 decodes to the ramp's colours",
          "[false-color]") {
  const std::vector<float> values{0.0f, 1e-2f, 1.0f, kNaN};
  const std::vector<std::uint8_t> rgb = glint::false_color_rgb8(values, 1e-4, 1.0);
  REQUIRE(rgb.size() == 12);
  const std::vector<char> png = glint::encode_png_rgb8(2, 2, rgb);
  int width = 0, height = 0, channels = 0;
  unsigned char* decoded = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                                                 int(png.size()), &width, &height, &channels, 3);
  REQUIRE(decoded != nullptr);
  CHECK(width == 2);
  CHECK(height == 2);
  const std::vector<std::uint8_t> pixels(decoded, decoded + 12);
  stbi_image_free(decoded);
  CHECK(pixels == rgb);
  const glint::Rgb8 middle = glint::error_ramp(0.5f);
  CHECK(glint::Rgb8{pixels[3], pixels[4], pixels[5]} == middle);
  CHECK(glint::Rgb8{pixels[6], pixels[7], pixels[8]} == glint::kErrorRamp.back());
  CHECK(glint::Rgb8{pixels[9], pixels[10], pixels[11]} == glint::kErrorRamp.back());

  CHECK_THROWS_AS(glint::encode_png_rgb8(2, 2, std::vector<std::uint8_t>(11)),
                  glint::ImageWriteError);
}
