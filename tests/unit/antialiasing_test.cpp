// Antialiasing policies: the distribution of the primary-ray offset each one produces.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "glint/math/random.hpp"
#include "glint/policy/antialiasing.hpp"
#include "statistics.hpp"

using glint::Vec2;

namespace {

constexpr int kSamples = 1 << 17;

template <typename Policy>
void draw_offsets(float sigma, std::uint64_t seed, std::vector<double>& xs,
                  std::vector<double>& ys) {
  glint::Pcg32 rng(seed, 9u);
  for (int i = 0; i < kSamples; ++i) {
    const float u = rng.next_float();
    const Vec2 offset = Policy::offset(Vec2(u, rng.next_float()), sigma);
    xs.push_back(offset.x);
    ys.push_back(offset.y);
  }
}

}  // namespace

TEST_CASE("NoAntialiasing: every ray through the pixel centre", "[antialiasing]") {
  STATIC_REQUIRE_FALSE(glint::NoAntialiasing::enabled);
  for (const float u : {0.0f, 0.25f, 0.999f})
    for (const float sigma : {0.0f, 0.5f, 3.0f})
      CHECK(glint::NoAntialiasing::offset(Vec2(u, 1.0f - u), sigma) == Vec2(0.0f));
}

TEST_CASE("GaussianAntialiasing: mean 0 and standard deviation sigma per axis",
          "[antialiasing][statistical]") {
  STATIC_REQUIRE(glint::GaussianAntialiasing::enabled);
  CHECK(glint::GaussianAntialiasing::offset(Vec2(0.7f, 0.2f), 0.0f) == Vec2(0.0f));
  for (const float sigma : {0.25f, 0.5f, 2.0f}) {
    std::vector<double> xs, ys;
    draw_offsets<glint::GaussianAntialiasing>(sigma, 40 + std::uint64_t(sigma * 4), xs, ys);
    const double n = kSamples;
    for (const auto* axis : {&xs, &ys}) {
      const glint::test::Moments m = glint::test::moments(*axis);
      INFO("sigma " << sigma);
      // Standard errors: sigma / sqrt(n) for the mean, sigma^2 sqrt(2 / n) for the variance.
      CHECK(std::abs(m.mean) <= glint::test::kTailZ * sigma / std::sqrt(n));
      CHECK(std::abs(m.variance - double(sigma) * sigma) <=
            glint::test::kTailZ * double(sigma) * sigma * std::sqrt(2.0 / n));
      CHECK(glint::test::kolmogorov_smirnov(*axis, [&](double x) {
              return glint::test::standard_normal_cdf(x / sigma);
            }) < glint::test::kolmogorov_smirnov_threshold(axis->size()));
    }
    double cross = 0.0;
    for (int i = 0; i < kSamples; ++i)
      cross += xs[std::size_t(i)] * ys[std::size_t(i)];
    CHECK(std::abs(cross / n) <= glint::test::kTailZ * double(sigma) * sigma / std::sqrt(n));
  }
}

TEST_CASE("BoxAntialiasing: uniform over the pixel, -0.5 <= offset < 0.5",
          "[antialiasing][statistical]") {
  CHECK(glint::BoxAntialiasing::offset(Vec2(0.0f), 0.5f) == Vec2(-0.5f));
  const Vec2 largest = glint::BoxAntialiasing::offset(Vec2(1.0f - 0x1p-24f), 0.5f);
  CHECK(largest.x < 0.5f);
  CHECK(largest.x == Approx(0.5).margin(1e-6));
  std::vector<double> xs, ys;
  draw_offsets<glint::BoxAntialiasing>(0.5f, 3, xs, ys);
  const auto cdf = [](double x) { return x + 0.5; };
  const int bins = 64;
  for (const auto* axis : {&xs, &ys}) {
    CHECK(*std::min_element(axis->begin(), axis->end()) >= -0.5);
    CHECK(*std::max_element(axis->begin(), axis->end()) < 0.5);
    CHECK(glint::test::chi_square_equiprobable(*axis, bins, cdf) <
          glint::test::chi_square_threshold(bins - 1));
  }
}

TEST_CASE("TentAntialiasing: triangular density 1 - |x| for |x| < 1",
          "[antialiasing][statistical]") {
  // CDF: (1 + x)^2 / 2 for x <= 0 and 1 - (1 - x)^2 / 2 for x >= 0.
  const auto cdf = [](double x) {
    if (x <= -1.0) return 0.0;
    if (x >= 1.0) return 1.0;
    return x <= 0.0 ? 0.5 * (1.0 + x) * (1.0 + x) : 1.0 - 0.5 * (1.0 - x) * (1.0 - x);
  };
  CHECK(glint::TentAntialiasing::tent(0.0f) == -1.0f);
  CHECK(glint::TentAntialiasing::tent(0.5f) == Approx(0.0).margin(1e-6));
  CHECK(glint::TentAntialiasing::tent(1.0f - 0x1p-24f) < 1.0f);
  CHECK(glint::TentAntialiasing::tent(0.125f) == Approx(-0.5).epsilon(1e-6));  // cdf(-0.5)
  CHECK(glint::TentAntialiasing::tent(0.875f) == Approx(0.5).epsilon(1e-6));

  std::vector<double> xs, ys;
  draw_offsets<glint::TentAntialiasing>(0.5f, 5, xs, ys);
  const int bins = 64;
  for (const auto* axis : {&xs, &ys}) {
    CHECK(glint::test::chi_square_equiprobable(*axis, bins, cdf) <
          glint::test::chi_square_threshold(bins - 1));
    // The tent has variance 1/6 and fourth moment 1/15, so the sample variance has standard
    // error sqrt((1/15 - 1/36) / n).
    const glint::test::Moments m = glint::test::moments(*axis);
    CHECK(std::abs(m.mean) <= glint::test::kTailZ * std::sqrt(1.0 / 6.0 / kSamples));
    CHECK(std::abs(m.variance - 1.0 / 6.0) <=
          glint::test::kTailZ * std::sqrt((1.0 / 15.0 - 1.0 / 36.0) / kSamples));
  }
  // A uniform offset on [-1, 1] fails the same test: it can tell the densities apart.
  std::vector<double> uniform;
  glint::Pcg32 rng(5u, 1u);
  for (int i = 0; i < kSamples; ++i)
    uniform.push_back(2.0 * rng.next_float() - 1.0);
  CHECK(glint::test::chi_square_equiprobable(uniform, bins, cdf) >
        10.0 * glint::test::chi_square_threshold(bins - 1));
}

namespace {

/// The integral of Policy's density over the square of its footprint, by the midpoint rule on a
/// grid of `steps` x `steps`, and the largest density found outside the footprint's square.
template <typename Policy>
double density_integral(float sigma, int steps) {
  const double half = Policy::footprint(sigma);
  const double step = 2.0 * half / steps;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j)
      sum += Policy::density(Vec2(float(-half + (i + 0.5) * step), float(-half + (j + 0.5) * step)),
                             sigma);
  return sum * step * step;
}

}  // namespace

TEST_CASE("pixel filters: densities integrate to one within their footprints, zero outside",
          "[antialiasing]") {
  for (const float sigma : {0.25f, 0.5f, 1.5f}) {
    INFO("sigma " << sigma);
    CHECK(density_integral<glint::GaussianAntialiasing>(sigma, 800) == Approx(1.0).epsilon(1e-4));
    const float reach = glint::GaussianAntialiasing::footprint(sigma);
    CHECK(glint::GaussianAntialiasing::density(Vec2(reach * 1.001f, 0.0f), sigma) == 0.0f);
    // The density at the centre and at one sigma, from the formula.
    CHECK(glint::GaussianAntialiasing::density(Vec2(0.0f), sigma) ==
          Approx(1.0 / (2.0 * M_PI * sigma * sigma)).epsilon(1e-6));
    CHECK(glint::GaussianAntialiasing::density(Vec2(0.6f * sigma, 0.8f * sigma), sigma) ==
          Approx(std::exp(-0.5) / (2.0 * M_PI * sigma * sigma)).epsilon(1e-6));
  }
  CHECK(glint::GaussianAntialiasing::footprint(0.0f) == 0.0f);
  CHECK(glint::GaussianAntialiasing::density(Vec2(0.0f), 0.0f) == 0.0f);
  CHECK(density_integral<glint::BoxAntialiasing>(0.5f, 400) == Approx(1.0).epsilon(1e-6));
  CHECK(glint::BoxAntialiasing::density(Vec2(0.5f, 0.0f), 0.5f) == 0.0f);
  CHECK(glint::BoxAntialiasing::density(Vec2(-0.5f, 0.0f), 0.5f) == 1.0f);
  CHECK(density_integral<glint::TentAntialiasing>(0.5f, 400) == Approx(1.0).epsilon(1e-4));
  CHECK(glint::TentAntialiasing::density(Vec2(0.5f, -0.5f), 0.5f) == 0.25f);
  CHECK(glint::NoAntialiasing::footprint(0.5f) == 0.0f);
  CHECK(glint::NoAntialiasing::density(Vec2(0.0f), 0.5f) == 0.0f);
}

TEST_CASE("pixel filters: the Gaussian density is that of the offsets drawn",
          "[antialiasing][statistical]") {
  // The drawn offsets' radius, binned in 32 rings of equal density mass: the count per ring
  // against the mass the density gives it, integrated numerically from density().
  const float sigma = 0.5f;
  std::vector<double> xs, ys;
  draw_offsets<glint::GaussianAntialiasing>(sigma, 11, xs, ys);
  std::vector<double> radii;
  for (std::size_t i = 0; i < xs.size(); ++i)
    radii.push_back(std::sqrt(xs[i] * xs[i] + ys[i] * ys[i]));
  const double reach = glint::GaussianAntialiasing::footprint(sigma);
  // The cdf of the radius from the density: the integral of 2 pi r density(r) dr.
  constexpr int kSteps = 20000;
  std::vector<double> cdf(kSteps + 1, 0.0);
  for (int i = 0; i < kSteps; ++i) {
    const double r = (i + 0.5) * reach / kSteps;
    cdf[std::size_t(i) + 1] =
        cdf[std::size_t(i)] +
        2.0 * M_PI * r * glint::GaussianAntialiasing::density(Vec2(float(r), 0.0f), sigma) * reach /
            kSteps;
  }
  const auto radius_cdf = [&](double r) {
    if (r >= reach) return 1.0;
    const double at = r / reach * kSteps;
    const auto i = std::size_t(at);
    return cdf[i] + (cdf[i + 1] - cdf[i]) * (at - double(i));
  };
  const int bins = 32;
  CHECK(glint::test::chi_square_equiprobable(radii, bins, radius_cdf) <
        glint::test::chi_square_threshold(bins - 1));
  // A density 5% too wide fails the same test: it can tell them apart.
  std::vector<double> wider;
  for (const double r : radii)
    wider.push_back(r * 1.05);
  CHECK(glint::test::chi_square_equiprobable(wider, bins, radius_cdf) >
        glint::test::chi_square_threshold(bins - 1));
}
