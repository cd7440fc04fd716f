#pragma once
// Random numbers that depend only on their inputs, never on the standard library or on thread
// scheduling: images are reproducible bit for bit across compilers and thread counts. Each
// formula is written once over its integer types (math/wide.hpp): std::uint64_t and
// std::uint32_t for one value, UInt64<W> and UInt<W> for W lanes, where integer arithmetic gives
// every lane exactly the value a single computation gives.

#include <bit>
#include <cstdint>
#include <type_traits>

#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// 2^64 divided by the golden ratio: an odd constant whose multiples are spread evenly
/// modulo 2^64, used to separate the inputs of a hash.
inline constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;

/// A 64-bit finaliser (MurmurHash3 fmix64 constants): avalanches every input bit.
template <UInt64Type U>
constexpr U mix_bits(U v) {
  v ^= v >> 33;
  v *= 0xff51afd7ed558ccdULL;
  v ^= v >> 33;
  v *= 0xc4ceb9fe1a85ec53ULL;
  v ^= v >> 33;
  return v;
}
/// The same for any unsigned value, converted to 64 bits.
constexpr std::uint64_t mix_bits(std::uint64_t v) {
  return mix_bits<std::uint64_t>(v);
}

namespace detail {

/// A hash input in U's lanes: an integer in every lane, or a UInt's lanes zero-extended.
template <UInt64Type U, typename T>
constexpr U hash_input(const T& value) {
  if constexpr (std::is_integral_v<T>)
    return splat64<U>(static_cast<std::uint64_t>(value));
  else
    return widen(value);
}

template <UInt64Type U, typename... Ts>
constexpr U hash_into(const Ts&... values) {
  U h = splat64<U>(kGoldenGamma);
  ((h = mix_bits(h ^ (hash_input<U>(values) + kGoldenGamma + (h << 6) + (h >> 2)))), ...);
  return h;
}

}  // namespace detail

/// Hashes any number of integers into one well-mixed 64-bit value.
template <typename... Ts>
constexpr std::uint64_t hash_values(Ts... values) {
  return detail::hash_into<std::uint64_t>(values...);
}

/// hash_values for W lanes at once, lane i hashing lane i of each UInt<W> argument; an integer
/// argument is the same in every lane.
template <int W, typename... Ts>
UInt64<W> hash_lanes(const Ts&... values) {
  return detail::hash_into<UInt64<W>>(values...);
}

/// Maps 24 random bits to a float uniformly in [0, 1): every value is exactly representable,
/// and 1 is never returned. Lane by lane for UInt<W>.
template <typename U>
requires std::is_same_v<U, UInt<kLanesOf<U>>>
constexpr Float<kLanesOf<U>> bits_to_unit_float(U bits) {
  // The top 24 bits as a signed integer: converted exactly, in one instruction at any width.
  const auto top = std::bit_cast<Int<kLanesOf<U>>>(U(bits >> 8u));
  Float<kLanesOf<U>> value;
  if constexpr (kLanesOf<U> == 1)
    value = static_cast<float>(top);
  else
    value = __builtin_convertvector(top, Float<kLanesOf<U>>);
  return value * 0x1p-24f;
}

namespace detail {

// PCG32's steps, written once for one generator (std::uint64_t) and for lanes of them.
inline constexpr std::uint64_t kPcgMultiplier = 6364136223846793005ULL;

template <UInt64Type U>
constexpr U pcg_advance(U state, U increment) {
  return state * kPcgMultiplier + increment;
}
/// XSH-RR: the output of the state before a step.
template <UInt64Type U>
constexpr UInt<kLanes64Of<U>> pcg_output(U old) {
  const auto xorshifted = low_bits(U(((old >> 18u) ^ old) >> 27u));
  const auto rot = low_bits(U(old >> 59u));
  return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}
template <UInt64Type U>
constexpr U pcg_increment(U stream) {
  return (stream << 1u) | 1u;
}
/// The state that reseeding leaves: one step from 0, the seed added, one more step.
template <UInt64Type U>
constexpr U pcg_seeded_state(U seed, U increment) {
  return pcg_advance(U(pcg_advance(U{}, increment) + seed), increment);
}

}  // namespace detail

/// PCG32 (O'Neill, XSH-RR output on a 64-bit LCG): small state, fast, statistically strong.
class Pcg32 {
 public:
  constexpr Pcg32() = default;
  constexpr Pcg32(std::uint64_t seed, std::uint64_t stream) { reseed(seed, stream); }

  constexpr void reseed(std::uint64_t seed, std::uint64_t stream) {
    increment_ = detail::pcg_increment(stream);
    state_ = detail::pcg_seeded_state(seed, increment_);
  }

  constexpr std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = detail::pcg_advance(old, increment_);
    return detail::pcg_output(old);
  }

  /// Uniform in [0, 1).
  constexpr float next_float() { return bits_to_unit_float(next_u32()); }

  /// W generators, one per lane; a lane outside a draw's mask keeps its state.
  template <int W>
  class Wide {
   public:
    void set_lane(int i, const Wide<1>& one) {
      glint::set_lane(state_, i, one.state_);
      glint::set_lane(increment_, i, one.increment_);
    }
    void get_lane(int i, Wide<1>& one) const {
      one.state_ = lane(state_, i);
      one.increment_ = lane(increment_, i);
    }
    /// Pcg32::reseed for the lanes of `mask`; the others keep their state.
    void reseed(Mask<W> mask, UInt64<W> seed, UInt64<W> stream) {
      const UInt64<W> increment = detail::pcg_increment(stream);
      state_ = select(mask, detail::pcg_seeded_state(seed, increment), state_);
      increment_ = select(mask, increment, increment_);
    }
    UInt<W> next_u32(Mask<W> mask) {
      const UInt64<W> old = state_;
      state_ = select(mask, detail::pcg_advance(old, increment_), old);
      return detail::pcg_output(old);
    }
    Float<W> next_float(Mask<W> mask) { return bits_to_unit_float(next_u32(mask)); }

   private:
    template <int>
    friend class Wide;

    UInt64<W> state_{}, increment_{};
  };

 private:
  std::uint64_t state_ = 0x853c49e6748fea9bULL;
  std::uint64_t increment_ = 0xda3e39cb94b95bdbULL;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
