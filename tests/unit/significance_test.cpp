// The significance tests the statistical tests rest on, against values of Student's t
// distribution from its closed forms (one and two degrees of freedom) and from tables, and
// Holm's procedure on families whose outcome follows from its definition.

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "../support/significance.hpp"

using glint_test::student_t_two_sided;

TEST_CASE("Student's t two-sided tail: closed forms and tables", "[statistics]") {
  // One degree of freedom (Cauchy): P(|T| >= t) = 1 - 2 atan(t) / pi.
  for (const double t : {0.1, 1.0, 3.0, 50.0, 1e4})
    CHECK(student_t_two_sided(t, 1.0) == Approx(1.0 - 2.0 * std::atan(t) / M_PI).epsilon(1e-10));
  // Two: P(|T| >= t) = 1 - t / sqrt(2 + t^2).
  for (const double t : {0.1, 1.0, 3.0, 50.0, 1e3})
    CHECK(student_t_two_sided(t, 2.0) == Approx(1.0 - t / std::sqrt(2.0 + t * t)).epsilon(1e-10));
  // Tables: t(0.975; 10) = 2.228139, t(0.9995; 30) = 3.645959.
  CHECK(student_t_two_sided(2.228139, 10.0) == Approx(0.05).epsilon(1e-5));
  CHECK(student_t_two_sided(3.645959, 30.0) == Approx(0.001).epsilon(1e-5));
  // Many degrees of freedom: the normal tail, 2 Phi(-5) = 5.733031e-7.
  CHECK(student_t_two_sided(5.0, 1e8) == Approx(5.733031e-7).epsilon(1e-5));
  CHECK(student_t_two_sided(0.0, 7.0) == 1.0);
  CHECK(student_t_two_sided(-2.228139, 10.0) == Approx(0.05).epsilon(1e-5));
}

TEST_CASE("Welch's test: noise-free estimates and the rounding allowance", "[statistics]") {
  const glint_test::MeanEstimate a{1.0, 0.0, 31.0};
  const glint_test::MeanEstimate b{1.00005, 0.0, 31.0};
  CHECK(glint_test::welch_p_value(a, b, 1e-4) == 1.0);
  CHECK(glint_test::welch_p_value(a, b, 1e-6) == 0.0);
  // Equal standard errors and degrees of freedom: t = d / (se sqrt 2), 2 (n - 1) degrees.
  const glint_test::MeanEstimate c{1.0, 0.1, 31.0};
  const glint_test::MeanEstimate d{1.0 + 0.1 * std::sqrt(2.0) * 2.0, 0.1, 31.0};
  CHECK(glint_test::welch_p_value(c, d, 0.0) == Approx(student_t_two_sided(2.0, 62.0)));
}

TEST_CASE("Holm's procedure judges a family at its level", "[statistics]") {
  const double alpha = glint_test::kFamilyFalseAlarm;
  glint_test::ComparisonFamily family;
  for (int i = 0; i < 99; ++i)
    family.add("large", 0.5);
  CHECK(family.rejected().empty());
  // One p-value just above alpha / m is kept, just below it is rejected.
  family.add("borderline", 1.01 * alpha / 100.0);
  CHECK(family.rejected().empty());
  glint_test::ComparisonFamily failing;
  for (int i = 0; i < 99; ++i)
    failing.add("large", 0.5);
  failing.add("small", 0.99 * alpha / 100.0);
  REQUIRE(failing.rejected().size() == 1);
  CHECK(failing.rejected().front().rfind("small", 0) == 0);
  // Step-down: once the smallest is rejected, the next is judged against alpha / (m - 1).
  glint_test::ComparisonFamily two;
  two.add("a", 0.4 * alpha);
  two.add("b", 0.9 * alpha);
  CHECK(two.rejected().size() == 2);
  glint_test::ComparisonFamily stops;
  stops.add("a", 0.6 * alpha);
  stops.add("b", 0.6 * alpha);
  CHECK(stops.rejected().empty());
}
