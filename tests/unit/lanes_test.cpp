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
using glint::Vec2Lanes;
using glint::Vec3;
using glint::Vec3Lanes;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

FloatLanes lanes_of(const float (&values)[kLaneCount]) {
  return glint::load_lanes(values);
}

bool same_bits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

}  // namespace

TEST_CASE("lane masks and their bits", "[lanes][unit]") {
  const float a_values[kLaneCount] = {1.0f, -2.0f, kNaN, 3.0f, kNaN, -0.0f, 0.0f, kInf};
  const float b_values[kLaneCount] = {2.0f, -3.0f, 1.0f, kNaN, kNaN, 0.0f, -0.0f, -kInf};
  const FloatLanes a = lanes_of(a_values), b = lanes_of(b_values);
  const IntLanes mask = glint::lanes_of_bits(0b10100101u);
  CHECK(glint::lane_bits(mask) == 0b10100101u);
  const FloatLanes chosen = glint::select(mask, a, b);
  for (int i = 0; i < kLaneCount; ++i)
    CHECK(same_bits(chosen[i], ((0b10100101u >> i) & 1u) ? a_values[i] : b_values[i]));
  CHECK(glint::lane_bits(a < b) == 0b00000001u);
  CHECK(glint::lane_bits(a != a) == 0b00010100u);
}

TEST_CASE("load_columns turns eight rows of eight floats, anywhere in memory, into columns",
          "[lanes][unit]") {
  // Rows scattered through a larger array, in no order and one of them twice, with NaN, -0
  // and infinity among the values, which a transpose must carry bit for bit.
  std::vector<float> memory(200);
  for (std::size_t k = 0; k < memory.size(); ++k)
    memory[k] = float(k) + 0.25f;
  memory[21] = kNaN;
  memory[42] = -0.0f;
  memory[99] = -kInf;
  const std::size_t starts[kLaneCount] = {40, 3, 120, 17, 40, 77, 91, 150};
  const float* rows[kLaneCount];
  for (int i = 0; i < kLaneCount; ++i)
    rows[i] = memory.data() + starts[i];
  FloatLanes columns[kLaneCount];
  glint::load_columns(rows, columns);
  for (int j = 0; j < kLaneCount; ++j)
    for (int i = 0; i < kLaneCount; ++i) {
      INFO("column " << j << ", lane " << i);
      CHECK(same_bits(columns[j][i], memory[starts[i] + std::size_t(j)]));
    }
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

TEST_CASE("Uint64Lanes gives each lane's low and high 32 bits", "[lanes][unit]") {
  glint::Pcg32 rng(3, 5);
  for (int round = 0; round < 1000; ++round) {
    glint::Uint64Lanes v = glint::Uint64Lanes::broadcast(0);
    std::uint64_t expected[kLaneCount];
    for (int i = 0; i < kLaneCount; ++i) {
      expected[i] = std::uint64_t(rng.next_u32()) << 32 | rng.next_u32();
      v.set_lane(i, expected[i]);
    }
    const glint::UintLanes low = v.low_bits(), high = v.high_bits();
    for (int i = 0; i < kLaneCount; ++i) {
      CHECK(low[i] == std::uint32_t(expected[i]));
      CHECK(high[i] == std::uint32_t(expected[i] >> 32));
    }
  }
}

TEST_CASE("a tile's samples are placed in SIMD lanes as one by one, at every quotient's edges",
          "[lanes][unit]") {
  // The lanes divide in floating point: the quotients that matter are those of the largest
  // tiles and passes, of divisors that are not powers of two, and of the samples on either
  // side of a multiple (the first and last sample of a pixel, the first and last pixel of a
  // row).
  glint::Pcg32 rng(2025, 8);
  const auto pick = [&](std::uint32_t count, std::uint32_t edge) {
    switch (rng.next_u32() % 4) {
      case 0:
        return std::uint32_t{0};
      case 1:
        return count - 1;
      case 2:
        return std::min(edge, count - 1);
      default:
        return rng.next_u32() % count;
    }
  };
  constexpr std::uint32_t kLimit = 1u << 20;  // tile pixels, and samples of a pass
  for (int trial = 0; trial < 20000; ++trial) {
    const std::uint32_t per_pixel = 1 + pick(kLimit, 1 + rng.next_u32() % 40);
    const int width = int(1 + pick(1024, 1 + rng.next_u32() % 40));
    const int height = int(1 + pick(kLimit / std::uint32_t(width), 1));
    const int x0 = int(rng.next_u32() % 32768), y0 = int(rng.next_u32() % 32768);
    const glint::detail::PieceLayout piece{
        {x0, y0, x0 + width, y0 + height}, int(rng.next_u32() % kLimit), per_pixel};
    std::uint64_t n[kLaneCount];
    for (std::uint64_t& sample : n) {
      // A pixel at a row's start or end, a sample at a pixel's start or end, or anywhere.
      const std::uint32_t row = pick(std::uint32_t(height), 1);
      const std::uint32_t column = pick(std::uint32_t(width), 1);
      sample = std::uint64_t{row * std::uint32_t(width) + column} * per_pixel + pick(per_pixel, 1);
    }
    glint::PixelSampleLanes lanes;
    piece.lanes(n, lanes);
    for (int i = 0; i < kLaneCount; ++i) {
      INFO("trial " << trial << ": sample " << n[i] << " of " << per_pixel << " per pixel, "
                    << width << "x" << height << " tile, lane " << i);
      CHECK(lanes.x[i] == std::uint32_t(piece.x(n[i])));
      CHECK(lanes.y[i] == std::uint32_t(piece.y(n[i])));
      CHECK(lanes.index[i] == piece.index(n[i]));
    }
  }
}

#endif  // GLINT_AVX2
