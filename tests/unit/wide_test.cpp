// The width-generic vocabulary (math/wide.hpp) and what is written once in it: every formula
// must give the same bits at widths 1, 8 and 16, lane by lane, over grids and random inputs that
// include the edge cases (NaN, signed zeros, infinities, total internal reflection, zero and
// infinite densities), whatever instruction set the compiler targets. The elementary functions
// are also checked against the double-precision library over the ranges the warps use.

#include <array>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "../support/float_values.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/random.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/antialiasing.hpp"
#include "glint/policy/diffuse_sampling.hpp"
#include "glint/policy/fresnel.hpp"
#include "glint/policy/light_sampling.hpp"
#include "glint/policy/path_termination.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/lights/sphere_light.hpp"
#include "glint/scene/emitters.hpp"

namespace {

using glint_test::kInf;
using glint_test::kNaN;
using glint_test::same_bits;

/// Arguments number `Arity` per call; `inputs` holds them call after call.
template <std::size_t Arity>
using Calls = std::vector<std::array<float, Arity>>;

/// The lanes of one argument of calls first .. first + W - 1.
template <int W, std::size_t Arity>
glint::Float<W> argument(const Calls<Arity>& calls, std::size_t first, int k) {
  glint::Float<W> value{};
  for (int lane = 0; lane < W; ++lane)
    glint::set_lane(value, lane, calls[first + std::size_t(lane)][std::size_t(k)]);
  return value;
}

/// Calls `formula` (a generic lambda taking Arity Floats and returning a std::array of Floats)
/// at widths 1, 8 and 16 on every call of `calls` (padded to a multiple of 16), and checks that
/// every output has the same bits at each width as at width 1.
template <std::size_t Arity, typename Formula>
void check_same_bits_at_every_width(Calls<Arity> calls, Formula formula) {
  while (calls.size() % 16 != 0)
    calls.push_back(calls.front());
  const auto run = [&]<int W>(std::size_t first) {
    return [&]<std::size_t... K>(std::index_sequence<K...>) {
      return formula(argument<W, Arity>(calls, first, int(K))...);
    }
    (std::make_index_sequence<Arity>{});
  };
  for (std::size_t first = 0; first < calls.size(); first += 16) {
    const auto wide16 = run.template operator()<16>(first);
    const auto wide8_low = run.template operator()<8>(first);
    const auto wide8_high = run.template operator()<8>(first + 8);
    for (int lane = 0; lane < 16; ++lane) {
      const auto scalar = run.template operator()<1>(first + std::size_t(lane));
      const auto& wide8 = lane < 8 ? wide8_low : wide8_high;
      for (std::size_t out = 0; out < scalar.size(); ++out) {
        const float one = scalar[out];
        const float eight = glint::lane(wide8[out], lane % 8);
        const float sixteen = glint::lane(wide16[out], lane);
        if (same_bits(one, eight) && same_bits(one, sixteen)) continue;
        INFO("arguments of call " << first + std::size_t(lane) << ": "
                                  << calls[first + std::size_t(lane)][0] << " ...; output " << out
                                  << ": width 1 " << one << ", 8 " << eight << ", 16 " << sixteen);
        CHECK(same_bits(one, eight));
        CHECK(same_bits(one, sixteen));
      }
    }
  }
}

/// Uniform pairs in [0, 1)^2, with the ends of the interval first.
Calls<2> uniform_pairs(int count) {
  Calls<2> calls = {{0.0f, 0.0f}, {0x1.fffffep-1f, 0.5f}, {0.5f, 0x1.fffffep-1f}, {0.25f, 0.75f}};
  glint::Pcg32 rng(7, 11);
  while (int(calls.size()) < count)
    calls.push_back({rng.next_float(), rng.next_float()});
  return calls;
}

/// Values that exercise the edge rules: NaN, zeros of both signs, infinities, tiny and huge.
const std::vector<float> kEdges = {0.0f,   -0.0f, 1.0f,  -1.0f, 0.5f,   kNaN,   kInf, -kInf,
                                   1e-30f, 1e30f, -2.0f, 3.0f,  0.999f, 1e-45f, 7.0f, 0.25f};

Calls<2> edge_pairs() {
  Calls<2> calls;
  for (const float a : kEdges)
    for (const float b : kEdges)
      calls.push_back({a, b});
  return calls;
}

}  // namespace

TEST_CASE("wide: sin and cos are within 8e-8 of the library's over [0, 2 pi], and far beyond",
          "[wide][unit]") {
  double worst = 0.0;
  const int steps = 1 << 18;
  for (int k = 0; k <= steps; ++k) {
    const float x = float(2.0 * M_PI * double(k) / steps);
    float s, c;
    glint::sincos(x, s, c);
    worst = std::max(worst, std::abs(double(s) - std::sin(double(x))));
    worst = std::max(worst, std::abs(double(c) - std::cos(double(x))));
  }
  CHECK(worst <= 8e-8);
  for (const float x : {0.0f, float(M_PI / 4), float(M_PI / 2), float(M_PI), float(1.5 * M_PI),
                        float(2 * M_PI), 100.0f, 1000.0f, 60000.0f}) {
    float s, c;
    glint::sincos(x, s, c);
    INFO("x = " << x);
    CHECK(std::abs(double(s) - std::sin(double(x))) <= 1e-6 * std::max(1.0, x / 1000.0));
    CHECK(std::abs(double(c) - std::cos(double(x))) <= 1e-6 * std::max(1.0, x / 1000.0));
  }
  float s, c;
  glint::sincos(0.0f, s, c);
  CHECK(same_bits(s, 0.0f));
  CHECK(same_bits(c, 1.0f));
}

TEST_CASE("wide: log is within 3e-7 of the library's, relative, from 1e-30 to 3e30",
          "[wide][unit]") {
  double worst = 0.0;
  glint::Pcg32 rng(1, 2);
  for (int round = 0; round < 1 << 17; ++round) {
    const int octave = int(rng.next_u32() % 200) - 100;
    const float x = std::ldexp(1.0f - rng.next_float(), octave);
    const double exact = std::log(double(x));
    worst =
        std::max(worst, std::abs(double(glint::log(x)) - exact) / std::max(1.0, std::abs(exact)));
  }
  CHECK(worst <= 3e-7);
  for (const float x : {0.5f, 2.0f, 0x1p-24f, 0.70710677f, 0.70710683f, 1e-30f, 3e30f}) {
    INFO("x = " << x);
    CHECK(double(glint::log(x)) == Approx(std::log(double(x))).epsilon(3e-7).margin(1e-7));
  }
  CHECK(glint::log(1.0f) == 0.0f);
}

TEST_CASE("wide: exponential is within 3e-7 of the library's exp, relative, from -103 to 88",
          "[wide][unit]") {
  double worst = 0.0;
  glint::Pcg32 rng(3, 4);
  for (int round = 0; round < 1 << 17; ++round) {
    const float x = -87.0f + 175.0f * rng.next_float();
    const double exact = std::exp(double(x));
    worst = std::max(worst, std::abs(double(glint::exponential(x)) - exact) / exact);
  }
  CHECK(worst <= 3e-7);
  CHECK(glint::exponential(0.0f) == 1.0f);
  CHECK(double(glint::exponential(-80.0f)) == Approx(std::exp(-80.0)).epsilon(3e-7));
  CHECK(glint::exponential(-104.0f) == 0.0f);
}

TEST_CASE("wide: sin, cos, log and sqrt give the same bits at every width", "[wide][unit]") {
  Calls<1> angles;
  for (int k = 0; k < 4096; ++k)
    angles.push_back({float(k) * (6.2831853f / 4096.0f)});
  for (const float x : {0.78539816f, 1.5707964f, 3.1415927f, 4.712389f, 6.2831855f, 1000.0f})
    angles.push_back({x});
  check_same_bits_at_every_width(angles, [](auto x) {
    decltype(x) s, c;
    glint::sincos(x, s, c);
    return std::array{s, c, glint::sqrt(x)};
  });
  Calls<1> positive;
  glint::Pcg32 rng(3, 4);
  for (int k = 0; k < 4096; ++k)
    positive.push_back({std::ldexp(1.0f - rng.next_float(), int(rng.next_u32() % 120) - 60)});
  check_same_bits_at_every_width(positive, [](auto x) {
    return std::array{glint::log(x), glint::sqrt(x)};
  });
}

TEST_CASE("wide: min, max, abs, copysign and select follow the scalar rules at every width",
          "[wide][unit]") {
  // Width 1 against the standard library's rules, NaN and -0 included...
  for (const auto& [a, b] : edge_pairs()) {
    INFO("a = " << a << ", b = " << b);
    CHECK(same_bits(glint::min(a, b), std::min(a, b)));
    CHECK(same_bits(glint::max(a, b), std::max(a, b)));
    CHECK(same_bits(glint::copysign(b, a), std::copysign(b, a)));
    CHECK(same_bits(glint::abs(a), std::fabs(a)));
  }
  // ...and every width against width 1.
  check_same_bits_at_every_width(edge_pairs(), [](auto a, auto b) {
    return std::array{glint::min(a, b), glint::max(a, b),           glint::copysign(b, a),
                      glint::abs(a),    glint::select(a < b, a, b), glint::select(a != a, b, a)};
  });
  const glint::Float<8> lanes = glint::splat<glint::Float<8>>(1.0f);
  CHECK(glint::all(lanes == 1.0f));
  CHECK(!glint::any(lanes != 1.0f));
  glint::Float<16> one_nan = glint::splat<glint::Float<16>>(2.0f);
  one_nan[13] = kNaN;
  CHECK(glint::any(one_nan != one_nan));
  CHECK(!glint::all(one_nan == one_nan));
}

TEST_CASE("wide: the warps and the frame give the same bits at every width", "[wide][unit]") {
  Calls<3> calls;
  glint::Pcg32 rng(5, 6);
  for (const auto& [u, v] : uniform_pairs(4096))
    calls.push_back({u, v, calls.size() % 7 == 0 ? 1e-7f : 2.0f * rng.next_float()});
  check_same_bits_at_every_width(calls, [](auto u, auto v, auto cone) {
    using F = decltype(u);
    using V2 = glint::Vec2For<F>;
    const auto hemisphere = glint::sample_uniform_hemisphere(V2{u, v});
    const auto cosine = glint::sample_cosine_hemisphere(V2{u, v});
    const auto sphere = glint::sample_uniform_sphere(V2{u, v});
    const auto in_cone = glint::sample_uniform_cone(V2{u, v}, cone);
    const auto normal = glint::sample_standard_normal_pair(V2{u, v});
    const auto world = glint::BasicFrame<glint::Vec3For<F>>::around(sphere).to_world(cosine);
    return std::array{hemisphere.x,
                      hemisphere.y,
                      hemisphere.z,
                      cosine.x,
                      cosine.y,
                      cosine.z,
                      sphere.x,
                      sphere.y,
                      sphere.z,
                      in_cone.x,
                      in_cone.y,
                      in_cone.z,
                      glint::uniform_cone_pdf(cone),
                      normal.x,
                      normal.y,
                      world.x,
                      world.y,
                      world.z};
  });
}

TEMPLATE_TEST_CASE("wide: diffuse sampling gives the same bits at every width", "[wide][unit]",
                   glint::UniformHemisphere, glint::CosineHemisphere) {
  check_same_bits_at_every_width(uniform_pairs(2048), [](auto u, auto v) {
    using V2 = glint::Vec2For<decltype(u)>;
    const auto sample = TestType::sample(V2{u, v});
    const auto cosine = sample.local_direction.z - 0.5f;  // some at or below zero
    return std::array{sample.local_direction.x, sample.local_direction.y, sample.local_direction.z,
                      sample.weight, TestType::pdf(cosine)};
  });
}

TEMPLATE_TEST_CASE("wide: pixel filters give the same bits at every width", "[wide][unit]",
                   glint::NoAntialiasing, glint::GaussianAntialiasing, glint::BoxAntialiasing,
                   glint::TentAntialiasing) {
  check_same_bits_at_every_width(uniform_pairs(4096), [](auto u, auto v) {
    const auto offset = TestType::offset(glint::Vec2For<decltype(u)>{u, v}, 0.7f);
    return std::array{offset.x, offset.y};
  });
}

TEMPLATE_TEST_CASE(
    "wide: Fresnel gives the same bits at every width, total internal "
    "reflection included",
    "[wide][unit]", glint::NoFresnel, glint::ExactFresnel, glint::SchlickFresnel) {
  Calls<3> calls;
  const float etas[][2] = {{1.0f, 1.5f}, {1.5f, 1.0f}, {1.33f, 1.5f}, {2.4f, 1.0f}, {1.0f, 1.0f}};
  for (const auto& eta : etas)
    for (int k = -8; k <= 1032; ++k)
      calls.push_back({float(k) / 1024.0f, eta[0], eta[1]});
  check_same_bits_at_every_width(calls, [](auto cosine, auto eta_i, auto eta_t) {
    return std::array{TestType::reflectance(cosine, eta_i, eta_t)};
  });
}

TEMPLATE_TEST_CASE("wide: MIS weights give the same bits at every width, at every edge",
                   "[wide][unit]", glint::PointLightsOnly, glint::EmitterSamplingOnly<>,
                   glint::EmitterSampling<glint::BalanceHeuristic>,
                   glint::EmitterSampling<glint::PowerHeuristic>) {
  check_same_bits_at_every_width(edge_pairs(), [](auto pdf, auto other) {
    return std::array{TestType::light_weight(pdf, other), TestType::bounce_weight(pdf, other)};
  });
}

TEMPLATE_TEST_CASE("wide: path termination gives the same bits at every width", "[wide][unit]",
                   glint::FixedDepth, glint::RussianRoulette) {
  Calls<2> calls;
  for (int depth = 0; depth < 6; ++depth)
    for (const float throughput : kEdges)
      calls.push_back({float(depth), throughput});
  check_same_bits_at_every_width(calls, [](auto depth, auto throughput) {
    return std::array{TestType::continue_probability(glint::truncate_to_int(depth), throughput)};
  });
}

TEST_CASE("wide: camera rays give the same bits at every width", "[wide][unit]") {
  glint::CameraDescription description;
  description.position = {1.0f, 2.0f, 30.0f};
  description.look_at = {0.0f, -1.0f, 0.0f};
  description.up = {0.0f, 1.0f, 0.0f};
  description.fov_degrees = 50.0f;
  description.near = 0.25f;
  const glint::Camera camera(description, 320, 200);
  Calls<2> calls = {{0.0f, 0.0f}, {320.0f, 200.0f}, {160.0f, 100.0f}, {0.5f, 199.5f}};
  glint::Pcg32 rng(5, 5);
  while (calls.size() < 2048)
    calls.push_back({rng.next_float() * 320.0f, rng.next_float() * 200.0f});
  check_same_bits_at_every_width(calls, [&](auto x, auto y) {
    using F = decltype(x);
    glint::Vec3For<F> direction;
    F t_min;
    camera.rays_through(glint::Vec2For<F>{x, y}, direction, t_min);
    return std::array{direction.x, direction.y, direction.z, t_min};
  });
}

TEST_CASE(
    "wide: emitter sampling gives the same bits at every width, from outside, inside and "
    "on the surface",
    "[wide][unit]") {
  // Arguments: the point (three), the radius, the view (0 outside, 1 inside, 2 none) and u;
  // the emitter's centre is (1, -2, 3), the points inside it where the view says so.
  Calls<7> calls;
  glint::Pcg32 rng(8, 9);
  for (int k = 0; k < 3072; ++k) {
    const float radius = k % 5 == 0 ? 1e-3f : 0.5f + 4.0f * rng.next_float();
    const float distance = k % 3 == 0 ? radius * 0.5f : radius * (1.0f + 100.0f * rng.next_float());
    const glint::Vec3 direction =
        glint::sample_uniform_sphere(glint::Vec2(rng.next_float(), rng.next_float()));
    const float view = k % 3 == 0 ? 1.0f : (k % 17 == 0 ? 2.0f : 0.0f);
    calls.push_back({1.0f + direction.x * distance, -2.0f + direction.y * distance,
                     3.0f + direction.z * distance, radius, view, rng.next_float(),
                     rng.next_float()});
  }
  check_same_bits_at_every_width(
      calls, [](auto x, auto y, auto z, auto radius, auto view, auto u, auto v) {
        using F = decltype(x);
        using V3 = glint::Vec3For<F>;
        const glint::BasicSphereLight<F> light(
            glint::splat_vector<V3>(glint::Vec3(1.0f, -2.0f, 3.0f)), radius,
            glint::splat_vector<V3>(glint::Vec3(1.0f)), glint::splat<glint::UIntFor<F>>(0u));
        const auto sample =
            light.sample_li(V3{x, y, z}, view == 0.0f, view == 2.0f, glint::Vec2For<F>{u, v});
        const F valid = glint::select(sample.valid, glint::splat<F>(1.0f), glint::splat<F>(0.0f));
        return std::array{sample.direction.x, sample.direction.y, sample.direction.z, sample.pdf,
                          valid};
      });
}
