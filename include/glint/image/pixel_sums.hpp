#pragma once
// Per-pixel running sums of a render's samples, kept between passes (and in checkpoints) and
// divided once at the end. They are double: a float sum of a million samples of a constant
// drifts by about 1% (each addition rounds to 24 bits of a growing total), and a float sum of
// large finite samples overflows to infinity where their mean would be finite. A double sum of
// finite float samples cannot overflow (a float is below 2^128 and a pixel has at most 2^20
// samples), so a render's means are finite floats. Only sums from elsewhere (a forged checkpoint)
// can have a mean beyond the float range: mean_color clamps it and says so.
//
// A render whose estimator splats (light paths connected to the camera: render/light_tracing.hpp)
// also keeps a SplatSums layer of the same size, summed into each pixel's sum when the image is
// made. A pixel's value is then (its samples' sum + its splats' sum) / samples per pixel.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "glint/image/film.hpp"
#include "glint/image/splat_sums.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

using ColorSum = glm::dvec3;

class PixelSums {
 public:
  PixelSums() = default;
  /// Sums of width x height pixels, with a layer of splats if `with_splats`.
  PixelSums(int width, int height, bool with_splats = false)
      : width_(width),
        height_(height),
        sums_(std::size_t(width) * std::size_t(height), ColorSum(0.0)),
        splats_(with_splats ? SplatSums(width, height) : SplatSums()) {}

  int width() const { return width_; }
  int height() const { return height_; }
  ColorSum& at(int x, int y) {
    return sums_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
  }
  const ColorSum& at(int x, int y) const {
    return sums_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
  }
  const std::vector<ColorSum>& pixels() const { return sums_; }

  bool has_splats() const { return !splats_.empty(); }
  /// The splats' layer; empty() unless made with splats.
  SplatSums& splats() { return splats_; }
  const SplatSums& splats() const { return splats_; }

  /// The sum of pixel (x, y)'s samples and splats.
  ColorSum total(int x, int y) const {
    return has_splats() ? at(x, y) + splats_.at(x, y) : at(x, y);
  }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<ColorSum> sums_;
  SplatSums splats_;
};

/// The mean of `samples` samples whose sum is `sum`, as a float colour. A component beyond the
/// largest float becomes the largest float, never infinity, and sets `out_of_range`.
inline Color mean_color(const ColorSum& sum, int samples, bool& out_of_range) {
  const ColorSum mean = sum / double(samples);
  constexpr double kLargest = std::numeric_limits<float>::max();
  Color color;
  for (int c = 0; c < 3; ++c) {
    // Rounding to float carries values a little above kLargest to infinity: clamp first.
    const bool beyond = !(std::abs(mean[c]) <= kLargest);
    out_of_range = out_of_range || beyond;
    color[c] = float(beyond ? std::copysign(kLargest, mean[c]) : mean[c]);
  }
  return color;
}

/// The image of per-pixel sums of `samples` samples each, and how many of its pixels had a
/// mean beyond the float range (clamped to the largest float; see mean_color).
struct MeanImage {
  Film film;
  std::uint64_t clamped_pixels = 0;
};

inline MeanImage mean_image(const PixelSums& sums, int samples) {
  MeanImage image{Film(sums.width(), sums.height()), 0};
  for (int y = 0; y < sums.height(); ++y)
    for (int x = 0; x < sums.width(); ++x) {
      bool out_of_range = false;
      image.film.at(x, y) = mean_color(sums.total(x, y), samples, out_of_range);
      image.clamped_pixels += out_of_range ? 1 : 0;
    }
  return image;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
