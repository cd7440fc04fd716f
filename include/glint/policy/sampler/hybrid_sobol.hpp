#pragma once
// Sobol' for the first requests of a sample, independent values after.

#include <cstdint>

#include "glint/math/random.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/sampler/sobol.hpp"

namespace glint {

/// Sobol' values for the first kSobolRequests requests of a sample (the camera jitter and the
/// first bounces, where low discrepancy visibly lowers the error), independent PCG32 values
/// after that (deep bounces, where it hardly helps but a scrambled Sobol' draw costs about
/// four times an independent one). The image converges to the same result as with either.
template <std::uint32_t kSobolRequests = 4>
class HybridSobolSampler {
 public:
  void start(const PixelSample& s) {
    sobol_.start(s);
    rng_.reseed(hash_values(s.x, s.y, s.index, s.seed, 0x50b01u), hash_values(s.seed));
    requests_ = 0;
  }
  float next_1d() { return requests_++ < kSobolRequests ? sobol_.next_1d() : rng_.next_float(); }
  Vec2 next_2d() {
    if (requests_++ < kSobolRequests) return sobol_.next_2d();
    const float u = rng_.next_float();
    return {u, rng_.next_float()};
  }

#if defined(GLINT_AVX2)
  /// Eight samplers, one per lane: each lane's request goes to Sobol' or to PCG32 as that
  /// lane's own count of requests says, and a part is computed only if some lane needs it.
  class Lanes {
   public:
    void set_lane(int i, const HybridSobolSampler& s) {
      sobol_.set_lane(i, s.sobol_);
      rng_.set_lane(i, s.rng_);
      requests_[i] = s.requests_;
    }
    void get_lane(int i, HybridSobolSampler& s) const {
      sobol_.get_lane(i, s.sobol_);
      rng_.get_lane(i, s.rng_);
      s.requests_ = requests_[i];
    }
    /// HybridSobolSampler::start for the lanes of `mask`; the others keep their state.
    void start(IntLanes mask, const PixelSampleLanes& s) {
      sobol_.start(mask, s);
      rng_.reseed(mask, hash_lanes(s.x, s.y, s.index, s.seed, 0x50b01u),
                  Uint64Lanes::broadcast(hash_values(s.seed)));
      requests_ = select(mask, UintLanes{}, requests_);
    }
    FloatLanes next_1d(IntLanes mask) {
      const IntLanes sobol = mask & by_sobol();
      const IntLanes independent = mask & ~sobol;
      requests_ = select(mask, requests_ + 1u, requests_);
      FloatLanes value = broadcast(0.0f);
      if (lane_bits(sobol) != 0) value = sobol_.next_1d(sobol);
      if (lane_bits(independent) != 0)
        value = select(independent, rng_.next_float(independent), value);
      return value;
    }
    Vec2Lanes next_2d(IntLanes mask) {
      const IntLanes sobol = mask & by_sobol();
      const IntLanes independent = mask & ~sobol;
      requests_ = select(mask, requests_ + 1u, requests_);
      Vec2Lanes value{broadcast(0.0f), broadcast(0.0f)};
      if (lane_bits(sobol) != 0) value = sobol_.next_2d(sobol);
      if (lane_bits(independent) != 0) {
        const FloatLanes u = rng_.next_float(independent);
        value = {select(independent, u, value.x),
                 select(independent, rng_.next_float(independent), value.y)};
      }
      return value;
    }

   private:
    IntLanes by_sobol() const {
      // requests_ < kSobolRequests, unsigned: both below 2^31, so the signed comparison agrees.
      return std::bit_cast<IntLanes>(requests_) < std::int32_t(kSobolRequests);
    }

    typename SobolSampler::Lanes sobol_;
    Pcg32::Lanes rng_;
    UintLanes requests_{};
  };
#endif

 private:
  SobolSampler sobol_;
  Pcg32 rng_;
  std::uint32_t requests_ = 0;
};
static_assert(Sampler<HybridSobolSampler<>>);

}  // namespace glint
