#pragma once
// Path termination policies: when a path stops.

#include <cmath>

#include "glint/policy/concepts.hpp"

namespace glint {

/// The report's: every path runs to the maximum depth (or until it escapes).
struct FixedDepth {
  static constexpr bool uses_roulette = false;
  static float continue_probability(int, float) { return 1.0f; }
#if defined(GLINT_AVX2)
  static FloatLanes continue_probability(IntLanes, FloatLanes) {
    return broadcast(1.0f);
  }
#endif
};

/// Russian roulette after three bounces, as pbrt-v4 plays it: a path whose throughput (the
/// largest colour component of its weight, including the 1/p of roulettes it survived) is
/// below one continues with probability equal to that throughput and is reweighted by 1/p, so
/// the estimate stays unbiased and a surviving path carries throughput one. A path at or
/// above one is never played: killing a lossless path (glass in a furnace) would only add
/// noise. The maximum depth still caps every path.
struct RussianRoulette {
  static constexpr bool uses_roulette = true;
  static constexpr int kMinimumBounces = 3;
  static float continue_probability(int depth, float throughput) {
    if (depth < kMinimumBounces) return 1.0f;
    return std::fmin(throughput, 1.0f);
  }
  /// std::fmin's rule for NaN: a NaN throughput continues with probability 1.
#if defined(GLINT_AVX2)
  static FloatLanes continue_probability(IntLanes depth, FloatLanes throughput) {
    const FloatLanes p = select(throughput < 1.0f, throughput, broadcast(1.0f));
    return select(depth < kMinimumBounces, broadcast(1.0f), p);
  }
#endif
};

static_assert(PathTermination<FixedDepth> && PathTermination<RussianRoulette>);

}  // namespace glint
