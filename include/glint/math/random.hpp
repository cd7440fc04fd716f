#pragma once
// Random numbers that depend only on their inputs, never on the standard library or on thread
// scheduling: images are reproducible bit for bit across compilers and thread counts.

#include <concepts>
#include <cstdint>

#include "glint/math/lanes.hpp"

namespace glint {

/// 2^64 divided by the golden ratio: an odd constant whose multiples are spread evenly
/// modulo 2^64, used to separate the inputs of a hash.
inline constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;

/// A 64-bit finaliser (MurmurHash3 fmix64 constants): avalanches every input bit.
constexpr std::uint64_t mix_bits(std::uint64_t v) {
  v ^= v >> 33;
  v *= 0xff51afd7ed558ccdULL;
  v ^= v >> 33;
  v *= 0xc4ceb9fe1a85ec53ULL;
  v ^= v >> 33;
  return v;
}
#if defined(GLINT_AVX2)
inline Uint64Lanes mix_bits(Uint64Lanes v) {
  v = v ^ (v >> 33);
  v = v * Uint64Lanes::broadcast(0xff51afd7ed558ccdULL);
  v = v ^ (v >> 33);
  v = v * Uint64Lanes::broadcast(0xc4ceb9fe1a85ec53ULL);
  return v ^ (v >> 33);
}
#endif

/// Hashes any number of integers into one well-mixed 64-bit value.
template <typename... Ts>
constexpr std::uint64_t hash_values(Ts... values) {
  std::uint64_t h = kGoldenGamma;
  ((h = mix_bits(h ^ (static_cast<std::uint64_t>(values) + kGoldenGamma + (h << 6) + (h >> 2)))),
   ...);
  return h;
}
#if defined(GLINT_AVX2)
namespace detail {
inline Uint64Lanes hash_input(UintLanes values) {
  return Uint64Lanes::from(values);
}
template <std::integral T>
Uint64Lanes hash_input(T value) {
  return Uint64Lanes::broadcast(static_cast<std::uint64_t>(value));
}
}  // namespace detail

/// hash_values for eight lanes at once, lane i hashing lane i of each UintLanes argument; a
/// scalar argument is the same in every lane. Integer arithmetic: exactly hash_values.
template <typename... Ts>
Uint64Lanes hash_lanes(const Ts&... values) {
  const Uint64Lanes gamma = Uint64Lanes::broadcast(kGoldenGamma);
  Uint64Lanes h = gamma;
  ((h = mix_bits(h ^ (detail::hash_input(values) + gamma + (h << 6) + (h >> 2)))), ...);
  return h;
}
#endif

/// Maps 24 random bits to a float uniformly in [0, 1): every value is exactly representable,
/// and 1 is never returned.
constexpr float bits_to_unit_float(std::uint32_t bits) {
  return static_cast<float>(bits >> 8) * 0x1p-24f;
}

/// PCG32 (O'Neill, XSH-RR output on a 64-bit LCG): small state, fast, statistically strong.
class Pcg32 {
 public:
  constexpr Pcg32() = default;
  constexpr Pcg32(std::uint64_t seed, std::uint64_t stream) { reseed(seed, stream); }

  constexpr void reseed(std::uint64_t seed, std::uint64_t stream) {
    state_ = 0;
    increment_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }

  constexpr std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * kMultiplier + increment_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  /// Uniform in [0, 1).
  constexpr float next_float() { return bits_to_unit_float(next_u32()); }

#if defined(GLINT_AVX2)
  /// Eight generators, one per lane; a lane outside a draw's mask keeps its state.
  class Lanes {
   public:
    void set_lane(int i, const Pcg32& rng) {
      state_.set_lane(i, rng.state_);
      increment_.set_lane(i, rng.increment_);
    }
    void get_lane(int i, Pcg32& rng) const {
      rng.state_ = state_.lane(i);
      rng.increment_ = increment_.lane(i);
    }
    /// Pcg32::reseed for the lanes of `mask`; the others keep their state.
    void reseed(IntLanes mask, const Uint64Lanes& seed, const Uint64Lanes& stream) {
      // reseed's two steps from state 0 in closed form: the first leaves the increment.
      const Uint64Lanes increment = (stream << 1) | Uint64Lanes::broadcast(1);
      state_ = select(mask, (increment + seed) * Uint64Lanes::broadcast(kMultiplier) + increment,
                      state_);
      increment_ = select(mask, increment, increment_);
    }
    UintLanes next_u32(IntLanes mask) {
      const Uint64Lanes old = state_;
      state_ = select(mask, old * Uint64Lanes::broadcast(kMultiplier) + increment_, old);
      const UintLanes xorshifted = (((old >> 18) ^ old) >> 27).low_bits();
      const UintLanes rot = (old >> 59).low_bits();
      return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    FloatLanes next_float(IntLanes mask) { return unit_floats(next_u32(mask)); }

   private:
    Uint64Lanes state_{}, increment_{};
  };
#endif

 private:
  static constexpr std::uint64_t kMultiplier = 6364136223846793005ULL;

  std::uint64_t state_ = 0x853c49e6748fea9bULL;
  std::uint64_t increment_ = 0xda3e39cb94b95bdbULL;
};

}  // namespace glint
