#pragma once
// The report's sampler: independent values from a hashed PCG32 stream.

#include "glint/math/random.hpp"
#include "glint/policy/concepts.hpp"

namespace glint {

/// Independent uniform values from a PCG32 stream seeded by hashing (pixel, sample, seed):
/// the report's sampler, and the baseline for the others.
class IndependentSampler {
 public:
  void start(const PixelSample& s) {
    rng_.reseed(hash_values(s.x, s.y, s.index, s.seed), hash_values(s.seed));
  }
  float next_1d() { return rng_.next_float(); }
  Vec2 next_2d() {
    const float u = rng_.next_float();
    return {u, rng_.next_float()};
  }

#if defined(GLINT_AVX2)
  /// Eight samplers, one per lane; a lane outside a draw's mask keeps its state.
  class Lanes {
   public:
    void set_lane(int i, const IndependentSampler& s) { rng_.set_lane(i, s.rng_); }
    void get_lane(int i, IndependentSampler& s) const { rng_.get_lane(i, s.rng_); }
    /// IndependentSampler::start for the lanes of `mask`; the others keep their state.
    void start(IntLanes mask, const PixelSampleLanes& s) {
      rng_.reseed(mask, hash_lanes(s.x, s.y, s.index, s.seed),
                  Uint64Lanes::broadcast(hash_values(s.seed)));
    }
    FloatLanes next_1d(IntLanes mask) { return rng_.next_float(mask); }
    Vec2Lanes next_2d(IntLanes mask) {
      const FloatLanes u = rng_.next_float(mask);
      return {u, rng_.next_float(mask)};
    }

   private:
    Pcg32::Lanes rng_;
  };
#endif

 private:
  Pcg32 rng_;
};
static_assert(Sampler<IndependentSampler>);

}  // namespace glint
