#pragma once
// Per-pixel sums of splats: light that a path brings to a pixel other than its own (a light
// path connected to the camera lands anywhere on the film). Any thread may add to any pixel at
// any time, so the sums must not depend on the order of the additions: each value is held in
// fixed point, as two integers, and integer addition is associative. So the same splats give the
// same bits whatever the threads, tiles, passes or processes that add them, with one atomic
// addition per integer and no lock.
//
// A value v is split into coarse = round(v * 2^kCoarseBits) and fine = round((v - coarse *
// 2^-kCoarseBits) * 2^kFineBits): the coarse part holds magnitudes up to 2^(63 - kCoarseBits),
// the fine part what the coarse grid rounds away, to 2^-kFineBits. A pixel's sum is exact to
// 2^-kFineBits per splat (about 1e-17), far below a float's rounding of any splat. A splat whose
// magnitude is not below kLargestSplat, or is not finite, is refused (the caller counts it as an
// invalid sample), so that no sum can overflow before a pixel has had 2^(63 - kCoarseBits) /
// kLargestSplat = 2^15 of the largest ones.

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/math/vector.hpp"

namespace glint {

class SplatSums {
 public:
  static constexpr int kCoarseBits = 16;
  static constexpr int kFineBits = 56;
  static constexpr double kLargestSplat = 4294967296.0;  // 2^32
  /// 2^kCoarseBits and 2^kFineBits.
  static constexpr double kCoarseScale = double(std::uint64_t(1) << kCoarseBits);
  static constexpr double kFineScale = double(std::uint64_t(1) << kFineBits);

  SplatSums() = default;
  SplatSums(int width, int height)
      : width_(width),
        height_(height),
        words_(std::size_t(width) * std::size_t(height) * kWordsPerPixel, 0) {}

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return words_.empty(); }

  /// Whether `value` can be splatted: every channel finite and below kLargestSplat in magnitude.
  static bool representable(const Color& value) {
    for (int c = 0; c < 3; ++c)
      if (!(std::fabs(double(value[c])) < kLargestSplat)) return false;
    return true;
  }

  /// Adds `value` to pixel (x, y), from any thread. Requires representable(value).
  void add(int x, int y, const Color& value) {
    std::int64_t* pixel = words_.data() + index(x, y);
    for (int c = 0; c < 3; ++c) {
      if (value[c] == 0.0f) continue;
      const double v = double(value[c]);
      // Every product is exact in double (scaling by a power of two, and the difference of v
      // and its coarse rounding is a multiple of v's last place, below 2^-kCoarseBits). A locked
      // addition is the cost of a splat: none for a word that would add zero.
      const double coarse = std::nearbyint(v * kCoarseScale);
      const double rest = v - coarse * (1.0 / kCoarseScale);
      const double fine = std::nearbyint(rest * kFineScale);
      if (coarse != 0.0)
        std::atomic_ref<std::int64_t>(pixel[2 * c])
            .fetch_add(std::int64_t(coarse), std::memory_order_relaxed);
      if (fine != 0.0)
        std::atomic_ref<std::int64_t>(pixel[2 * c + 1])
            .fetch_add(std::int64_t(fine), std::memory_order_relaxed);
    }
  }

  /// Adds every pixel of `other` (of the same size) to this one: the sum of two sets of splats.
  void add(const SplatSums& other) {
    for (std::size_t i = 0; i < words_.size(); ++i)
      words_[i] += other.words_[i];
  }

  /// The sum at pixel (x, y). Not synchronised: read once the additions have finished.
  glm::dvec3 at(int x, int y) const {
    const std::int64_t* pixel = words_.data() + index(x, y);
    glm::dvec3 sum;
    for (int c = 0; c < 3; ++c)
      sum[c] = double(pixel[2 * c]) * (1.0 / kCoarseScale) +
               double(pixel[2 * c + 1]) * (1.0 / kFineScale);
    return sum;
  }

  /// The integers themselves, coarse and fine per channel, pixel by pixel from the top left: for
  /// saving and comparing sums bit for bit.
  const std::vector<std::int64_t>& words() const { return words_; }
  std::vector<std::int64_t>& words() { return words_; }
  static constexpr std::size_t kWordsPerPixel = 6;

 private:
  std::size_t index(int x, int y) const {
    return (std::size_t(y) * std::size_t(width_) + std::size_t(x)) * kWordsPerPixel;
  }

  int width_ = 0;
  int height_ = 0;
  std::vector<std::int64_t> words_;
};

}  // namespace glint
