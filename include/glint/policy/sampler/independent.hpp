#pragma once
// The report's sampler: independent values from a hashed PCG32 stream.

#include "glint/instruction_set.hpp"
#include "glint/math/random.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Independent uniform values from a PCG32 stream seeded by hashing (pixel, sample, seed):
/// the report's sampler, and the baseline for the others.
class IndependentSampler {
 public:
  /// W samplers, one per lane, each drawing what an IndependentSampler draws; a lane outside a
  /// call's mask keeps its state. The sampler itself is the width-1 form with every lane on.
  template <int W>
  class Wide {
   public:
    void set_lane(int i, const IndependentSampler& s) { rng_.set_lane(i, s.state_.rng_); }
    void get_lane(int i, IndependentSampler& s) const { rng_.get_lane(i, s.state_.rng_); }
    /// IndependentSampler::start for the lanes of `mask`.
    void start(Mask<W> mask, const PixelSamples<W>& s) {
      rng_.reseed(mask, hash_lanes<W>(s.x, s.y, s.index, s.seed),
                  splat64<UInt64<W>>(hash_values(s.seed)));
    }
    Float<W> next_1d(Mask<W> mask) { return rng_.next_float(mask); }
    Vec2For<Float<W>> next_2d(Mask<W> mask) {
      const Float<W> u = rng_.next_float(mask);
      return {u, rng_.next_float(mask)};
    }

   private:
    template <int>
    friend class Wide;

    Pcg32::Wide<W> rng_;
  };

  void start(const PixelSample& s) { state_.start(true, s); }
  float next_1d() { return state_.next_1d(true); }
  Vec2 next_2d() { return state_.next_2d(true); }

 private:
  Wide<1> state_;
};
static_assert(Sampler<IndependentSampler>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
