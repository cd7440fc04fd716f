#pragma once
// Path termination policies: when a path stops. Each is written once for every width
// (math/wide.hpp).

#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The report's: every path runs to the maximum depth (or until it escapes).
struct FixedDepth {
  static constexpr bool uses_roulette = false;
  template <FloatType F>
  static F continue_probability(IntFor<F>, F) {
    return splat<F>(1.0f);
  }
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
  /// std::fmin's rule for NaN: a NaN throughput continues with probability 1.
  template <FloatType F>
  static F continue_probability(IntFor<F> depth, F throughput) {
    const F p = select(throughput < 1.0f, throughput, splat<F>(1.0f));
    return select(depth < kMinimumBounces, splat<F>(1.0f), p);
  }
};

static_assert(PathTermination<FixedDepth> && PathTermination<RussianRoulette>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
