#pragma once
// Sampling in proportion to a table of non-negative weights: a piecewise-constant density on
// [0, 1) (one value per equal-width bin) and on the unit square (a row of bins per line, a line
// chosen by its row's total, then a bin of the row). The tables are summed in double when built,
// so the cumulative sums of a long row do not drift; sampling is a binary search and the density
// a lookup. An environment light draws its directions from one (scene/environment.hpp).
//
// A table of zeros is sampled uniformly, so that every table gives a density that integrates to
// one; a bin of weight zero is never drawn.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A density on [0, 1) that is constant on each of n equal bins, in proportion to the weights.
class PiecewiseConstant1D {
 public:
  struct Sample {
    float x;    ///< in [0, 1)
    float pdf;  ///< the density at x
    std::size_t bin;
  };

  PiecewiseConstant1D() = default;
  /// `weights`: one or more finite, non-negative values.
  explicit PiecewiseConstant1D(std::span<const double> weights) {
    const std::size_t n = weights.size();
    double total = 0.0;
    for (const double w : weights)
      total += w;
    const bool uniform = !(total > 0.0);
    if (uniform) total = double(n);
    // The mean weight, by which a bin's weight is its density.
    integral_ = total / double(n);
    density_.resize(n);
    cdf_.resize(n + 1);
    cdf_[0] = 0.0f;
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double w = uniform ? 1.0 : weights[i];
      density_[i] = float(w / integral_);
      sum += w;
      cdf_[i + 1] = i + 1 == n ? 1.0f : float(sum / total);
    }
  }

  std::size_t size() const { return density_.size(); }
  /// The mean of the weights (of ones for a table of zeros): a row's share of a 2D table.
  double integral() const { return integral_; }

  /// The point for a uniform number u in [0, 1): in the bin whose cumulative range holds u, as
  /// far into it as u is into that range.
  Sample sample(float u) const {
    // The last bin whose cumulative start is at most u; its range is not empty, since u lies in
    // it.
    const auto upper = std::upper_bound(cdf_.begin() + 1, cdf_.end() - 1, u);
    const auto bin = std::size_t(upper - cdf_.begin()) - 1;
    const float start = cdf_[bin], width = cdf_[bin + 1] - start;
    const float within = width > 0.0f ? std::clamp((u - start) / width, 0.0f, 1.0f) : 0.0f;
    const float x = std::min((float(bin) + within) / float(size()), kBelowOne);
    return {x, density_[bin], bin};
  }

  /// The density at x in [0, 1].
  float pdf(float x) const { return density_[bin_of(x)]; }
  /// The density of bin `bin`.
  float bin_pdf(std::size_t bin) const { return density_[bin]; }
  /// The bin that holds x in [0, 1] (the last for x = 1).
  std::size_t bin_of(float x) const {
    const float scaled = x * float(size());
    return scaled >= float(size()) ? size() - 1 : scaled > 0.0f ? std::size_t(scaled) : 0;
  }

 private:
  static constexpr float kBelowOne = 0x1.fffffep-1f;

  std::vector<float> density_;
  std::vector<float> cdf_;  ///< n + 1 values from 0 to exactly 1
  double integral_ = 0.0;
};

/// A density on the unit square, constant on each of width x height equal cells, in proportion to
/// the weights (row by row, row 0 at v = 0): v from the rows' totals, then u from the row's.
class PiecewiseConstant2D {
 public:
  struct Sample {
    Vec2 uv;    ///< in [0, 1)^2
    float pdf;  ///< the density at uv, per unit area of the square
  };

  PiecewiseConstant2D() = default;
  /// `weights`: width x height finite, non-negative values, row by row.
  PiecewiseConstant2D(std::span<const double> weights, std::size_t width, std::size_t height) {
    rows_.reserve(height);
    std::vector<double> row_totals(height);
    for (std::size_t y = 0; y < height; ++y) {
      rows_.emplace_back(weights.subspan(y * width, width));
      double total = 0.0;
      for (const double w : weights.subspan(y * width, width))
        total += w;
      row_totals[y] = total;
    }
    lines_ = PiecewiseConstant1D(row_totals);
  }

  std::size_t width() const { return rows_.empty() ? 0 : rows_.front().size(); }
  std::size_t height() const { return rows_.size(); }

  Sample sample(const Vec2& u) const {
    const PiecewiseConstant1D::Sample line = lines_.sample(u.y);
    const PiecewiseConstant1D::Sample cell = rows_[line.bin].sample(u.x);
    return {{cell.x, line.x}, line.pdf * cell.pdf};
  }

  /// The density at uv in [0, 1]^2.
  float pdf(const Vec2& uv) const {
    const std::size_t line = lines_.bin_of(uv.y);
    return lines_.bin_pdf(line) * rows_[line].pdf(uv.x);
  }

 private:
  std::vector<PiecewiseConstant1D> rows_;
  PiecewiseConstant1D lines_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
