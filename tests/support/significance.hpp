#pragma once
// Significance tests shared by the statistical tests, and the suite's false-alarm budget.
//
// Each statistical test case of the render family is one family of comparisons: it collects
// the p-value of every comparison it makes (a block of an image, a whole image, a seed-paired
// difference) and judges them together with Holm's step-down procedure at the level
// kFamilyFalseAlarm. So a correct renderer fails a test case with probability at most
// kFamilyFalseAlarm whatever the number of comparisons in it, and the whole suite, which has at
// most kComparisonFamilies such test cases (a test counts them), with probability at most
// kSuiteFalseAlarm. The p-values come from Student's t distribution with the degrees of freedom
// of the estimate (Welch's for two independent estimates), not from a normal approximation,
// which a handful of seeds would make far too optimistic. (The unit family's distribution tests
// are judged one by one, each at about 1e-6: unit/statistics.hpp.)

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace glint_test {

/// The probability that a correct build fails any statistical comparison of the suite.
inline constexpr double kSuiteFalseAlarm = 1e-3;
/// An upper bound on the number of comparison families (statistical test cases) in the suite;
/// `statistical comparisons: the families fit the suite's false-alarm budget` checks it.
inline constexpr int kComparisonFamilies = 64;
/// The level at which each family is judged.
inline constexpr double kFamilyFalseAlarm = kSuiteFalseAlarm / kComparisonFamilies;

/// I_x(a, b), the regularised incomplete beta function. The continued fraction converges
/// quickly for x < (a + 1) / (a + b + 2); the other side follows from I_x(a, b) =
/// 1 - I_{1-x}(b, a). Evaluated with the modified Lentz method.
inline double regularized_incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  if (x > (a + 1.0) / (a + b + 2.0)) return 1.0 - regularized_incomplete_beta(b, a, 1.0 - x);
  const double log_front =
      a * std::log(x) + b * std::log1p(-x) - (std::lgamma(a) + std::lgamma(b) - std::lgamma(a + b));
  // I_x(a, b) = front / (a K), K = 1 + d1 / (1 + d2 / (1 + ...)), the numerators alternating
  // between d(2m+1) = -(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1)) and
  // d(2m) = m (b - m) x / ((a + 2m - 1)(a + 2m)).
  constexpr double kTiny = 1e-300;
  double k = 1.0;
  double c = 1.0;
  double d = 0.0;
  for (int j = 1; j <= 1000; ++j) {
    const double m = double(j / 2);
    const double numerator =
        j % 2 == 1 ? -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0))
                   : m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m));
    d = 1.0 + numerator * d;
    d = 1.0 / (std::abs(d) < kTiny ? kTiny : d);
    c = 1.0 + numerator / c;
    if (std::abs(c) < kTiny) c = kTiny;
    k *= c * d;
    if (std::abs(c * d - 1.0) < 1e-15) break;
  }
  return std::exp(log_front) / (a * k);
}

/// P(|T| >= |t|) for Student's t distribution with `dof` degrees of freedom.
inline double student_t_two_sided(double t, double dof) {
  if (!std::isfinite(t)) return std::isnan(t) ? 1.0 : 0.0;
  return regularized_incomplete_beta(0.5 * dof, 0.5, dof / (dof + t * t));
}

/// A mean estimated from n independent values: its standard error and degrees of freedom.
struct MeanEstimate {
  double mean = 0.0;
  double standard_error = 0.0;
  double degrees_of_freedom = 0.0;  ///< n - 1
};

inline MeanEstimate estimate_mean(const std::vector<double>& values) {
  const double n = double(values.size());
  double sum = 0.0;
  for (const double v : values)
    sum += v;
  const double mean = sum / n;
  double squares = 0.0;
  for (const double v : values)
    squares += (v - mean) * (v - mean);
  return {mean, std::sqrt(squares / (n - 1.0) / n), n - 1.0};
}

/// Two-sided p-value of Welch's test that two independent estimates have the same expectation.
/// A difference within `rounding` is not evidence (two renderers may add the same light in
/// another order); where neither estimate has noise, any larger difference is (p = 0).
inline double welch_p_value(const MeanEstimate& a, const MeanEstimate& b, double rounding) {
  const double excess = std::max(0.0, std::abs(a.mean - b.mean) - rounding);
  const double va = a.standard_error * a.standard_error;
  const double vb = b.standard_error * b.standard_error;
  if (va + vb == 0.0) return excess > 0.0 ? 0.0 : 1.0;
  const double dof =
      (va + vb) * (va + vb) / (va * va / a.degrees_of_freedom + vb * vb / b.degrees_of_freedom);
  return student_t_two_sided(excess / std::sqrt(va + vb), dof);
}

/// Two-sided p-value of the test that values (paired differences) have expectation zero.
inline double zero_mean_p_value(const MeanEstimate& difference, double rounding) {
  const double excess = std::max(0.0, std::abs(difference.mean) - rounding);
  if (difference.standard_error == 0.0) return excess > 0.0 ? 0.0 : 1.0;
  return student_t_two_sided(excess / difference.standard_error, difference.degrees_of_freedom);
}

/// One-sided p-value of the test that values (differences from a bound) have expectation at most
/// zero: evidence only of an expectation above the bound by more than `rounding`.
inline double above_zero_p_value(const MeanEstimate& difference, double rounding) {
  const double excess = std::max(0.0, difference.mean - rounding);
  if (excess == 0.0) return 1.0;
  if (difference.standard_error == 0.0) return 0.0;
  return 0.5 *
         student_t_two_sided(excess / difference.standard_error, difference.degrees_of_freedom);
}

/// The comparisons of one statistical test case, judged together by Holm's step-down procedure
/// at kFamilyFalseAlarm: sorted by p-value, the i-th smallest (from 0) of m fails when it and
/// every smaller one are below kFamilyFalseAlarm / (m - i).
class ComparisonFamily {
 public:
  /// Records one comparison: what it was (for the failure message) and its p-value.
  void add(std::string what, double p_value) { comparisons_.push_back({p_value, std::move(what)}); }

  std::size_t size() const { return comparisons_.size(); }

  /// The comparisons the procedure rejects, most significant first.
  std::vector<std::string> rejected() const {
    std::vector<std::pair<double, std::string>> sorted = comparisons_;
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto& l, const auto& r) { return l.first < r.first; });
    std::vector<std::string> out;
    const double m = double(sorted.size());
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      if (!(sorted[i].first <= kFamilyFalseAlarm / (m - double(i)))) break;
      std::ostringstream line;
      line << sorted[i].second << " (p = " << sorted[i].first << ")";
      out.push_back(line.str());
    }
    return out;
  }

  /// CHECKs that the family holds, naming every rejected comparison.
  void check() const {
    const std::vector<std::string> failures = rejected();
    std::ostringstream message;
    message << failures.size() << " of " << comparisons_.size()
            << " comparisons rejected at family level " << kFamilyFalseAlarm;
    for (const std::string& f : failures)
      message << "\n  " << f;
    INFO(message.str());
    CHECK(failures.empty());
  }

 private:
  std::vector<std::pair<double, std::string>> comparisons_;
};

}  // namespace glint_test
