// Tone mapping: each operator's values worked out by hand, exposure as a power of two, order
// kept over the whole float range, no NaN from any input, and the default mapping giving the
// bytes of the plain sRGB encoding that glint wrote before tone mapping existed.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "../support/float_values.hpp"
#include "glint/image/tone_map.hpp"
#include "glint/io/image_writer.hpp"

namespace {

using glint_test::kInf;
using glint_test::kNaN;

constexpr glint::ToneMapOperator kOperators[] = {
    glint::ToneMapOperator::clip, glint::ToneMapOperator::reinhard, glint::ToneMapOperator::aces};

/// Every 4099th float bit pattern from 0 to +inf: a monotone walk over all magnitudes,
/// denormals and the largest floats included.
std::vector<float> increasing_floats() {
  std::vector<float> values;
  const std::uint32_t infinity_bits = 0x7f800000u;
  for (std::uint64_t bits = 0; bits <= infinity_bits; bits += 4099) {
    float value;
    const auto word = static_cast<std::uint32_t>(bits);
    std::memcpy(&value, &word, sizeof value);
    values.push_back(value);
  }
  values.push_back(kInf);
  return values;
}

}  // namespace

TEST_CASE("tone mapping: each operator's values at 0, 1 and large radiance", "[image][tonemap]") {
  using glint::tone_map;
  using glint::ToneMapOperator;
  for (const ToneMapOperator op : kOperators) {
    INFO(glint::name_of(op));
    CHECK(tone_map(0.0f, op) == 0.0f);
    CHECK(tone_map(kInf, op) == 1.0f);
    CHECK(tone_map(std::numeric_limits<float>::max(), op) == 1.0f);
  }
  // clip: the identity up to 1.
  CHECK(tone_map(0.25f, ToneMapOperator::clip) == 0.25f);
  CHECK(tone_map(1.0f, ToneMapOperator::clip) == 1.0f);
  CHECK(tone_map(1000.0f, ToneMapOperator::clip) == 1.0f);
  // reinhard: x / (1 + x), so 1 -> 1/2, 3 -> 3/4, 1e6 -> 1 - 1e-6.
  CHECK(tone_map(1.0f, ToneMapOperator::reinhard) == 0.5f);
  CHECK(tone_map(3.0f, ToneMapOperator::reinhard) == 0.75f);
  CHECK(tone_map(1e6f, ToneMapOperator::reinhard) == Approx(1.0 - 1e-6).epsilon(1e-7));
  CHECK(tone_map(1e-3f, ToneMapOperator::reinhard) == Approx(1e-3 / 1.001).epsilon(1e-6));
  // aces: x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14): 1 -> 2.54 / 3.16; slope 0.03 / 0.14
  // near 0; it reaches 1 at (0.56 + sqrt(0.56^2 + 4 * 0.08 * 0.14)) / 0.16 = 7.2418.
  CHECK(tone_map(1.0f, ToneMapOperator::aces) == Approx(2.54 / 3.16).epsilon(1e-6));
  CHECK(tone_map(1e-4f, ToneMapOperator::aces) / 1e-4f == Approx(0.03 / 0.14).epsilon(1e-2));
  CHECK(tone_map(7.2f, ToneMapOperator::aces) < 1.0f);
  CHECK(tone_map(7.3f, ToneMapOperator::aces) == 1.0f);
  CHECK(tone_map(100.0f, ToneMapOperator::aces) == 1.0f);
}

TEST_CASE("tone mapping: exposure +1 doubles the radiance, -1 halves it", "[image][tonemap]") {
  for (const glint::ToneMapOperator op : kOperators) {
    INFO(glint::name_of(op));
    for (const float x : {1e-6f, 0.01f, 0.3f, 0.5f, 1.0f, 2.5f, 40.0f}) {
      CHECK(glint::ToneMapping{op, 1.0f}(x) == glint::tone_map(2.0f * x, op));
      CHECK(glint::ToneMapping{op, -1.0f}(x) == glint::tone_map(0.5f * x, op));
      CHECK(glint::ToneMapping{op, 3.0f}(x) == glint::tone_map(8.0f * x, op));
      CHECK(glint::ToneMapping{op, 0.0f}(x) == glint::tone_map(x, op));
    }
  }
  CHECK(glint::ToneMapping{glint::ToneMapOperator::clip, 0.5f}(0.5f) ==
        Approx(0.5 * std::sqrt(2.0)).epsilon(1e-6));
}

TEST_CASE("tone mapping: non-decreasing over every float, in [0, 1], never NaN",
          "[image][tonemap]") {
  const std::vector<float> values = increasing_floats();
  for (const glint::ToneMapOperator op : kOperators) {
    for (const float exposure :
         {-glint::limits::max_exposure, -3.0f, 0.0f, 2.0f, glint::limits::max_exposure}) {
      INFO(glint::name_of(op) << " at exposure " << exposure);
      const glint::ToneMapping mapping{op, exposure};
      float previous = 0.0f;
      bool ordered = true, in_range = true;
      for (const float x : values) {
        const float y = mapping(x);
        ordered = ordered && y >= previous;
        in_range = in_range && y >= 0.0f && y <= 1.0f;  // false for NaN too
        previous = y;
      }
      CHECK(ordered);
      CHECK(in_range);
      for (const float bad : {kNaN, -kNaN, -kInf, -1.0f, -0.0f, -1e-40f})
        CHECK(mapping(bad) == 0.0f);
    }
  }
}

TEST_CASE("tone mapping: operator names parse back, and nothing else parses", "[tonemap]") {
  for (const auto& [name, op] : glint::kToneMapOperators) {
    CHECK(glint::name_of(op) == name);
    CHECK(glint::parse_tone_map_operator(name) == op);
  }
  CHECK_FALSE(glint::parse_tone_map_operator("Reinhard"));
  CHECK_FALSE(glint::parse_tone_map_operator(""));
  CHECK_FALSE(glint::parse_tone_map_operator("filmic"));
  CHECK(glint::tone_map_operator_list() == "clip, reinhard or aces");
}

TEST_CASE("tone mapping: the default mapping writes the plain sRGB bytes", "[image][tonemap]") {
  // What glint wrote before tone mapping existed: the sRGB code of each channel as it is.
  const std::vector<float> values = increasing_floats();
  glint::Film film(int(values.size()), 1);
  for (std::size_t i = 0; i < values.size(); ++i)
    film.at(int(i), 0) = glint::Color(values[i], -values[i], i % 7 == 0 ? kNaN : 0.5f);
  const std::vector<std::uint8_t> bytes = glint::to_srgb8(film);
  REQUIRE(bytes.size() == values.size() * 3);
  bool same = true;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const glint::Color& c = film.at(int(i), 0);
    same = same && bytes[3 * i] == glint::linear_to_srgb8(c.x) &&
           bytes[3 * i + 1] == glint::linear_to_srgb8(c.y) &&
           bytes[3 * i + 2] == glint::linear_to_srgb8(c.z);
  }
  CHECK(same);
  // And another mapping changes them: reinhard shows 1.0 as the sRGB code of 0.5.
  glint::Film one(1, 1);
  one.at(0, 0) = glint::Color(1.0f);
  const std::vector<std::uint8_t> mapped =
      glint::to_srgb8(one, {glint::ToneMapOperator::reinhard, 0.0f});
  CHECK(mapped[0] == glint::linear_to_srgb8(0.5f));
  CHECK(mapped[0] == 188);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354, times 255
}

TEST_CASE("tone mapping: exposure text parses to stops within the limit, nothing else does",
          "[tonemap]") {
  CHECK(glint::parse_exposure("1.5") == 1.5f);
  CHECK(glint::parse_exposure("-64") == -glint::limits::max_exposure);
  CHECK(glint::parse_exposure("64") == glint::limits::max_exposure);
  CHECK(glint::parse_exposure("0") == 0.0f);
  for (const char* bad : {"65", "-64.5", "nan", "inf", "-inf", "1x", "", " 1", "1e3"})
    CHECK_FALSE(glint::parse_exposure(bad));
  CHECK(glint::exposure_range_text() == "stops from -64 to 64");
}
