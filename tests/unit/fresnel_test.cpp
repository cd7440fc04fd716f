// Fresnel policies against values worked out independently: the normal-incidence reflectance
// ((n1 - n2) / (n1 + n2))^2, the critical and Brewster angles, and the textbook sine/tangent
// forms of the Fresnel equations, rs = -sin(ti - tt) / sin(ti + tt), rp = tan(ti - tt) /
// tan(ti + tt), evaluated in double precision.

#include <catch2/catch.hpp>
#include <cmath>

#include "../support/float_values.hpp"
#include "glint/policy/fresnel.hpp"

namespace {

using glint_test::kDegree;

/// Unpolarised reflectance from the sine and tangent forms (valid for 0 < ti < critical).
double textbook_reflectance(double incident_angle, double n1, double n2) {
  const double sin_t = n1 / n2 * std::sin(incident_angle);
  if (sin_t >= 1.0) return 1.0;
  const double tt = std::asin(sin_t);
  const double rs = -std::sin(incident_angle - tt) / std::sin(incident_angle + tt);
  const double rp = std::tan(incident_angle - tt) / std::tan(incident_angle + tt);
  return 0.5 * (rs * rs + rp * rp);
}

float cosine(double angle) {
  return static_cast<float>(std::cos(angle));
}

}  // namespace

TEST_CASE("ExactFresnel: normal incidence", "[fresnel]") {
  // ((1.5 - 1) / (1.5 + 1))^2 = (0.5 / 2.5)^2 = 0.04, entering or leaving the glass.
  CHECK(glint::ExactFresnel::reflectance(1.0f, 1.0f, 1.5f) == Approx(0.04).epsilon(1e-6));
  CHECK(glint::ExactFresnel::reflectance(1.0f, 1.5f, 1.0f) == Approx(0.04).epsilon(1e-6));
  // Water to diamond: ((1.33 - 2.42) / 3.75)^2.
  CHECK(glint::ExactFresnel::reflectance(1.0f, 1.33f, 2.42f) ==
        Approx(std::pow(1.09 / 3.75, 2)).epsilon(1e-5));
  // Matched indices: no interface, no reflection at any angle.
  for (const double degrees : {0.0, 30.0, 60.0, 89.0})
    CHECK(glint::ExactFresnel::reflectance(cosine(degrees * kDegree), 1.5f, 1.5f) ==
          Approx(0.0).margin(1e-6));
}

TEST_CASE("ExactFresnel: total internal reflection beyond the critical angle", "[fresnel]") {
  const double critical = std::asin(1.0 / 1.5);  // 41.81 degrees
  CHECK(critical / kDegree == Approx(41.8103).epsilon(1e-5));
  for (const double beyond : {0.01, 0.5, 5.0, 20.0, 48.0}) {
    INFO("critical angle + " << beyond << " degrees");
    CHECK(glint::ExactFresnel::reflectance(cosine(critical + beyond * kDegree), 1.5f, 1.0f) ==
          1.0f);
  }
  // Just inside the critical angle light still gets out, and reflectance rises steeply to 1.
  const float below =
      glint::ExactFresnel::reflectance(cosine(critical - 0.5 * kDegree), 1.5f, 1.0f);
  CHECK(below < 1.0f);
  CHECK(below == Approx(textbook_reflectance(critical - 0.5 * kDegree, 1.5, 1.0)).epsilon(1e-3));
  // From the lighter side there is no critical angle.
  for (const double degrees : {45.0, 60.0, 80.0, 89.0})
    CHECK(glint::ExactFresnel::reflectance(cosine(degrees * kDegree), 1.0f, 1.5f) < 1.0f);
}

TEST_CASE("ExactFresnel: Brewster's angle reflects only s-polarised light", "[fresnel]") {
  // At tan(theta_B) = n2/n1 the reflected and refracted rays are perpendicular, rp = 0 and
  // R = rs^2 / 2 with rs = -sin(ti - tt) = -cos(2 ti) since tt = 90 deg - ti.
  for (const auto& [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 2.0}}) {
    const double brewster = std::atan(n2 / n1);
    const double rs = -std::cos(2.0 * brewster);
    INFO("n1 " << n1 << ", n2 " << n2 << ", Brewster angle " << brewster / kDegree);
    CHECK(glint::ExactFresnel::reflectance(cosine(brewster), float(n1), float(n2)) ==
          Approx(0.5 * rs * rs).epsilon(1e-4));
  }
  // For glass from air: theta_B = 56.31 degrees, rs^2/2 = 0.0739.
  CHECK(glint::ExactFresnel::reflectance(cosine(std::atan(1.5)), 1.0f, 1.5f) ==
        Approx(0.07396).epsilon(1e-3));
}

TEST_CASE("ExactFresnel: grazing incidence reflects everything", "[fresnel]") {
  CHECK(glint::ExactFresnel::reflectance(0.0f, 1.0f, 1.5f) == Approx(1.0).epsilon(1e-6));
  CHECK(glint::ExactFresnel::reflectance(1e-3f, 1.0f, 1.5f) > 0.99f);
  CHECK(glint::ExactFresnel::reflectance(0.0f, 1.5f, 1.0f) == 1.0f);
  // Out-of-range cosines are clamped, not turned into NaN.
  CHECK(glint::ExactFresnel::reflectance(-0.1f, 1.0f, 1.5f) == Approx(1.0).epsilon(1e-6));
  CHECK(glint::ExactFresnel::reflectance(1.0001f, 1.0f, 1.5f) == Approx(0.04).epsilon(1e-5));
}

TEST_CASE("ExactFresnel: the textbook formula over all angles, both ways", "[fresnel]") {
  for (int step = 1; step < 900; ++step) {
    const double angle = step * 0.1 * kDegree;
    INFO(step * 0.1 << " degrees");
    const double entering = textbook_reflectance(angle, 1.0, 1.5);
    CHECK(glint::ExactFresnel::reflectance(cosine(angle), 1.0f, 1.5f) ==
          Approx(entering).margin(2e-5));
    const double leaving = textbook_reflectance(angle, 1.5, 1.0);
    CHECK(glint::ExactFresnel::reflectance(cosine(angle), 1.5f, 1.0f) ==
          Approx(leaving).margin(2e-4));  // steep near the critical angle
    // Reciprocity: light leaving at the refraction angle sees the same reflectance (steep
    // near the critical angle, where the float cosine carries more of the error).
    const double refracted = std::asin(std::sin(angle) / 1.5);
    CHECK(glint::ExactFresnel::reflectance(cosine(refracted), 1.5f, 1.0f) ==
          Approx(entering).margin(2e-4));
  }
}

TEST_CASE("SchlickFresnel: R0 at normal incidence, lower-index-side cosine", "[fresnel]") {
  CHECK(glint::SchlickFresnel::reflectance(1.0f, 1.0f, 1.5f) == Approx(0.04).epsilon(1e-6));
  CHECK(glint::SchlickFresnel::reflectance(1.0f, 1.5f, 1.0f) == Approx(0.04).epsilon(1e-6));
  CHECK(glint::SchlickFresnel::reflectance(0.0f, 1.0f, 1.5f) == Approx(1.0).epsilon(1e-6));

  SECTION("total internal reflection from inside") {
    const double critical = std::asin(1.0 / 1.5);
    for (const double beyond : {0.01, 1.0, 10.0, 45.0})
      CHECK(glint::SchlickFresnel::reflectance(cosine(critical + beyond * kDegree), 1.5f, 1.0f) ==
            1.0f);
  }
  SECTION("from inside it equals the outside value at the refraction angle") {
    // Using the cosine on the air side makes Schlick reciprocal like the exact formula; the
    // incident-side cosine would give ~0.04-0.1 just below the critical angle instead of ~1.
    for (int step = 1; step < 900; ++step) {
      const double outside_angle = step * 0.1 * kDegree;
      const double inside_angle = std::asin(std::sin(outside_angle) / 1.5);
      INFO("outside " << step * 0.1 << " degrees");
      CHECK(glint::SchlickFresnel::reflectance(cosine(inside_angle), 1.5f, 1.0f) ==
            Approx(glint::SchlickFresnel::reflectance(cosine(outside_angle), 1.0f, 1.5f))
                .margin(2e-4));
    }
    const double near_critical = std::asin(1.0 / 1.5) - 0.01 * kDegree;
    CHECK(glint::SchlickFresnel::reflectance(cosine(near_critical), 1.5f, 1.0f) > 0.8f);
  }
  SECTION("close to the exact reflectance") {
    // Schlick's error for glass is largest near grazing incidence (about 0.036 at 85 degrees)
    // and small below 45 degrees.
    for (int step = 0; step <= 900; ++step) {
      const double angle = step * 0.1 * kDegree;
      const double exact = textbook_reflectance(std::max(angle, 1e-6), 1.0, 1.5);
      const double schlick = glint::SchlickFresnel::reflectance(cosine(angle), 1.0f, 1.5f);
      INFO(step * 0.1 << " degrees: exact " << exact << ", Schlick " << schlick);
      CHECK(std::abs(schlick - exact) <= (angle <= 45.0 * kDegree ? 0.01 : 0.04));
    }
  }
}

TEST_CASE("NoFresnel never reflects", "[fresnel]") {
  STATIC_REQUIRE_FALSE(glint::NoFresnel::enabled);
  STATIC_REQUIRE(glint::ExactFresnel::enabled);
  STATIC_REQUIRE(glint::SchlickFresnel::enabled);
  for (const float c : {0.0f, 0.3f, 1.0f})
    for (const auto& [n1, n2] : {std::pair{1.0f, 1.5f}, std::pair{1.5f, 1.0f}})
      CHECK(glint::NoFresnel::reflectance(c, n1, n2) == 0.0f);
}
