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

 private:
  Pcg32 rng_;
};
static_assert(Sampler<IndependentSampler>);

}  // namespace glint
