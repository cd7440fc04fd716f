// Light sampling's parts, each against values worked out here rather than by the library: the
// uniform cone against its law (chi-square over cos theta and phi) and its solid angle, the
// directions towards a sphere from outside (each one hits it, the cap is covered uniformly) and
// from inside (the density integrates to one, its reciprocal to the solid angle covered), the
// choice of emitters in proportion to power, the MIS heuristics' partition of unity, and the
// Russian roulette probability.
//
// Every statistical check has a fixed seed and a threshold that a correct implementation
// exceeds with probability about 1e-6 (statistics.hpp), or five standard errors (normal tail
// 6e-7), so the tests are deterministic and fail only for a wrong density.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "glint/math/random.hpp"
#include "glint/math/sampling.hpp"
#include "glint/policy/light_sampling.hpp"
#include "glint/policy/path_termination.hpp"
#include "glint/render/lights/sphere_light.hpp"
#include "glint/scene/emitters.hpp"
#include "statistics.hpp"

using glint::Color;
using glint::SphereLight;
using EmitterView = glint::SphereLightView;
using glint::SphereEmitter;
using glint::Vec2;
using glint::Vec3;

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kFourPi = 4.0 * M_PI;

struct DVec {
  double x, y, z;
  DVec operator+(const DVec& o) const { return {x + o.x, y + o.y, z + o.z}; }
  DVec operator-(const DVec& o) const { return {x - o.x, y - o.y, z - o.z}; }
  DVec operator*(double s) const { return {x * s, y * s, z * s}; }
  double dot(const DVec& o) const { return x * o.x + y * o.y + z * o.z; }
  DVec cross(const DVec& o) const {
    return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x};
  }
  double length() const { return std::sqrt(dot(*this)); }
  DVec unit() const { return *this * (1.0 / length()); }
};

DVec to_double(const Vec3& v) {
  return {v.x, v.y, v.z};
}
Vec3 to_float(const DVec& v) {
  return {float(v.x), float(v.y), float(v.z)};
}

/// 1 - cos of the half-angle a sphere of radius r subtends at distance d, without cancellation.
double one_minus_cos_max(double r, double d) {
  const double sin2 = (r / d) * (r / d);
  return sin2 / (1.0 + std::sqrt(1.0 - sin2));
}

/// The solid angle of a sphere of radius r seen from distance d > r.
double sphere_solid_angle(double r, double d) {
  return kTwoPi * one_minus_cos_max(r, d);
}

/// Coordinates of a unit direction around `axis`: 1 - cos of its angle to the axis (from the
/// perpendicular part, which keeps its precision for directions close to the axis) and its
/// azimuth as a fraction of a turn.
struct ConeCoordinates {
  double one_minus_cos;
  double azimuth01;
};

ConeCoordinates cone_coordinates(const DVec& direction, const DVec& axis) {
  const DVec d = direction.unit();
  const DVec a = axis.unit();
  // Any frame around the axis will do: the law is uniform in azimuth.
  const DVec helper = std::fabs(a.x) < 0.5 ? DVec{1, 0, 0} : DVec{0, 1, 0};
  const DVec t = a.cross(helper).unit();
  const DVec b = a.cross(t);
  const double along = d.dot(a);
  const double x = d.dot(t), y = d.dot(b);
  const double sin2 = x * x + y * y;
  const double one_minus_cos = along > 0.0 ? sin2 / (1.0 + along) : 1.0 - along;
  double phi = std::atan2(y, x);
  if (phi < 0.0) phi += kTwoPi;
  return {one_minus_cos, phi / kTwoPi};
}

/// Chi-square statistic of (cos theta, phi) pairs against the uniform cone of 1 - cos theta_max
/// = `m`, on a grid of bins x bins cells of equal probability.
double cone_chi_square(const std::vector<ConeCoordinates>& samples, double m, int bins) {
  std::vector<double> counts(std::size_t(bins * bins), 0.0);
  for (const ConeCoordinates& c : samples) {
    const int i = std::clamp(int(c.one_minus_cos / m * bins), 0, bins - 1);
    const int j = std::clamp(int(c.azimuth01 * bins), 0, bins - 1);
    counts[std::size_t(i * bins + j)] += 1.0;
  }
  const double expected = double(samples.size()) / (bins * bins);
  double chi2 = 0.0;
  for (const double c : counts)
    chi2 += (c - expected) * (c - expected) / expected;
  return chi2;
}

Vec2 next_2d(glint::Pcg32& rng) {
  const float a = rng.next_float();
  return {a, rng.next_float()};
}

/// The nearer and farther ray parameters where a ray meets a sphere, in double precision.
struct Roots {
  bool hit;
  double near, far;
};

Roots intersect(const DVec& origin, const DVec& direction, const DVec& center, double radius) {
  const DVec f = origin - center;
  const DVec d = direction.unit();
  const double b = f.dot(d);
  const DVec perpendicular = f - d * b;
  const double disc = radius * radius - perpendicular.dot(perpendicular);
  if (disc < 0.0) return {false, 0.0, 0.0};
  const double s = std::sqrt(disc);
  return {true, -b - s, -b + s};
}

/// The distance from `center` to the line through `origin` along `direction`.
double miss_distance(const DVec& origin, const DVec& direction, const DVec& center) {
  const DVec d = direction.unit();
  const DVec f = center - origin;
  const DVec perpendicular = f - d * f.dot(d);
  return perpendicular.length();
}

constexpr std::uint32_t kEmitterSphere = 7;
constexpr std::uint32_t kOtherSphere = 3;

/// A direction towards `light` from `point`, which sees it as `view` says; none where nothing
/// can arrive.
std::optional<glint::LightSample> sample_towards(const SphereLight& light, const Vec3& point,
                                                 EmitterView view, Vec2 u) {
  const glint::LightSample sample =
      light.sample_li(point, view == EmitterView::outside, view == EmitterView::none, u);
  if (!sample.valid) return std::nullopt;
  return sample;
}

SphereLight make_emitter(Vec3 center, float radius) {
  return SphereLight(SphereEmitter{center, radius, Color(1.0f), kEmitterSphere});
}

}  // namespace

// ---- the uniform cone ---------------------------------------------------------------------

TEST_CASE("emitter sampling: sample_uniform_cone follows the uniform law over the cone",
          "[emitters][statistical]") {
  // 1 - cos(theta_max): a cone wider than a hemisphere, the whole sphere, and a narrow one.
  const double cones[] = {1.5, 2.0, 1e-3};
  const int n = 1 << 17;
  const int bins = 16;  // 256 cells, 2^17 / 256 = 512 expected per cell
  for (const double m : cones) {
    INFO("1 - cos theta_max = " << m);
    glint::Pcg32 rng(12345u, 7u);
    std::vector<ConeCoordinates> samples;
    samples.reserve(n);
    int outside = 0, not_unit = 0;
    for (int i = 0; i < n; ++i) {
      const Vec3 v = glint::sample_uniform_cone(next_2d(rng), float(m));
      const DVec d = to_double(v);
      if (std::fabs(d.length() - 1.0) > 1e-6) ++not_unit;
      const ConeCoordinates c = cone_coordinates(d, {0, 0, 1});
      // Float rounding of the sampled cosine: a few ulps of 1, or of m for the narrow cone.
      if (c.one_minus_cos > m * (1.0 + 1e-5) + 1e-7) ++outside;
      samples.push_back(c);
    }
    CHECK(not_unit == 0);
    CHECK(outside == 0);
    CHECK(cone_chi_square(samples, m, bins) < glint::test::chi_square_threshold(bins * bins - 1));
  }
}

TEST_CASE("emitter sampling: uniform_cone_pdf is the reciprocal of the cone's solid angle",
          "[emitters]") {
  // Integrating a constant density over the cone gives pdf * 2 pi (1 - cos theta_max): one.
  for (const double m : {2.0, 1.0, 0.3, 1e-3, 1e-6, 5e-9}) {
    INFO("1 - cos theta_max = " << m);
    const double pdf = glint::uniform_cone_pdf(float(m));
    CHECK(pdf * kTwoPi * m == Approx(1.0).epsilon(1e-6));
  }
}

TEST_CASE(
    "emitter sampling: a tiny distant cone keeps a finite density and its directions inside it",
    "[emitters]") {
  // A sphere of radius 1 at distance 1e4: 1 - cos theta_max ~ 5e-9, below float's epsilon
  // at 1, which is why the cone is given by 1 - cos and not by the cosine.
  const double r = 1.0, d = 1e4;
  const double m = one_minus_cos_max(r, d);
  const double theta_max = std::asin(r / d);
  const float pdf = glint::uniform_cone_pdf(float(m));
  CHECK(std::isfinite(pdf));
  CHECK(1.0 / pdf == Approx(sphere_solid_angle(r, d)).epsilon(1e-5));
  glint::Pcg32 rng(99u, 3u);
  double largest_angle = 0.0, smallest_angle = 1.0;
  for (int i = 0; i < 4096; ++i) {
    // The corners of the unit square too: u.x = 0 and u.x close to 1 are the cone's axis and rim.
    const Vec2 u = i == 0 ? Vec2(0.0f) : i == 1 ? Vec2(1.0f - 0x1p-24f) : next_2d(rng);
    const Vec3 v = glint::sample_uniform_cone(u, float(m));
    REQUIRE(std::isfinite(v.x));
    REQUIRE(std::isfinite(v.y));
    REQUIRE(std::isfinite(v.z));
    const double angle = std::atan2(std::hypot(double(v.x), double(v.y)), double(v.z));
    largest_angle = std::max(largest_angle, angle);
    smallest_angle = std::min(smallest_angle, angle);
  }
  // The angle comes from the sine, exact to float precision: far tighter than the cone.
  CHECK(largest_angle <= theta_max * (1.0 + 1e-5));
  // The directions spread over the cone rather than collapsing onto its axis (u.x rounding).
  CHECK(largest_angle > 0.99 * theta_max);
  CHECK(smallest_angle < 0.1 * theta_max);

  // The same through SphereLight: every direction still meets the sphere. Float directions
  // are good to ~1e-7 radians after the change of frame; at 1e4 that is 1e-3 sideways.
  const Vec3 center(3.0f, -2.0f, 1.0f);
  const SphereLight emitter = make_emitter(center, float(r));
  const DVec axis = DVec{1, 2, -2}.unit();
  const DVec point = to_double(center) - axis * d;
  const Vec3 p = to_float(point);
  REQUIRE(emitter.view_from({p, kOtherSphere, false}) == EmitterView::outside);
  int misses = 0;
  for (int i = 0; i < 4096; ++i) {
    const auto sample = sample_towards(emitter, p, EmitterView::outside, next_2d(rng));
    REQUIRE(sample.has_value());
    REQUIRE(std::isfinite(sample->pdf));
    if (miss_distance(to_double(p), to_double(sample->direction), to_double(center)) > r + 2e-7 * d)
      ++misses;
    CHECK(1.0 / sample->pdf == Approx(sphere_solid_angle(r, d)).epsilon(1e-4));
  }
  CHECK(misses == 0);
}

// ---- SphereLight ---------------------------------------------------------------------------

TEST_CASE("emitter sampling: SphereLight::view_from", "[emitters]") {
  const SphereLight emitter = make_emitter(Vec3(1.0f, 2.0f, 3.0f), 2.0f);
  const Vec3 on_surface(1.0f, 2.0f, 5.0f);
  // A point on the emitter's own surface sees it only from inside.
  CHECK(emitter.view_from({on_surface, kEmitterSphere, false}) == EmitterView::none);
  CHECK(emitter.view_from({on_surface, kEmitterSphere, true}) == EmitterView::inside);
  // A point of another sphere: by where it is.
  CHECK(emitter.view_from({Vec3(1.0f, 2.0f, 8.0f), kOtherSphere, false}) == EmitterView::outside);
  CHECK(emitter.view_from({Vec3(1.0f, 2.0f, 8.0f), kOtherSphere, true}) == EmitterView::outside);
  CHECK(emitter.view_from({Vec3(1.5f, 2.0f, 3.0f), kOtherSphere, false}) == EmitterView::inside);
  CHECK(emitter.view_from({Vec3(1.5f, 2.0f, 3.0f), kOtherSphere, true}) == EmitterView::inside);
  // Nothing to sample, no density, from a point that cannot see the emitter.
  CHECK_FALSE(sample_towards(emitter, on_surface, EmitterView::none, Vec2(0.3f, 0.6f)));
  CHECK(emitter.pdf_li(on_surface, EmitterView::none, Vec3(0.0f, 0.0f, -1.0f), 4.0f,
                       Vec3(0.0f, 0.0f, -1.0f)) == 0.0f);
}

TEST_CASE(
    "emitter sampling: SphereLight from outside: every direction hits, uniformly over the cone",
    "[emitters][statistical]") {
  const DVec center{1.0, 2.0, 3.0};
  const double r = 2.0;
  const SphereLight emitter = make_emitter(to_float(center), float(r));
  // Close (the cap is a large part of the sphere) and farther away.
  for (const double distance : {2.5, 5.0, 40.0}) {
    INFO("distance " << distance);
    const DVec axis = DVec{-0.3, 0.8, 0.52}.unit();
    const DVec point = center - axis * distance;
    const Vec3 p = to_float(point);
    const double solid_angle = sphere_solid_angle(r, distance);
    const double m = one_minus_cos_max(r, distance);
    REQUIRE(emitter.view_from({p, kOtherSphere, false}) == EmitterView::outside);

    glint::Pcg32 rng(2024u, 11u);
    const int n = 1 << 16;
    std::vector<ConeCoordinates> samples;
    samples.reserve(n);
    int misses = 0, pdf_mismatches = 0;
    for (int i = 0; i < n; ++i) {
      const auto sample = sample_towards(emitter, p, EmitterView::outside, next_2d(rng));
      REQUIRE(sample.has_value());
      const DVec direction = to_double(sample->direction);
      const Roots roots = intersect(point, direction, center, r);
      // Directions at the rim may graze it by rounding: allow float precision of the direction.
      if (!roots.hit && miss_distance(point, direction, center) > r + 1e-6 * distance) ++misses;
      if (i % 64 == 0) CHECK(1.0 / sample->pdf == Approx(solid_angle).epsilon(1e-5));
      // The density of the direction as a bounce that met the sphere would ask for it.
      const double t = roots.hit ? roots.near : (center - point).dot(direction.unit());
      const DVec at = point + direction.unit() * t;
      const Vec3 normal = to_float((at - center).unit());
      const float pdf =
          emitter.pdf_li(p, EmitterView::outside, sample->direction, float(t), normal);
      if (!(std::fabs(pdf - sample->pdf) <= 1e-6f * sample->pdf)) ++pdf_mismatches;
      samples.push_back(cone_coordinates(direction, center - point));
    }
    CHECK(misses == 0);
    CHECK(pdf_mismatches == 0);
    const int bins = 16;
    CHECK(cone_chi_square(samples, m, bins) < glint::test::chi_square_threshold(bins * bins - 1));
  }
}

TEST_CASE(
    "emitter sampling: SphereLight from inside: the density integrates to one over all "
    "directions",
    "[emitters][statistical]") {
  // Seen from inside, directions are drawn through uniform points of the sphere's area; the
  // density must then cover every direction that meets the sphere from there. Two checks,
  // both independent of how the library draws its samples:
  //  - E over uniform directions of 4 pi * direction_pdf(...) = integral of the pdf = 1,
  //    with the distance and normal of the hit worked out here;
  //  - E over its own samples of g / pdf = integral of g over the directions covered.
  const DVec center{-1.0, 0.5, 2.0};
  const double r = 3.0;
  const SphereLight emitter = make_emitter(to_float(center), float(r));

  const auto integrate_pdf = [&](const DVec& point, EmitterView view) {
    glint::Pcg32 rng(77u, 5u);
    const int n = 1 << 16;
    std::vector<double> values;
    values.reserve(n);
    for (int i = 0; i < n; ++i) {
      const DVec direction = to_double(glint::sample_uniform_sphere(next_2d(rng))).unit();
      const Roots roots = intersect(point, direction, center, r);
      double value = 0.0;
      // From inside only the far root lies ahead; from the surface, directions leaving the
      // sphere meet nothing of it (their far root is ~0).
      if (roots.hit && roots.far > 1e-9 * r) {
        const DVec at = point + direction * roots.far;
        const float pdf = emitter.pdf_li(to_float(point), view, to_float(direction),
                                         float(roots.far), to_float((at - center).unit()));
        value = kFourPi * pdf;
      }
      values.push_back(value);
    }
    return glint::test::moments(values);
  };

  SECTION("from a point inside the sphere") {
    const DVec point = center + DVec{0.6, -0.8, 1.2} * (0.6 * r / 1.56);
    const Vec3 p = to_float(point);
    REQUIRE(emitter.view_from({p, kOtherSphere, false}) == EmitterView::inside);

    const glint::test::Moments integral = integrate_pdf(point, EmitterView::inside);
    CHECK(std::abs(integral.mean - 1.0) <= 5.0 * std::sqrt(integral.variance / (1 << 16)));

    glint::Pcg32 rng(31u, 9u);
    const int n = 1 << 16;
    std::vector<double> all, upper, cos2;
    int mismatches = 0;
    for (int i = 0; i < n; ++i) {
      const auto sample = sample_towards(emitter, p, EmitterView::inside, next_2d(rng));
      REQUIRE(sample.has_value());
      REQUIRE(sample->pdf > 0.0f);
      const DVec direction = to_double(sample->direction);
      const Roots roots = intersect(point, direction, center, r);
      REQUIRE(roots.hit);
      const DVec at = point + direction.unit() * roots.far;
      const float pdf = emitter.pdf_li(p, EmitterView::inside, sample->direction, float(roots.far),
                                       to_float((at - center).unit()));
      if (!(std::fabs(pdf - sample->pdf) <= 1e-4f * sample->pdf)) ++mismatches;
      const double inverse = 1.0 / sample->pdf;
      all.push_back(inverse);
      upper.push_back(direction.z > 0.0 ? inverse : 0.0);
      cos2.push_back(direction.z * direction.z * inverse);
    }
    CHECK(mismatches == 0);
    // Whole sphere, upper hemisphere, and the integral of cos^2 theta over the sphere.
    const std::array<std::pair<const std::vector<double>*, double>, 3> checks = {
        {{&all, kFourPi}, {&upper, kTwoPi}, {&cos2, kFourPi / 3.0}}};
    for (const auto& [values, expected] : checks) {
      const glint::test::Moments m = glint::test::moments(*values);
      const double se = std::sqrt(m.variance / n);
      INFO("mean " << m.mean << " +- " << se << ", expected " << expected);
      CHECK(std::abs(m.mean - expected) <= 5.0 * se);
    }
  }

  SECTION("from a point on the sphere, seen from inside") {
    const DVec normal = DVec{0.2, -0.9, 0.4}.unit();
    const DVec point = center + normal * r;
    const Vec3 p = to_float(point);
    REQUIRE(emitter.view_from({p, kEmitterSphere, true}) == EmitterView::inside);

    const glint::test::Moments integral = integrate_pdf(point, EmitterView::inside);
    CHECK(std::abs(integral.mean - 1.0) <= 5.0 * std::sqrt(integral.variance / (1 << 16)));

    // The samples cover the inward hemisphere, where the density is cos(alpha) / pi with alpha
    // the angle to the inward normal (chord 2 r cos alpha, and the same cosine at its far
    // end). 1/pdf has infinite variance there, so the check weighs by cos alpha:
    // E[cos alpha / pdf] = integral of cos over the hemisphere = pi, with finite variance.
    glint::Pcg32 rng(31u, 9u);
    const int n = 1 << 16;
    std::vector<double> weighted;
    int mismatches = 0, degenerate = 0;
    for (int i = 0; i < n; ++i) {
      const auto sample = sample_towards(emitter, p, EmitterView::inside, next_2d(rng));
      if (!sample) {  // the sampled point fell on the shading point itself
        ++degenerate;
        continue;
      }
      const DVec direction = to_double(sample->direction).unit();
      const double cos_alpha = -direction.dot(normal);
      const double length = 2.0 * r * cos_alpha;  // the chord, worked out independently
      const float pdf = emitter.pdf_li(p, EmitterView::inside, sample->direction, float(length),
                                       to_float((point + direction * length - center).unit()));
      if (!(std::fabs(pdf - sample->pdf) <= 1e-3f * sample->pdf)) ++mismatches;
      if (!(std::fabs(sample->pdf - cos_alpha / M_PI) <= 1e-3 * cos_alpha / M_PI)) ++mismatches;
      weighted.push_back(cos_alpha / sample->pdf);
    }
    CHECK(degenerate <= 1);
    CHECK(mismatches == 0);
    const glint::test::Moments m = glint::test::moments(weighted);
    const double mean = m.mean * double(weighted.size()) / n;  // failed samples count zero
    CHECK(std::abs(mean - M_PI) <= 5.0 * std::sqrt(m.variance / n) + 1e-6);
  }
}

// ---- EmitterTable --------------------------------------------------------------------------

TEST_CASE("emitter sampling: EmitterTable chooses emitters in proportion to power",
          "[emitters][statistical]") {
  // Power is area times mean radiance: r^2 * (R + G + B) / 3, up to a common factor.
  const std::vector<SphereEmitter> emitters = {
      {Vec3(0.0f), 1.0f, Color(3.0f, 0.0f, 0.0f), 0u},
      {Vec3(5.0f), 2.0f, Color(0.5f, 1.0f, 1.5f), 4u},
      {Vec3(-5.0f), 0.5f, Color(10.0f, 10.0f, 10.0f), 9u},
      {Vec3(9.0f), 0.1f, Color(1.0f, 2.0f, 0.0f), 2u},
  };
  std::vector<double> power;
  double total = 0.0;
  for (const SphereEmitter& e : emitters) {
    power.push_back(double(e.radius) * e.radius * (e.radiance.r + e.radiance.g + e.radiance.b));
    total += power.back();
  }
  const glint::EmitterTable table(emitters);
  REQUIRE(table.size() == emitters.size());
  double sum = 0.0;
  for (std::uint32_t i = 0; i < table.size(); ++i) {
    INFO("emitter " << i);
    // Each probability is a step of the cdf as stored in float, whose values near one are
    // spaced 6e-8 apart: an absolute error of a few 1e-8, large relative to a small step.
    CHECK(table.probability(i) == Approx(power[i] / total).epsilon(1e-6).margin(2.5e-7));
    CHECK(table[i].sphere == emitters[i].sphere);
    sum += table.probability(i);
  }
  CHECK(sum == Approx(1.0).epsilon(1e-6));

  // The ends of [0, 1): a valid emitter with the probability it is chosen with.
  for (const float u : {0.0f, std::nextafter(1.0f, 0.0f)}) {
    const glint::EmitterTable::Choice c = table.choose(u);
    REQUIRE(c.index < table.size());
    CHECK(c.probability > 0.0f);
    CHECK(c.probability == table.probability(c.index));
  }
  CHECK(table.choose(0.0f).index == 0u);
  CHECK(table.choose(std::nextafter(1.0f, 0.0f)).index == table.size() - 1);

  glint::Pcg32 rng(4242u, 1u);
  const int n = 1 << 18;
  std::vector<double> counts(table.size(), 0.0);
  int wrong_probability = 0;
  for (int i = 0; i < n; ++i) {
    const glint::EmitterTable::Choice c = table.choose(rng.next_float());
    REQUIRE(c.index < table.size());
    if (c.probability != table.probability(c.index)) ++wrong_probability;
    counts[c.index] += 1.0;
  }
  CHECK(wrong_probability == 0);
  double chi2 = 0.0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double expected = n * power[i] / total;
    chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
  }
  CHECK(chi2 < glint::test::chi_square_threshold(int(counts.size()) - 1));

  // One emitter: always it, with probability exactly one.
  const glint::EmitterTable single({emitters[1]});
  CHECK(single.choose(0.0f).index == 0u);
  CHECK(single.choose(0.7f).probability == 1.0f);
}

// ---- MIS heuristics ------------------------------------------------------------------------

namespace {

template <typename Heuristic>
void check_partition_of_unity(double log10_low, double log10_high) {
  glint::Pcg32 rng(8u, 13u);
  int bad = 0;
  float example_a = 0.0f, example_b = 0.0f, example_sum = 0.0f;
  for (int i = 0; i < 100000; ++i) {
    const float a = float(std::pow(10.0, log10_low + (log10_high - log10_low) * rng.next_float()));
    const float b = float(std::pow(10.0, log10_low + (log10_high - log10_low) * rng.next_float()));
    const float wa = Heuristic::weight(a, b), wb = Heuristic::weight(b, a);
    const bool ok = std::isfinite(wa) && std::isfinite(wb) && wa >= 0.0f && wa <= 1.0f &&
                    wb >= 0.0f && wb <= 1.0f && std::fabs(wa + wb - 1.0f) <= 1e-5f;
    if (!ok) {
      ++bad;
      example_a = a;
      example_b = b;
      example_sum = wa + wb;
    }
  }
  INFO("e.g. weight(" << example_a << ", " << example_b << ") + weight(" << example_b << ", "
                      << example_a << ") = " << example_sum);
  CHECK(bad == 0);
}

template <typename Heuristic>
void check_heuristic_limits() {
  constexpr float inf = std::numeric_limits<float>::infinity();
  for (const float x : {0.0f, 1e-30f, 0.5f, 3.0f, 1e30f}) {
    INFO("other pdf " << x);
    CHECK(Heuristic::weight(0.0f, x) == 0.0f);
    CHECK(Heuristic::weight(inf, x) == 1.0f);
  }
  // A strategy whose density is zero leaves everything to the other one.
  CHECK(Heuristic::weight(0.25f, 0.0f) == 1.0f);
  // Equal densities share equally.
  CHECK(Heuristic::weight(2.0f, 2.0f) == Approx(0.5f));
  // The ends of the float range: still weights in [0, 1] that sum to one.
  constexpr float big = std::numeric_limits<float>::max();
  constexpr float tiny = std::numeric_limits<float>::denorm_min();
  const std::pair<float, float> extremes[] = {{big, big},   {big, 0.5f * big},   {big, 1.0f},
                                              {tiny, tiny}, {tiny, 4.0f * tiny}, {tiny, 1.0f}};
  for (const auto& [a, b] : extremes) {
    const float wa = Heuristic::weight(a, b), wb = Heuristic::weight(b, a);
    INFO("weight(" << a << ", " << b << ") = " << wa << ", weight(" << b << ", " << a
                   << ") = " << wb);
    CHECK(std::isfinite(wa));
    CHECK(std::isfinite(wb));
    CHECK(wa >= 0.0f);
    CHECK(wb >= 0.0f);
    CHECK(wa + wb == Approx(1.0f).margin(1e-5));
  }
}

}  // namespace

TEMPLATE_TEST_CASE_SIG(
    "emitter sampling: EmitterTable::choose_lanes chooses what choose does, lane by lane",
    "[emitters][lanes]", ((int W), W), 8, 16) {
  // Tables counted over (1, 7, 64 emitters) and searched (65, 300); each u is tried at the
  // cdf's steps and their neighbours, where a count and a search could disagree, and at random.
  using F = glint::Float<W>;
  glint::Pcg32 rng(77u, 3u);
  for (const int size : {1, 7, 64, 65, 300}) {
    std::vector<SphereEmitter> emitters;
    for (int i = 0; i < size; ++i)
      emitters.push_back({Vec3(float(i)), 0.1f + rng.next_float(),
                          Color(rng.next_float(), rng.next_float(), 1.0f), std::uint32_t(i)});
    const glint::EmitterTable table(emitters);
    std::vector<float> us = {0.0f, std::nextafter(1.0f, 0.0f)};
    float step = 0.0f;
    for (std::uint32_t i = 0; i < table.size(); ++i) {
      step += table.probability(i);
      for (const float u : {step, std::nextafter(step, 0.0f), std::nextafter(step, 1.0f)})
        if (u >= 0.0f && u < 1.0f) us.push_back(u);
    }
    for (int i = 0; i < 256; ++i)
      us.push_back(rng.next_float());
    while (us.size() % W != 0)
      us.push_back(0.5f);
    for (std::size_t base = 0; base < us.size(); base += W) {
      F u;
      for (int i = 0; i < W; ++i)
        u[i] = us[base + std::size_t(i)];
      const glint::EmitterLanes<F> chosen = table.choose_lanes(u);
      for (int i = 0; i < W; ++i) {
        INFO(size << " emitters, u = " << u[i]);
        const glint::EmitterTable::Choice c = table.choose(u[i]);
        CHECK(chosen.sphere[i] == table[c.index].sphere);
        CHECK(chosen.probability[i] == c.probability);
        CHECK(chosen.radius[i] == table[c.index].radius);
        CHECK(chosen.center.lane(i) == table[c.index].center);
        CHECK(chosen.radiance.lane(i) == table[c.index].radiance);
      }
    }
  }
}

TEST_CASE("emitter sampling: balance heuristic: weights of (a, b) and (b, a) sum to one",
          "[emitters]") {
  // The balance weight is a / (a + b) (Veach 1997, 9.2.2).
  CHECK(glint::BalanceHeuristic::weight(1.0f, 3.0f) == Approx(0.25));
  check_heuristic_limits<glint::BalanceHeuristic>();
  SECTION("densities from 1e-6 to 1e6") {
    check_partition_of_unity<glint::BalanceHeuristic>(-6, 6);
  }
  SECTION("densities from 1e-38 to 1e38") {
    check_partition_of_unity<glint::BalanceHeuristic>(-37, 38);
  }
}

TEST_CASE("emitter sampling: power heuristic: weights of (a, b) and (b, a) sum to one",
          "[emitters]") {
  // The power weight (exponent 2) is a^2 / (a^2 + b^2) (Veach 1997, 9.2.4).
  CHECK(glint::PowerHeuristic::weight(1.0f, 3.0f) == Approx(0.1));
  check_heuristic_limits<glint::PowerHeuristic>();
  SECTION("densities from 1e-6 to 1e6") {
    check_partition_of_unity<glint::PowerHeuristic>(-6, 6);
  }
  // Densities beyond the square root of the float range arise: the cone density of a small
  // distant lamp is 1 / (2 pi (1 - cos theta_max)), 1e20 for a lamp 1e10 times as far away as
  // it is wide, and the area density from inside a huge emitter near a grazing point is tiny.
  // Squaring them must not overflow to a weight of one for both strategies, nor underflow
  // to 0 / 0.
  SECTION("densities from 1e-38 to 1e38") {
    check_partition_of_unity<glint::PowerHeuristic>(-37, 38);
  }
}

TEST_CASE(
    "emitter sampling: EmitterSamplingOnly: light samples weigh one, bounces onto emitters zero",
    "[emitters]") {
  using L = glint::EmitterSamplingOnly<>;
  STATIC_REQUIRE(L::samples_emitters);
  STATIC_REQUIRE_FALSE(glint::PointLightsOnly::samples_emitters);
  for (const auto& [a, b] : {std::pair{0.1f, 10.0f}, {10.0f, 0.1f}, {1.0f, 0.0f}, {0.0f, 1.0f}}) {
    CHECK(L::light_weight(a, b) == 1.0f);
    CHECK(L::bounce_weight(a, b) == 0.0f);
    // Bounces alone: a bounce that finds an emitter keeps all of it.
    CHECK(glint::PointLightsOnly::bounce_weight(a, b) == 1.0f);
  }
  // EmitterSampling hands each strategy its heuristic weight, with the arguments in the order
  // (own density, other density).
  using Mis = glint::EmitterSampling<glint::BalanceHeuristic>;
  CHECK(Mis::light_weight(3.0f, 1.0f) == Approx(0.75));
  CHECK(Mis::bounce_weight(1.0f, 3.0f) == Approx(0.25));
}

// ---- Russian roulette ----------------------------------------------------------------------

TEST_CASE("emitter sampling: RussianRoulette::continue_probability", "[emitters]") {
  using R = glint::RussianRoulette;
  // Never before three bounces, whatever the throughput.
  for (const int depth : {0, 1, 2})
    for (const float throughput : {0.0f, 1e-6f, 0.3f, 1.0f, 5.0f})
      CHECK(R::continue_probability(depth, throughput) == 1.0f);
  for (const int depth : {3, 4, 10, 1000}) {
    INFO("depth " << depth);
    // A path at or above throughput one is never played (a lossless path is never killed).
    for (const float throughput : {1.0f, 1.0000001f, 2.5f, 1e30f})
      CHECK(R::continue_probability(depth, throughput) == 1.0f);
    // Below one it continues with probability equal to its throughput, so that a survivor
    // carries throughput one.
    for (const float throughput : {0.0f, 1e-20f, 0.01f, 0.5f, std::nextafter(1.0f, 0.0f)})
      CHECK(R::continue_probability(depth, throughput) == throughput);
  }
}
