// The emitter choices of light sampling (policy/emitter_choice.hpp), against values worked out
// here: the choice by contribution chooses each emitter with the probability it reports (counted
// over evenly spread u), its probabilities sum to one, every emitter that can light the point
// has a chance and none wholly below the horizon or behind the point's own surface has one, its
// estimate is the radiance times the solid angle times the elevation of the lamp's top, and every
// width chooses the same emitters with the same bits.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "glint/math/random.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/emitter_choice.hpp"
#include "glint/scene/emitters.hpp"

using glint::Color;
using glint::EmitterChoiceByContribution;
using glint::EmitterChoicePoint;
using glint::EmitterTable;
using glint::SphereEmitter;
using glint::Vec3;

namespace {

using Choice = EmitterChoiceByContribution;
constexpr std::uint32_t kFloorSphere = 1000;  // the sphere the shading points lie on

/// `count` lamps of radius 0.2 to 2.2 and radiance 1 to 20 (channel means) scattered in a box of
/// side 40 about the origin.
EmitterTable scattered_lamps(int count, std::uint64_t seed) {
  glint::Pcg32 rng(seed, 5u);
  std::vector<SphereEmitter> lamps;
  for (int i = 0; i < count; ++i) {
    const Vec3 center(40.0f * rng.next_float() - 20.0f, 40.0f * rng.next_float() - 20.0f,
                      40.0f * rng.next_float() - 20.0f);
    const float level = 1.0f + 19.0f * rng.next_float();
    lamps.push_back({center, 0.2f + 2.0f * rng.next_float(),
                     Color(level, 0.5f * level, 1.5f * level), std::uint32_t(i)});
  }
  return EmitterTable(lamps);
}

/// A unit vector drawn uniformly on the sphere.
Vec3 random_direction(glint::Pcg32& rng) {
  const float z = 2.0f * rng.next_float() - 1.0f;
  const float phi = 2.0f * float(M_PI) * rng.next_float();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

EmitterChoicePoint<float> random_point(glint::Pcg32& rng) {
  const Vec3 point(30.0f * rng.next_float() - 15.0f, 30.0f * rng.next_float() - 15.0f,
                   30.0f * rng.next_float() - 15.0f);
  return {point, random_direction(rng), kFloorSphere, false};
}

/// Whether any direction of the cone towards a sphere (centre, radius) from `p` is above the
/// plane of normal `n`, in double, with the margin by which it is: the cosine of the angle
/// between n and the cone's nearest direction (the cone's half-angle taken off the angle to its
/// centre), or one where n lies inside the cone.
double highest_cosine(const EmitterChoicePoint<float>& at, const SphereEmitter& e) {
  const double dx = double(e.center.x) - at.point.x, dy = double(e.center.y) - at.point.y,
               dz = double(e.center.z) - at.point.z;
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double cos_center = (dx * at.normal.x + dy * at.normal.y + dz * at.normal.z) / d;
  const double theta_center = std::acos(std::clamp(cos_center, -1.0, 1.0));
  const double theta_max = std::asin(std::min(1.0, double(e.radius) / d));
  return theta_center <= theta_max ? 1.0 : std::cos(theta_center - theta_max);
}

}  // namespace

TEST_CASE("emitter choice: by contribution, each emitter is chosen with its probability",
          "[emitters][unit]") {
  // For evenly spread u, u_k = (k + 1/2) / M, the choice of emitter i must happen M p_i times
  // to within the two steps a boundary can fall between, and each choice must report p_i.
  constexpr int kUs = 4096;
  glint::Pcg32 rng(11u, 2u);
  // Up to EmitterChoiceByContribution::kKeptEstimates emitters the second pass reads the first's
  // estimates, beyond it computes them again: both ways are counted.
  static_assert(Choice::kKeptEstimates == 64);
  for (const int count : {1, 3, 60, 64, 65, 150}) {
    const EmitterTable table = scattered_lamps(count, std::uint64_t(count));
    for (int trial = 0; trial < 40; ++trial) {
      const EmitterChoicePoint<float> at = random_point(rng);
      std::vector<double> p(std::size_t(count), 0.0);
      double sum = 0.0;
      for (int i = 0; i < count; ++i) {
        p[std::size_t(i)] = Choice::probability(table, at, std::uint32_t(i));
        CHECK(p[std::size_t(i)] >= 0.0);
        sum += p[std::size_t(i)];
      }
      INFO(count << " lamps, trial " << trial << ", probabilities sum to " << sum);
      // Each lamp is somewhere in the box, the point anywhere with any normal: some can be
      // wholly below the horizon, and sometimes all of them (with one or three lamps).
      if (sum == 0.0) {
        CHECK(Choice::choose(table, at, 0.5f).probability == 0.0f);
        continue;
      }
      CHECK(sum == Approx(1.0).epsilon(1e-5));
      std::vector<int> chosen(std::size_t(count), 0);
      for (int k = 0; k < kUs; ++k) {
        const float u = (float(k) + 0.5f) / float(kUs);
        const glint::EmitterLanes<float> c = Choice::choose(table, at, u);
        const auto index = std::size_t(c.sphere);
        REQUIRE(index < std::size_t(count));
        ++chosen[index];
        CHECK(c.probability == float(p[index]));
        CHECK(c.probability > 0.0f);
      }
      // The largest u, where u times the sum may round up to the sum: still an emitter with a
      // chance, and its own probability.
      const glint::EmitterLanes<float> last = Choice::choose(table, at, std::nextafter(1.0f, 0.0f));
      CHECK(last.probability > 0.0f);
      CHECK(last.probability == float(p[std::size_t(last.sphere)]));
      for (std::size_t i = 0; i < std::size_t(count); ++i) {
        INFO("lamp " << i << ": chosen " << chosen[i] << " times, probability " << p[i]);
        CHECK(std::abs(double(chosen[i]) - kUs * p[i]) <= 2.0);
      }
    }
  }
}

TEST_CASE(
    "emitter choice: by contribution, a lamp that can light the point has a chance, one wholly "
    "below its horizon none",
    "[emitters][unit]") {
  // Against the cone's highest direction worked out in double: clearly above the horizon means a
  // positive probability, clearly below means zero.
  glint::Pcg32 rng(12u, 4u);
  const EmitterTable table = scattered_lamps(60, 99u);
  int above = 0, below = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const EmitterChoicePoint<float> at = random_point(rng);
    for (std::uint32_t i = 0; i < table.size(); ++i) {
      const double highest = highest_cosine(at, table[i]);
      const float p = Choice::probability(table, at, i);
      INFO("lamp " << i << ", highest cosine " << highest << ", probability " << p);
      if (highest > 1e-4) {
        CHECK(p > 0.0f);
        ++above;
      } else if (highest < -1e-4) {
        CHECK(p == 0.0f);
        ++below;
      }
    }
  }
  // Both kinds were met many times.
  CHECK(above > 1000);
  CHECK(below > 1000);
}

TEST_CASE("emitter choice: by contribution, the point's own lamp and lamps around it",
          "[emitters][unit]") {
  // Two lamps: the point lies on lamp 0. Seen from its outside it can reach none of lamp 0, so
  // lamp 1 is the only choice; seen from its inside (the point lies inside the sphere's shell,
  // which it fills), lamp 0 fills the hemisphere: an estimate of one, against lamp 1's small
  // solid angle.
  const EmitterTable table(
      {{Vec3(0.0f), 1.0f, Color(2.0f), 0u}, {Vec3(0.0f, 10.0f, 0.0f), 0.5f, Color(2.0f), 1u}});
  const Vec3 top(0.0f, 1.0f, 0.0f);
  const EmitterChoicePoint<float> outside{top, top, 0u, false};
  CHECK(Choice::probability(table, outside, 0) == 0.0f);
  CHECK(Choice::probability(table, outside, 1) == 1.0f);
  const EmitterChoicePoint<float> inside{top, -top, 0u, true};
  CHECK(Choice::estimate(table, 0, inside) == 2.0f);     // its mean radiance times one
  CHECK(Choice::probability(table, inside, 1) == 0.0f);  // lamp 1 is behind the inner side
  // A point strictly inside a lamp (not on it) also sees all of it.
  const EmitterChoicePoint<float> within{Vec3(0.0f, 0.5f, 0.0f), top, kFloorSphere, false};
  CHECK(Choice::estimate(table, 0, within) == 2.0f);
}

TEST_CASE("emitter choice: by contribution, a two-sided point weighs lamps on either side",
          "[emitters][unit]") {
  // A lamp below the tangent plane gets nothing at a one-sided point facing up, and at a
  // two-sided point what it would get above: the estimate with |h| for h, whichever way the
  // normal points.
  const EmitterTable table({{Vec3(0.0f, 0.0f, -6.0f), 1.0f, Color(3.0f), 0u},
                            {Vec3(4.0f, 0.0f, 3.0f), 1.0f, Color(3.0f), 1u}});
  const Vec3 up(0.0f, 0.0f, 1.0f);
  const EmitterChoicePoint<float> one_sided{Vec3(0.0f), up, kFloorSphere, false};
  CHECK(Choice::estimate(table, 0, one_sided) == 0.0f);
  const EmitterChoicePoint<float> mirrored_lamp_above{Vec3(0.0f), -up, kFloorSphere, false};
  const float above = Choice::estimate(table, 0, mirrored_lamp_above);
  CHECK(above == Approx(3.0 * (1.0 / 36.0)).epsilon(1e-6));  // straight over: L (r/d)^2
  for (const Vec3& normal : {up, -up}) {
    const EmitterChoicePoint<float> two_sided{Vec3(0.0f), normal, kFloorSphere, false, true};
    CHECK(Choice::estimate(table, 0, two_sided) == above);
    CHECK(Choice::estimate(table, 1, two_sided) == Choice::estimate(table, 1, one_sided));
  }
}

TEST_CASE("emitter choice: by contribution, lamps weigh radiance times (r/d)^2 times elevation",
          "[emitters][unit]") {
  // Straight above, the estimate is the mean radiance times (r/d)^2, the solid angle of a small
  // sphere over pi; a lamp whose top just shows above the horizon weighs that times the sine of
  // its top's elevation. Worked out here in double.
  const Vec3 up(0.0f, 0.0f, 1.0f);
  const EmitterTable table({{Vec3(0.0f, 0.0f, 5.0f), 1.0f, Color(3.0f, 3.0f, 3.0f), 0u},
                            {Vec3(0.0f, 0.0f, 40.0f), 4.0f, Color(1.0f, 2.0f, 6.0f), 1u},
                            {Vec3(30.0f, 0.0f, -1.0f), 2.0f, Color(6.0f, 0.0f, 0.0f), 2u}});
  const EmitterChoicePoint<float> at{Vec3(0.0f), up, kFloorSphere, false};
  const double w0 = 3.0 * (1.0 / 25.0), w1 = 3.0 * (16.0 / 1600.0);
  const double d2 = std::sqrt(30.0 * 30.0 + 1.0);
  const double w2 = 2.0 * (4.0 / (d2 * d2)) * (1.0 / d2);  // its top is 1 above the plane
  CHECK(Choice::estimate(table, 0, at) == Approx(w0).epsilon(1e-6));
  CHECK(Choice::estimate(table, 1, at) == Approx(w1).epsilon(1e-6));
  CHECK(Choice::estimate(table, 2, at) == Approx(w2).epsilon(1e-5));
  CHECK(Choice::probability(table, at, 0) == Approx(w0 / (w0 + w1 + w2)).epsilon(1e-5));
  // By power the far lamp, sixteen times the area of the near one, would be chosen more often.
  CHECK(table.probability(1) > 2.0f * table.probability(0));
}

TEMPLATE_TEST_CASE_SIG("emitter choice: by contribution, every width chooses what one lane does",
                       "[emitters][unit][lanes]", ((int W), W), 8, 16) {
  using F = glint::Float<W>;
  glint::Pcg32 rng(13u, 6u);
  for (const int count : {60, 150}) {
    const EmitterTable table = scattered_lamps(count, 7u);
    for (int round = 0; round < 64; ++round) {
      EmitterChoicePoint<F> at;
      F u;
      std::vector<EmitterChoicePoint<float>> points;
      for (int i = 0; i < W; ++i) {
        EmitterChoicePoint<float> p = random_point(rng);
        // Some lanes on lamp 3, from either side.
        if (i % 5 == 0) {
          p.sphere = 3;
          p.from_inside = i % 2 == 0;
        }
        points.push_back(p);
        at.point.set_lane(i, p.point);
        at.normal.set_lane(i, p.normal);
        at.sphere[i] = p.sphere;
        at.from_inside[i] = p.from_inside ? -1 : 0;
        u[i] = rng.next_float();
      }
      const glint::EmitterLanes<F> chosen = Choice::choose(table, at, u);
      for (int i = 0; i < W; ++i) {
        const glint::EmitterLanes<float> one = Choice::choose(table, points[std::size_t(i)], u[i]);
        INFO("round " << round << ", lane " << i);
        CHECK(chosen.sphere[i] == one.sphere);
        CHECK(chosen.probability[i] == one.probability);
        CHECK(chosen.center.lane(i) == one.center);
        CHECK(chosen.radius[i] == one.radius);
        CHECK(chosen.radiance.lane(i) == one.radiance);
      }
    }
  }
}
