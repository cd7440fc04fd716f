// What AVX2 adds to the eight-lane width for the wavefront renderer (math/lanes.hpp): masks as
// bits, transposes, the packing of lanes into queues, 64-bit lanes, a tile's samples in lanes.
// What is written once for every width is checked in wide_test.cpp, and the samplers' lane-wise
// forms in wide_sampler_test.cpp.

#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "../support/float_values.hpp"
#include "glint/math/lanes.hpp"
#include "glint/math/random.hpp"
#include "glint/math/sampling.hpp"
#include "glint/policy/antialiasing.hpp"
#include "glint/policy/diffuse_sampling.hpp"
#include "glint/policy/fresnel.hpp"
#include "glint/policy/light_sampling.hpp"
#include "glint/policy/path_termination.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/wavefront/wavefront_execution.hpp"

// The lane-wise code exists only where the compiler targets AVX2 (see math/lanes.hpp).
#if defined(GLINT_AVX2)

using glint::FloatLanes;
using glint::IntLanes;
using glint::kLaneCount;
using glint::Vec2;
using glint::Vec3;
using glint::Vec3Lanes;

namespace {

using glint_test::kInf;
using glint_test::kNaN;
using glint_test::same_bits;

FloatLanes lanes_of(const float (&values)[kLaneCount]) {
  return glint::load<FloatLanes>(values);
}

}  // namespace

TEST_CASE("lane masks and their bits", "[lanes][unit]") {
  const float a_values[kLaneCount] = {1.0f, -2.0f, kNaN, 3.0f, kNaN, -0.0f, 0.0f, kInf};
  const float b_values[kLaneCount] = {2.0f, -3.0f, 1.0f, kNaN, kNaN, 0.0f, -0.0f, -kInf};
  const FloatLanes a = lanes_of(a_values), b = lanes_of(b_values);
  const IntLanes mask = glint::mask_of_bits<IntLanes>(0b10100101u);
  CHECK(glint::bits_of_mask(mask) == 0b10100101u);
  const FloatLanes chosen = glint::select(mask, a, b);
  for (int i = 0; i < kLaneCount; ++i)
    CHECK(same_bits(chosen[i], ((0b10100101u >> i) & 1u) ? a_values[i] : b_values[i]));
  CHECK(glint::bits_of_mask(a < b) == 0b00000001u);
  CHECK(glint::bits_of_mask(a != a) == 0b00010100u);
}

namespace {

/// load_columns on rows that start at `starts` in an array of 400 floats with NaN, -0 and
/// infinity among the values, which a transpose must carry bit for bit: column j must hold
/// row i's float j in lane i.
template <std::size_t kRows>
void check_load_columns(const std::size_t (&starts)[kRows]) {
  std::vector<float> memory(400);
  for (std::size_t k = 0; k < memory.size(); ++k)
    memory[k] = float(k) + 0.25f;
  memory[21] = kNaN;
  memory[42] = -0.0f;
  memory[399] = -kInf;
  const float* rows[kRows];
  for (std::size_t i = 0; i < kRows; ++i)
    rows[i] = memory.data() + starts[i];
  glint::Float<int(kRows)> columns[kLaneCount];
  glint::load_columns(rows, columns);
  for (int j = 0; j < kLaneCount; ++j)
    for (std::size_t i = 0; i < kRows; ++i) {
      INFO("column " << j << ", lane " << i);
      CHECK(same_bits(columns[j][i], memory[starts[i] + std::size_t(j)]));
    }
}

}  // namespace

TEST_CASE("load_columns turns eight rows of eight floats, anywhere in memory, into columns",
          "[lanes][unit]") {
  // Rows scattered through the array, in no order and one of them twice.
  check_load_columns<kLaneCount>({40, 3, 120, 17, 40, 77, 91, 392});
#if defined(GLINT_AVX512)
  // Sixteen rows, those of the two halves of a register from unrelated places, so that a
  // piece taken from the wrong half or the wrong row shows.
  check_load_columns<2 * kLaneCount>(
      {40, 3, 120, 17, 40, 77, 91, 150, 215, 300, 8, 392, 181, 260, 14, 121});
#endif
}

TEST_CASE(
    "packing_order and rotated_order move the lanes of a mask, in order, where a queue "
    "continues",
    "[lanes][unit]") {
  const IntLanes values = glint::lane_indices() * 10 + 3;
  for (std::uint32_t mask = 0; mask < 256; ++mask) {
    std::vector<int> chosen;  // the lanes of the mask, lowest first
    for (int lane = 0; lane < kLaneCount; ++lane)
      if ((mask >> lane) & 1u) chosen.push_back(lane);
    const IntLanes packed = glint::permute(values, glint::packing_order(mask));
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      INFO("mask " << mask << ", entry " << k);
      CHECK(packed[k] == chosen[k] * 10 + 3);
    }
    for (int at = 0; at < kLaneCount; ++at) {
      const IntLanes appended =
          glint::permute(values, glint::rotated_order(glint::packing_order(mask), at));
      for (std::size_t k = 0; k < chosen.size(); ++k) {
        INFO("mask " << mask << ", at " << at << ", entry " << k);
        CHECK(appended[(std::size_t(at) + k) % kLaneCount] == chosen[k] * 10 + 3);
      }
    }
  }
  // Floats move bit for bit.
  const float float_values[kLaneCount] = {kNaN, -0.0f, 1.5f, kInf, -kInf, 0.0f, 2.0f, -3.0f};
  const FloatLanes moved =
      glint::permute(lanes_of(float_values), glint::packing_order(0b11110000u));
  for (int k = 0; k < 4; ++k)
    CHECK(same_bits(moved[k], float_values[k + 4]));
}

#endif  // GLINT_AVX2
