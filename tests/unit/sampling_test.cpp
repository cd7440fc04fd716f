// Random numbers and sample warps: PCG32 against the reference implementation's published
// output, uniformity and independence of the floats and hashes, and the hemisphere, normal and
// frame constructions against their densities.

#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "glint/math/random.hpp"
#include "glint/math/sampling.hpp"
#include "glint/policy/diffuse_sampling.hpp"
#include "glint/policy/sampler.hpp"
#include "statistics.hpp"

using glint::Vec2;
using glint::Vec3;

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

double azimuth01(const Vec3& d) {
  const double phi = std::atan2(double(d.y), double(d.x));
  return (phi < 0.0 ? phi + kTwoPi : phi) / kTwoPi;
}

}  // namespace

TEST_CASE("Pcg32 reproduces the reference pcg32_srandom_r / pcg32_random_r output", "[random]") {
  // pcg32-demo from pcg-c-basic: pcg32_srandom_r(&rng, 42u, 54u), then pcg32_random_r.
  glint::Pcg32 rng(42u, 54u);
  const std::uint32_t expected[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u,
                                    0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
  for (const std::uint32_t value : expected)
    CHECK(rng.next_u32() == value);
  // The generator is usable at compile time.
  STATIC_REQUIRE(glint::Pcg32(42u, 54u).next_u32() == 0xa15c02b7u);
  // reseed restarts the same sequence.
  rng.reseed(42u, 54u);
  CHECK(rng.next_u32() == 0xa15c02b7u);
  // Another stream gives another sequence from the same seed.
  glint::Pcg32 other(42u, 55u);
  CHECK(other.next_u32() != 0xa15c02b7u);
}

TEST_CASE("Pcg32::next_float is uniform, 0 <= u < 1", "[random][statistical]") {
  CHECK(glint::bits_to_unit_float(0u) == 0.0f);
  CHECK(glint::bits_to_unit_float(0xffffffffu) == 1.0f - 0x1p-24f);
  glint::Pcg32 rng(2024u, 1u);
  const int n = 1 << 20;
  std::vector<double> values(n);
  float lo = 1.0f, hi = 0.0f;
  for (double& v : values) {
    const float f = rng.next_float();
    lo = std::min(lo, f);
    hi = std::max(hi, f);
    v = f;
  }
  CHECK(lo >= 0.0f);
  CHECK(hi < 1.0f);
  const int bins = 256;
  CHECK(glint::test::chi_square_equiprobable(values, bins, [](double x) { return x; }) <
        glint::test::chi_square_threshold(bins - 1));
  // Successive values are independent: pairs fall uniformly on a 16 x 16 grid.
  std::vector<double> pairs;
  for (std::size_t i = 0; i + 1 < values.size(); i += 2)
    pairs.push_back((std::floor(values[i] * 16.0) + values[i + 1]) / 16.0);
  CHECK(glint::test::chi_square_equiprobable(pairs, bins, [](double x) { return x; }) <
        glint::test::chi_square_threshold(bins - 1));
}

TEST_CASE("hash_values is deterministic and well mixed", "[random]") {
  // Worked out apart from glint (Python, from the definition: boost's hash_combine step with
  // MurmurHash3's 64-bit finaliser, seeded with the golden-ratio constant).
  STATIC_REQUIRE(glint::hash_values(1u, 2u, 3u) == 0x3c5c554c9fef36e1ULL);
  STATIC_REQUIRE(glint::mix_bits(0u) == 0u);
  CHECK(glint::hash_values(1u, 2u, 3u) != glint::hash_values(3u, 2u, 1u));
  CHECK(glint::hash_values(1u, 2u, 3u) != glint::hash_values(1u, 2u, 4u));
  CHECK(glint::hash_values(0u) != glint::hash_values(0u, 0u));

  SECTION("one flipped input bit flips half of the output bits") {
    glint::Pcg32 rng(5u, 5u);
    double total = 0.0;
    int trials = 0;
    for (int i = 0; i < 2000; ++i) {
      const std::uint64_t v = (std::uint64_t(rng.next_u32()) << 32) | rng.next_u32();
      for (int bit = 0; bit < 64; ++bit) {
        total += std::popcount(glint::mix_bits(v) ^ glint::mix_bits(v ^ (1ull << bit)));
        ++trials;
      }
    }
    // Binomial(64, 1/2) per trial: mean 32, standard deviation 4.
    CHECK(std::abs(total / trials - 32.0) < glint::test::kTailZ * 4.0 / std::sqrt(trials));
  }
  SECTION("neighbouring pixels get independent sampler streams") {
    // The first value of IndependentSampler over a 256 x 256 block of pixels is uniform.
    std::vector<double> first;
    for (std::uint32_t y = 0; y < 256; ++y) {
      for (std::uint32_t x = 0; x < 256; ++x) {
        glint::IndependentSampler sampler;
        sampler.start(glint::PixelSample{x, y, 0, 1, 7});
        first.push_back(sampler.next_1d());
      }
    }
    CHECK(glint::test::chi_square_equiprobable(first, 128, [](double v) { return v; }) <
          glint::test::chi_square_threshold(127));
  }
  SECTION("IndependentSampler depends only on the pixel sample") {
    glint::IndependentSampler a, b;
    a.start({3, 4, 5, 16, 99});
    b.start({9, 9, 9, 16, 1});
    (void)b.next_2d();
    b.start({3, 4, 5, 16, 99});
    for (int i = 0; i < 8; ++i)
      CHECK(a.next_1d() == b.next_1d());
    a.start({3, 4, 5, 16, 100});  // another seed
    b.start({3, 4, 5, 16, 99});
    CHECK(a.next_1d() != b.next_1d());
  }
}

namespace {

struct HemisphereSamples {
  std::vector<double> cos_theta, phi01;
  std::vector<Vec3> directions;
};

template <typename Warp>
HemisphereSamples draw_hemisphere(Warp warp, int n, std::uint64_t seed) {
  glint::Pcg32 rng(seed, 3u);
  HemisphereSamples s;
  for (int i = 0; i < n; ++i) {
    const float u = rng.next_float();
    const Vec3 d = warp(Vec2(u, rng.next_float()));
    s.directions.push_back(d);
    s.cos_theta.push_back(d.z);
    s.phi01.push_back(azimuth01(d));
  }
  return s;
}

void check_on_hemisphere(const HemisphereSamples& s) {
  int bad_length = 0, below = 0;
  for (const Vec3& d : s.directions) {
    if (std::abs(glm::length(d) - 1.0f) > 1e-5f) ++bad_length;
    if (d.z < 0.0f) ++below;
  }
  CHECK(bad_length == 0);
  CHECK(below == 0);
}

}  // namespace

TEST_CASE("uniform hemisphere: cos(theta) uniform, phi uniform, pdf 1/(2 pi)",
          "[sampling][statistical]") {
  const int n = 1 << 18;
  const HemisphereSamples s = draw_hemisphere(glint::sample_uniform_hemisphere<glint::Vec2>, n, 17);
  check_on_hemisphere(s);
  // Uniform on the hemisphere: dω = d(cos θ) dφ, so cos θ ~ U[0,1] and φ ~ U[0,2π).
  const int bins = 64;
  const double threshold = glint::test::chi_square_threshold(bins - 1);
  CHECK(glint::test::chi_square_equiprobable(s.cos_theta, bins, [](double c) { return c; }) <
        threshold);
  CHECK(glint::test::chi_square_equiprobable(s.phi01, bins, [](double p) { return p; }) <
        threshold);
  // Jointly: (cos θ, φ) uniform on a 16 x 16 grid.
  std::vector<double> joint;
  for (int i = 0; i < n; ++i)
    joint.push_back((std::floor(s.cos_theta[i] * 16.0) + s.phi01[i]) / 16.0);
  CHECK(glint::test::chi_square_equiprobable(joint, 256, [](double v) { return v; }) <
        glint::test::chi_square_threshold(255));
  CHECK(glint::kUniformHemispherePdf == Approx(1.0 / kTwoPi).epsilon(1e-7));
}

TEST_CASE("cosine hemisphere: cos(theta) has density 2 cos, phi uniform",
          "[sampling][statistical]") {
  const int n = 1 << 18;
  const HemisphereSamples s = draw_hemisphere(glint::sample_cosine_hemisphere<glint::Vec2>, n, 23);
  check_on_hemisphere(s);
  // pdf(ω) = cos θ / π, so cos θ has density 2 cos θ on [0, 1]: CDF cos²θ.
  const int bins = 64;
  const double threshold = glint::test::chi_square_threshold(bins - 1);
  CHECK(glint::test::chi_square_equiprobable(s.cos_theta, bins, [](double c) { return c * c; }) <
        threshold);
  CHECK(glint::test::chi_square_equiprobable(s.phi01, bins, [](double p) { return p; }) <
        threshold);
  // The uniform-hemisphere samples must fail this test: the test can tell them apart.
  const HemisphereSamples uniform =
      draw_hemisphere(glint::sample_uniform_hemisphere<glint::Vec2>, n, 23);
  CHECK(glint::test::chi_square_equiprobable(uniform.cos_theta, bins,
                                             [](double c) { return c * c; }) > 100.0 * threshold);
}

TEMPLATE_TEST_CASE("diffuse sampling policies: weight = cos / pdf, and they integrate cos to pi",
                   "[sampling][statistical]", glint::UniformHemisphere, glint::CosineHemisphere) {
  glint::Pcg32 rng(31u, 7u);
  const int n = 1 << 18;
  double sum = 0.0, sum2 = 0.0, cos2_over_pdf = 0.0, cos2_over_pdf2 = 0.0;
  int inconsistent = 0;
  for (int i = 0; i < n; ++i) {
    const float u = rng.next_float();
    const glint::DirectionSample s = TestType::sample(Vec2(u, rng.next_float()));
    const float cos_theta = s.local_direction.z;
    const float pdf = TestType::pdf(cos_theta);
    if (cos_theta > 1e-3f && std::abs(s.weight - cos_theta / pdf) > 1e-5f * s.weight)
      ++inconsistent;
    sum += s.weight;
    sum2 += double(s.weight) * s.weight;
    // An estimator that uses pdf() alone: E[cos² / pdf] = ∫ cos² dω = 2π/3.
    const double g = pdf > 0.0f ? double(cos_theta) * cos_theta / pdf : 0.0;
    cos2_over_pdf += g;
    cos2_over_pdf2 += g * g;
  }
  CHECK(inconsistent == 0);
  // ∫ cos θ dω over the hemisphere = π; tolerance from the sample's own standard error (plus a
  // float-accumulation slack, for the zero-variance cosine estimator).
  const double mean = sum / n;
  const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  CHECK(std::abs(mean - M_PI) <= glint::test::kTailZ * se + 1e-6);
  const double mean2 = cos2_over_pdf / n;
  const double se2 = std::sqrt(std::max(0.0, cos2_over_pdf2 / n - mean2 * mean2) / n);
  CHECK(std::abs(mean2 - kTwoPi / 3.0) <= glint::test::kTailZ * se2 + 1e-6);
}

TEST_CASE("Box-Muller pairs are independent standard normals", "[sampling][statistical]") {
  // Extreme inputs stay finite: u.x = 0 gives radius 0, the largest u.x below 1 gives
  // sqrt(2 * 24 ln 2) ~ 5.77.
  CHECK(glint::sample_standard_normal_pair(Vec2(0.0f, 0.3f)) == Vec2(0.0f));
  const Vec2 extreme = glint::sample_standard_normal_pair(Vec2(1.0f - 0x1p-24f, 0.0f));
  CHECK(extreme.x == Approx(std::sqrt(48.0 * std::log(2.0))).epsilon(1e-4));

  glint::Pcg32 rng(77u, 2u);
  const int pairs = 1 << 17;
  std::vector<double> first, second, all;
  double cross = 0.0;
  for (int i = 0; i < pairs; ++i) {
    const float u = rng.next_float();
    const Vec2 z = glint::sample_standard_normal_pair(Vec2(u, rng.next_float()));
    first.push_back(z.x);
    second.push_back(z.y);
    all.push_back(z.x);
    all.push_back(z.y);
    cross += double(z.x) * z.y;
  }
  const double n = double(all.size());
  const glint::test::Moments m = glint::test::moments(all);
  CHECK(std::abs(m.mean) <= glint::test::kTailZ / std::sqrt(n));
  CHECK(std::abs(m.variance - 1.0) <= glint::test::kTailZ * std::sqrt(2.0 / n));
  // Uncorrelated within a pair (the correlation estimate has standard deviation 1/sqrt(pairs)).
  CHECK(std::abs(cross / pairs) <= glint::test::kTailZ / std::sqrt(double(pairs)));
  const auto cdf = [](double x) { return glint::test::standard_normal_cdf(x); };
  for (const auto* values : {&first, &second, &all}) {
    CHECK(glint::test::kolmogorov_smirnov(*values, cdf) <
          glint::test::kolmogorov_smirnov_threshold(values->size()));
  }
  // The KS test detects a 5% error in the standard deviation at this sample size.
  std::vector<double> wide = all;
  for (double& v : wide)
    v *= 1.05;
  CHECK(glint::test::kolmogorov_smirnov(wide, cdf) >
        glint::test::kolmogorov_smirnov_threshold(wide.size()));
}

TEST_CASE("Frame::around is a right-handed orthonormal basis", "[sampling]") {
  std::vector<Vec3> normals = {{0, 0, 1},
                               {0, 0, -1},
                               {1, 0, 0},
                               {-1, 0, 0},
                               {0, 1, 0},
                               {0, -1, 0},
                               glm::normalize(Vec3(1e-4f, 0, -1)),
                               glm::normalize(Vec3(0, 1e-7f, -1)),
                               glm::normalize(Vec3(1, 1, 1))};
  glint::Pcg32 rng(8u, 8u);
  for (int i = 0; i < 10000; ++i) {
    const float z = 2.0f * rng.next_float() - 1.0f;
    const float phi = 2.0f * glint::kPi * rng.next_float();
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    normals.push_back(glm::normalize(Vec3(r * std::cos(phi), r * std::sin(phi), z)));
  }
  for (const Vec3& n : normals) {
    const glint::Frame f = glint::Frame::around(n);
    INFO("normal (" << n.x << ", " << n.y << ", " << n.z << ")");
    CHECK(std::abs(glm::length(f.tangent) - 1.0f) < 1e-5f);
    CHECK(std::abs(glm::length(f.bitangent) - 1.0f) < 1e-5f);
    CHECK(std::abs(glm::dot(f.tangent, f.bitangent)) < 1e-5f);
    CHECK(std::abs(glm::dot(f.tangent, n)) < 1e-5f);
    CHECK(std::abs(glm::dot(f.bitangent, n)) < 1e-5f);
    CHECK(glm::length(glm::cross(f.tangent, f.bitangent) - n) < 1e-5f);
    CHECK(glm::length(f.to_world(Vec3(0, 0, 1)) - n) < 1e-6f);
    // A local direction keeps its angle to the normal.
    const Vec3 local = glm::normalize(Vec3(0.3f, -0.4f, 0.5f));
    CHECK(glm::dot(f.to_world(local), n) == Approx(local.z).margin(1e-5));
  }
}
