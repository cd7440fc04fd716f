// The eight-lane arithmetic of the wavefront renderer's shading (math/lanes.hpp) and the
// lane-wise forms of the warps and policies: sin and cos against the double-precision library
// over the warps' angles, the NaN and signed-zero rules of min, max, copysign and select, and
// each lane-wise warp or policy against its scalar form, lane by lane, over grids and random
// inputs that include the edge cases (total internal reflection, zero and infinite densities,
// NaN throughput).

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
#include "glint/policy/sampler.hpp"
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

/// Eight uniform pairs from a generator.
Vec2Lanes uniform_pairs(glint::Pcg32& rng, Vec2 (&pairs)[kLaneCount]) {
  Vec2Lanes u{};
  for (int i = 0; i < kLaneCount; ++i) {
    pairs[i] = {rng.next_float(), rng.next_float()};
    u.x[i] = pairs[i].x;
    u.y[i] = pairs[i].y;
  }
  return u;
}

bool same_bits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

void check_close(const Vec3& lane, const Vec3& scalar, float tolerance) {
  for (int c = 0; c < 3; ++c) {
    INFO("component " << c << ": lanes " << lane[c] << ", scalar " << scalar[c]);
    CHECK(std::abs(lane[c] - scalar[c]) <= tolerance);
  }
}

}  // namespace

TEST_CASE("sincos_lanes is within 2e-7 of sin and cos from 0 to 2 pi, and close beyond",
          "[lanes][unit]") {
  double worst = 0.0;
  const int steps = 1 << 16;
  for (int k = 0; k <= steps; k += kLaneCount) {
    FloatLanes x{};
    for (int i = 0; i < kLaneCount; ++i)
      x[i] = float(2.0 * M_PI * double(k + i) / steps);
    FloatLanes s, c;
    glint::sincos_lanes(x, s, c);
    for (int i = 0; i < kLaneCount; ++i) {
      worst = std::max(worst, std::abs(double(s[i]) - std::sin(double(x[i]))));
      worst = std::max(worst, std::abs(double(c[i]) - std::cos(double(x[i]))));
    }
  }
  CHECK(worst <= 2e-7);
  // The quadrant boundaries exactly, and larger angles.
  const float edges[kLaneCount] = {
      0.0f,   float(M_PI / 4), float(M_PI / 2), float(M_PI), float(1.5 * M_PI), float(2 * M_PI),
      100.0f, 1000.0f};
  FloatLanes s, c;
  glint::sincos_lanes(lanes_of(edges), s, c);
  for (int i = 0; i < kLaneCount; ++i) {
    INFO("x = " << edges[i]);
    CHECK(std::abs(double(s[i]) - std::sin(double(edges[i]))) <= 1e-6);
    CHECK(std::abs(double(c[i]) - std::cos(double(edges[i]))) <= 1e-6);
  }
  CHECK(same_bits(s[0], 0.0f));
  CHECK(same_bits(c[0], 1.0f));
}

TEST_CASE("lane min, max, select and copysign follow the scalar rules, NaN and -0 included",
          "[lanes][unit]") {
  const float a_values[kLaneCount] = {1.0f, -2.0f, kNaN, 3.0f, kNaN, -0.0f, 0.0f, kInf};
  const float b_values[kLaneCount] = {2.0f, -3.0f, 1.0f, kNaN, kNaN, 0.0f, -0.0f, -kInf};
  const FloatLanes a = lanes_of(a_values), b = lanes_of(b_values);
  const FloatLanes low = glint::min_lanes(a, b), high = glint::max_lanes(a, b);
  const FloatLanes sign = glint::copysign_lanes(b, a);
  const FloatLanes magnitude = glint::abs_lanes(a);
  for (int i = 0; i < kLaneCount; ++i) {
    INFO("a = " << a_values[i] << ", b = " << b_values[i]);
    CHECK(same_bits(low[i], std::min(a_values[i], b_values[i])));
    CHECK(same_bits(high[i], std::max(a_values[i], b_values[i])));
    CHECK(same_bits(sign[i], std::copysign(b_values[i], a_values[i])));
    CHECK(same_bits(magnitude[i], std::fabs(a_values[i])));
  }
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

TEST_CASE("lane-wise warps and frames agree with the scalar ones", "[lanes][unit]") {
  glint::Pcg32 rng(7, 11);
  for (int round = 0; round < 4096; ++round) {
    Vec2 pairs[kLaneCount];
    const Vec2Lanes u = uniform_pairs(rng, pairs);
    FloatLanes cone{};
    for (int i = 0; i < kLaneCount; ++i)
      cone[i] = i == 0 ? 1e-7f : (i == 1 ? 2.0f : rng.next_float() * 2.0f);
    const Vec3Lanes uniform = glint::sample_uniform_hemisphere_lanes(u);
    const Vec3Lanes cosine = glint::sample_cosine_hemisphere_lanes(u);
    const Vec3Lanes sphere = glint::sample_uniform_sphere_lanes(u);
    const Vec3Lanes in_cone = glint::sample_uniform_cone_lanes(u, cone);
    const FloatLanes cone_pdf = glint::uniform_cone_pdf_lanes(cone);
    const glint::FrameLanes frame = glint::FrameLanes::around(sphere);
    const Vec3Lanes world = frame.to_world(cosine);
    for (int i = 0; i < kLaneCount; ++i) {
      check_close(uniform.lane(i), glint::sample_uniform_hemisphere(pairs[i]), 1e-6f);
      check_close(cosine.lane(i), glint::sample_cosine_hemisphere(pairs[i]), 1e-6f);
      check_close(sphere.lane(i), glint::sample_uniform_sphere(pairs[i]), 1e-6f);
      check_close(in_cone.lane(i), glint::sample_uniform_cone(pairs[i], cone[i]), 1e-6f);
      CHECK(cone_pdf[i] == Approx(glint::uniform_cone_pdf(cone[i])).epsilon(1e-6));
      const glint::Frame scalar_frame = glint::Frame::around(sphere.lane(i));
      check_close(world.lane(i), scalar_frame.to_world(cosine.lane(i)), 2e-6f);
    }
  }
}

TEMPLATE_TEST_CASE("lane-wise diffuse sampling agrees with the scalar policy", "[lanes][unit]",
                   glint::UniformHemisphere, glint::CosineHemisphere) {
  glint::Pcg32 rng(3, 5);
  for (int round = 0; round < 1024; ++round) {
    Vec2 pairs[kLaneCount];
    const glint::DirectionSampleLanes lanes = TestType::sample(uniform_pairs(rng, pairs));
    const FloatLanes cosines = lanes.local_direction.z - 0.5f;  // some at or below zero
    const FloatLanes pdf = TestType::pdf(cosines);
    for (int i = 0; i < kLaneCount; ++i) {
      const glint::DirectionSample scalar = TestType::sample(pairs[i]);
      check_close(lanes.local_direction.lane(i), scalar.local_direction, 1e-6f);
      CHECK(lanes.weight[i] == Approx(scalar.weight).epsilon(1e-5).margin(1e-6));
      CHECK(pdf[i] == Approx(TestType::pdf(cosines[i])).epsilon(1e-6));
    }
  }
}

TEMPLATE_TEST_CASE(
    "lane-wise Fresnel agrees with the scalar policy, total internal reflection "
    "included",
    "[lanes][unit]", glint::NoFresnel, glint::ExactFresnel, glint::SchlickFresnel) {
  const float etas[][2] = {{1.0f, 1.5f}, {1.5f, 1.0f}, {1.33f, 1.5f}, {2.4f, 1.0f}, {1.0f, 1.0f}};
  for (const auto& eta : etas)
    for (int k = 0; k <= 1024; k += kLaneCount) {
      FloatLanes cosine{};
      for (int i = 0; i < kLaneCount; ++i)
        cosine[i] = float(k + i) / 1024.0f;
      const FloatLanes lanes =
          TestType::reflectance(cosine, glint::broadcast(eta[0]), glint::broadcast(eta[1]));
      for (int i = 0; i < kLaneCount; ++i) {
        INFO("cos " << cosine[i] << ", eta " << eta[0] << " / " << eta[1]);
        CHECK(lanes[i] ==
              Approx(TestType::reflectance(cosine[i], eta[0], eta[1])).margin(2e-6).epsilon(1e-5));
      }
    }
}

TEMPLATE_TEST_CASE("lane-wise MIS weights agree with the scalar heuristics at every edge",
                   "[lanes][unit]", glint::BalanceHeuristic, glint::PowerHeuristic) {
  const float pdfs[kLaneCount] = {0.0f, -1.0f, kNaN, kInf, 1e-30f, 0.5f, 3.0f, 1e30f};
  const float others[] = {0.0f, 1e-30f, 0.5f, 3.0f, 1e30f, kInf, kNaN, 1.0f};
  for (float other : others) {
    const FloatLanes lanes = TestType::weight(lanes_of(pdfs), glint::broadcast(other));
    for (int i = 0; i < kLaneCount; ++i) {
      const float scalar = TestType::weight(pdfs[i], other);
      INFO("pdf " << pdfs[i] << ", other " << other << ": scalar " << scalar);
      if (std::isnan(scalar))
        CHECK(std::isnan(lanes[i]));
      else
        CHECK(lanes[i] == Approx(scalar).epsilon(1e-6));
    }
  }
  using Sampling = glint::EmitterSampling<TestType>;
  CHECK(Sampling::light_weight(glint::broadcast(2.0f), glint::broadcast(1.0f))[3] ==
        Approx(Sampling::light_weight(2.0f, 1.0f)));
}

TEMPLATE_TEST_CASE("lane-wise path termination agrees with the scalar policy", "[lanes][unit]",
                   glint::FixedDepth, glint::RussianRoulette) {
  const float throughputs[kLaneCount] = {0.0f, 0.25f, 0.999f, 1.0f, 7.0f, kNaN, kInf, 1e-30f};
  for (int depth = 0; depth < 6; ++depth) {
    const FloatLanes lanes =
        TestType::continue_probability(glint::broadcast(depth), lanes_of(throughputs));
    for (int i = 0; i < kLaneCount; ++i)
      CHECK(same_bits(lanes[i], TestType::continue_probability(depth, throughputs[i])));
  }
}

TEST_CASE("log_lanes is within 3e-7 of log, relative, from 1e-30 to 3e30", "[lanes][unit]") {
  double worst = 0.0;
  glint::Pcg32 rng(1, 2);
  for (int round = 0; round < 1 << 14; ++round) {
    FloatLanes x{};
    for (int i = 0; i < kLaneCount; ++i)
      x[i] = i == 0 ? 1.0f - rng.next_float() : std::ldexp(1.0f - rng.next_float(), i * 9 - 30);
    const FloatLanes y = glint::log_lanes(x);
    for (int i = 0; i < kLaneCount; ++i) {
      const double exact = std::log(double(x[i]));
      worst = std::max(worst, std::abs(double(y[i]) - exact) / std::max(1.0, std::abs(exact)));
    }
  }
  CHECK(worst <= 3e-7);
  const float edges[kLaneCount] = {1.0f,        0.5f,        2.0f,   0x1p-24f,
                                   0.70710677f, 0.70710683f, 1e-30f, 3e30f};
  const FloatLanes y = glint::log_lanes(lanes_of(edges));
  for (int i = 0; i < kLaneCount; ++i) {
    INFO("x = " << edges[i]);
    CHECK(double(y[i]) == Approx(std::log(double(edges[i]))).epsilon(3e-7).margin(1e-7));
  }
  CHECK(y[0] == 0.0f);
}

TEMPLATE_TEST_CASE("lane-wise pixel filter offsets agree with the scalar policy", "[lanes][unit]",
                   glint::NoAntialiasing, glint::GaussianAntialiasing, glint::BoxAntialiasing,
                   glint::TentAntialiasing) {
  glint::Pcg32 rng(9, 4);
  for (int round = 0; round < 4096; ++round) {
    Vec2 pairs[kLaneCount];
    Vec2Lanes u = uniform_pairs(rng, pairs);
    if (round == 0) {  // the ends of [0, 1)
      for (int i = 0; i < kLaneCount; ++i) {
        pairs[i] = {i < 4 ? 0.0f : 0x1.fffffep-1f, (i & 1) ? 0.5f : 0.0f};
        u.x[i] = pairs[i].x;
        u.y[i] = pairs[i].y;
      }
    }
    const Vec2Lanes lanes = TestType::offset(u, 0.7f);
    for (int i = 0; i < kLaneCount; ++i) {
      const Vec2 scalar = TestType::offset(pairs[i], 0.7f);
      INFO("u = " << pairs[i].x << ", " << pairs[i].y);
      CHECK(lanes.x[i] == Approx(scalar.x).epsilon(1e-5).margin(1e-6));
      CHECK(lanes.y[i] == Approx(scalar.y).epsilon(1e-5).margin(1e-6));
    }
  }
}

TEST_CASE("Camera::rays_through agrees with ray_through", "[lanes][unit]") {
  glint::CameraDescription description;
  description.position = {1.0f, 2.0f, 30.0f};
  description.look_at = {0.0f, -1.0f, 0.0f};
  description.up = {0.0f, 1.0f, 0.0f};
  description.fov_degrees = 50.0f;
  description.near = 0.25f;
  const glint::Camera camera(description, 320, 200);
  glint::Pcg32 rng(5, 5);
  for (int round = 0; round < 1024; ++round) {
    Vec2Lanes film{};
    for (int i = 0; i < kLaneCount; ++i) {
      film.x[i] = rng.next_float() * 320.0f;
      film.y[i] = rng.next_float() * 200.0f;
    }
    Vec3Lanes direction;
    FloatLanes t_min;
    camera.rays_through(film, direction, t_min);
    for (int i = 0; i < kLaneCount; ++i) {
      const glint::Ray ray = camera.ray_through({film.x[i], film.y[i]});
      check_close(direction.lane(i), ray.direction, 1e-6f);
      CHECK(t_min[i] == Approx(ray.t_min).epsilon(1e-6));
    }
  }
  CHECK(camera.position() == description.position);
}

TEMPLATE_TEST_CASE("a sampler's Lanes form draws bit for bit what the sampler draws, lane by lane",
                   "[lanes][unit]", glint::IndependentSampler, glint::SobolSampler,
                   glint::HybridSobolSampler<>, glint::HybridSobolSampler<6>) {
  // Eight samplers at different pixels and sample indices; each round draws a 1D or a 2D value
  // for a random subset of lanes, as the wavefront's stages do; the lanes left out must keep
  // their state, so that their next draws still match.
  glint::Pcg32 rng(2024, 12);
  for (int trial = 0; trial < 64; ++trial) {
    TestType scalar[kLaneCount];
    typename TestType::Lanes lanes;
    for (int i = 0; i < kLaneCount; ++i) {
      scalar[i].start(glint::PixelSample{rng.next_u32() % 4096, rng.next_u32() % 4096,
                                         rng.next_u32() % 1024, 1024, rng.next_u32()});
      lanes.set_lane(i, scalar[i]);
    }
    for (int round = 0; round < 40; ++round) {
      const std::uint32_t bits = rng.next_u32() & 0xffu;
      const IntLanes mask = glint::lanes_of_bits(bits);
      const bool two = (rng.next_u32() & 1u) != 0;
      const Vec2Lanes drawn = two ? lanes.next_2d(mask) : Vec2Lanes{lanes.next_1d(mask), {}};
      for (int i = 0; i < kLaneCount; ++i) {
        if (!((bits >> i) & 1u)) continue;
        INFO("trial " << trial << ", round " << round << ", lane " << i);
        if (two) {
          const Vec2 u = scalar[i].next_2d();
          CHECK(same_bits(drawn.x[i], u.x));
          CHECK(same_bits(drawn.y[i], u.y));
        } else {
          CHECK(same_bits(drawn.x[i], scalar[i].next_1d()));
        }
      }
    }
    // Stored back, each lane continues as its sampler does.
    for (int i = 0; i < kLaneCount; ++i) {
      TestType stored;
      lanes.get_lane(i, stored);
      CHECK(same_bits(stored.next_1d(), scalar[i].next_1d()));
    }
  }
}

namespace {

/// Any 32-bit value, the ends of the range and small values included.
std::uint32_t any_word(glint::Pcg32& rng) {
  switch (rng.next_u32() % 8) {
    case 0:
      return 0;
    case 1:
      return ~std::uint32_t{0};
    case 2:
      return rng.next_u32() % 64;
    default:
      return rng.next_u32();
  }
}

}  // namespace

TEMPLATE_TEST_CASE("a sampler's Lanes form starts the lanes of a mask as the sampler starts",
                   "[lanes][unit]", glint::IndependentSampler, glint::SobolSampler,
                   glint::HybridSobolSampler<>, glint::HybridSobolSampler<6>) {
  // The wavefront's camera stage starts the lanes of a block's mask, while the other lanes'
  // paths are under way: every mask, from samplers that have drawn a while, at pixels, sample
  // indices and seeds anywhere in their ranges.
  glint::Pcg32 rng(2025, 7);
  for (int trial = 0; trial < 16; ++trial) {
    TestType before[kLaneCount];
    typename TestType::Lanes under_way;
    for (int i = 0; i < kLaneCount; ++i) {
      before[i].start(
          glint::PixelSample{rng.next_u32(), rng.next_u32(), rng.next_u32(), 16, rng.next_u32()});
      for (std::uint32_t draws = rng.next_u32() % 12; draws > 0; --draws)
        before[i].next_1d();
      under_way.set_lane(i, before[i]);
    }
    for (std::uint32_t bits = 0; bits < 256; ++bits) {
      INFO("trial " << trial << ", lanes " << bits);
      glint::PixelSampleLanes sample;
      sample.samples_per_pixel = 1 + rng.next_u32() % 1024;
      sample.seed = (std::uint64_t{any_word(rng)} << 32) | any_word(rng);
      TestType scalar[kLaneCount];
      typename TestType::Lanes expected = under_way;
      for (int i = 0; i < kLaneCount; ++i) {
        sample.x[i] = any_word(rng);
        sample.y[i] = any_word(rng);
        sample.index[i] = any_word(rng);
        scalar[i] = before[i];
        if (!((bits >> i) & 1u)) continue;
        scalar[i].start(glint::PixelSample{sample.x[i], sample.y[i], sample.index[i],
                                           sample.samples_per_pixel, sample.seed});
        expected.set_lane(i, scalar[i]);
      }
      typename TestType::Lanes lanes = under_way;
      lanes.start(glint::lanes_of_bits(bits), sample);
      // The Lanes forms are vectors only, without padding: the same state is the same bytes.
      CHECK(std::memcmp(&lanes, &expected, sizeof lanes) == 0);
      // Every lane then draws what its sampler draws: the started ones and the others.
      const IntLanes all = glint::lanes_of_bits(0xffu);
      for (int round = 0; round < 10; ++round) {
        const bool two = round % 3 == 1;
        const Vec2Lanes drawn = two ? lanes.next_2d(all) : Vec2Lanes{lanes.next_1d(all), {}};
        for (int i = 0; i < kLaneCount; ++i) {
          INFO("round " << round << ", lane " << i);
          if (two) {
            const Vec2 u = scalar[i].next_2d();
            CHECK(same_bits(drawn.x[i], u.x));
            CHECK(same_bits(drawn.y[i], u.y));
          } else {
            CHECK(same_bits(drawn.x[i], scalar[i].next_1d()));
          }
        }
      }
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
