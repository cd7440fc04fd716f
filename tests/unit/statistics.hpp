#pragma once
// Small statistical helpers for the unit tests: chi-square and Kolmogorov-Smirnov tests whose
// thresholds follow from the sample count and a fixed false-alarm probability of about 1e-6,
// so that a correct sampler with a fixed seed passes with a wide margin and a wrong density
// fails by orders of magnitude.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace glint::test {

/// z-score of the one-sided tail used for every threshold: P(Z > 4.75) ~ 1e-6.
inline constexpr double kTailZ = 4.75;

/// The chi-square value exceeded with probability ~1e-6 (Wilson-Hilferty approximation).
inline double chi_square_threshold(int degrees_of_freedom) {
  const double k = degrees_of_freedom;
  const double a = 2.0 / (9.0 * k);
  const double cube_root = 1.0 - a + kTailZ * std::sqrt(a);
  return k * cube_root * cube_root * cube_root;
}

/// Counts values into `bins` equally likely bins, given the hypothesised CDF; returns the
/// chi-square statistic (bins - 1 degrees of freedom).
template <typename Cdf>
double chi_square_equiprobable(const std::vector<double>& values, int bins, Cdf cdf) {
  std::vector<double> counts(std::size_t(bins), 0.0);
  for (const double v : values) {
    const double p = cdf(v);
    const int bin = std::clamp(static_cast<int>(p * bins), 0, bins - 1);
    counts[std::size_t(bin)] += 1.0;
  }
  const double expected = double(values.size()) / bins;
  double chi2 = 0.0;
  for (const double c : counts)
    chi2 += (c - expected) * (c - expected) / expected;
  return chi2;
}

/// A chi-square statistic and its degrees of freedom.
struct ChiSquare {
  double statistic = 0.0;
  int degrees_of_freedom = 0;
  bool rejected() const { return statistic > chi_square_threshold(degrees_of_freedom); }
};

/// Pearson's chi-square of observed against expected counts (the same total), the cells whose
/// expectation is below `least_expected` pooled into one, as pbrt-v4's and Mitsuba 3's sampling
/// tests pool them, so that the statistic keeps its distribution.
inline ChiSquare chi_square_pooled(const std::vector<double>& observed,
                                   const std::vector<double>& expected,
                                   double least_expected = 5.0) {
  ChiSquare result;
  double pooled_observed = 0.0, pooled_expected = 0.0;
  int cells = 0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < least_expected) {
      pooled_observed += observed[i];
      pooled_expected += expected[i];
      continue;
    }
    const double d = observed[i] - expected[i];
    result.statistic += d * d / expected[i];
    ++cells;
  }
  if (pooled_expected > 0.0) {
    const double d = pooled_observed - pooled_expected;
    result.statistic += d * d / pooled_expected;
    ++cells;
  } else if (pooled_observed > 0.0) {
    // Samples where the density says none can be: no chi-square can pass that.
    result.statistic = INFINITY;
  }
  result.degrees_of_freedom = std::max(cells - 1, 1);
  return result;
}

/// Kolmogorov-Smirnov distance between the sample and the hypothesised CDF.
template <typename Cdf>
double kolmogorov_smirnov(std::vector<double> values, Cdf cdf) {
  std::sort(values.begin(), values.end());
  const double n = double(values.size());
  double distance = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double f = cdf(values[i]);
    distance = std::max({distance, f - double(i) / n, double(i + 1) / n - f});
  }
  return distance;
}

/// The KS distance exceeded with probability ~1e-6 for n samples: sqrt(ln(2/alpha) / 2n).
inline double kolmogorov_smirnov_threshold(std::size_t n) {
  return std::sqrt(std::log(2.0 / 1e-6) / (2.0 * double(n)));
}

inline double standard_normal_cdf(double x) {
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

struct Moments {
  double mean = 0.0;
  double variance = 0.0;  ///< unbiased
};

inline Moments moments(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values)
    sum += v;
  const double mean = sum / double(values.size());
  double squares = 0.0;
  for (const double v : values)
    squares += (v - mean) * (v - mean);
  return {mean, squares / double(values.size() - 1)};
}

}  // namespace glint::test
