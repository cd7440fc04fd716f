#pragma once
// Sobol' for the first requests of a sample, independent values after.

#include <bit>
#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/random.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/sampler/sobol.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Sobol' values for the first kSobolRequests requests of a sample (the camera jitter and the
/// first bounces, where low discrepancy visibly lowers the error), independent PCG32 values
/// after that (deep bounces, where it hardly helps but a scrambled Sobol' draw costs about
/// four times an independent one). The image converges to the same result as with either.
template <std::uint32_t kSobolRequests = 4>
class HybridSobolSampler {
 public:
  /// W samplers, one per lane, each drawing what a HybridSobolSampler draws: each lane's
  /// request goes to Sobol' or to PCG32 as that lane's own count of requests says, and a part
  /// is computed only if some lane needs it. A lane outside a call's mask keeps its state. The
  /// sampler itself is the width-1 form with every lane on.
  template <int W>
  class Wide {
   public:
    void set_lane(int i, const HybridSobolSampler& s) { set_lane(i, s.state_); }
    void get_lane(int i, HybridSobolSampler& s) const { get_lane(i, s.state_); }
    void set_lane(int i, const Wide<1>& one) {
      sobol_.set_lane(i, one.sobol_);
      rng_.set_lane(i, one.rng_);
      glint::set_lane(requests_, i, one.requests_);
    }
    void get_lane(int i, Wide<1>& one) const {
      sobol_.get_lane(i, one.sobol_);
      rng_.get_lane(i, one.rng_);
      one.requests_ = lane(requests_, i);
    }
    /// HybridSobolSampler::start for the lanes of `mask`.
    void start(Mask<W> mask, const PixelSamples<W>& s) {
      sobol_.start(mask, s);
      rng_.reseed(mask, hash_lanes<W>(s.x, s.y, s.index, s.seed, 0x50b01u),
                  splat64<UInt64<W>>(hash_values(s.seed)));
      requests_ = select(mask, UInt<W>{}, requests_);
    }
    Float<W> next_1d(Mask<W> mask) {
      const Mask<W> sobol = select(by_sobol(), mask, Mask<W>{});
      const Mask<W> independent = select(sobol, Mask<W>{}, mask);
      requests_ = select(mask, UInt<W>(requests_ + 1u), requests_);
      Float<W> value{};
      if (any(sobol)) value = sobol_.next_1d(sobol);
      if (any(independent)) value = select(independent, rng_.next_float(independent), value);
      return value;
    }
    Vec2For<Float<W>> next_2d(Mask<W> mask) {
      const Mask<W> sobol = select(by_sobol(), mask, Mask<W>{});
      const Mask<W> independent = select(sobol, Mask<W>{}, mask);
      requests_ = select(mask, UInt<W>(requests_ + 1u), requests_);
      Vec2For<Float<W>> value{Float<W>{}, Float<W>{}};
      if (any(sobol)) value = sobol_.next_2d(sobol);
      if (any(independent)) {
        const Float<W> u = rng_.next_float(independent);
        value = {select(independent, u, value.x),
                 select(independent, rng_.next_float(independent), value.y)};
      }
      return value;
    }

   private:
    template <int>
    friend class Wide;

    Mask<W> by_sobol() const {
      // requests_ < kSobolRequests, unsigned: both below 2^31, so the signed comparison (one
      // instruction in SIMD lanes) agrees.
      return std::bit_cast<Int<W>>(requests_) < std::int32_t(kSobolRequests);
    }

    typename SobolSampler::template Wide<W> sobol_;
    Pcg32::Wide<W> rng_;
    UInt<W> requests_{};
  };

  void start(const PixelSample& s) { state_.start(true, s); }
  float next_1d() { return state_.next_1d(true); }
  Vec2 next_2d() { return state_.next_2d(true); }

 private:
  Wide<1> state_;
};
static_assert(Sampler<HybridSobolSampler<>>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
