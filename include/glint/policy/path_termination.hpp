#pragma once
// Path termination policies: when a path stops.

#include <algorithm>

#include "glint/policy/concepts.hpp"

namespace glint {

/// The report's: every path runs to the maximum depth (or until it escapes).
struct FixedDepth {
  static constexpr bool uses_roulette = false;
  static float continue_probability(int, float) { return 1.0f; }
};

/// Russian roulette after three bounces: a path continues with probability tied to the
/// throughput it carries and is reweighted by 1/probability, so the estimate stays unbiased.
/// The maximum depth still caps every path.
struct RussianRoulette {
  static constexpr bool uses_roulette = true;
  static constexpr int kMinimumBounces = 3;
  static float continue_probability(int depth, float throughput) {
    if (depth < kMinimumBounces) return 1.0f;
    return std::clamp(throughput, 0.05f, 0.95f);
  }
};

static_assert(PathTermination<FixedDepth> && PathTermination<RussianRoulette>);

}  // namespace glint
