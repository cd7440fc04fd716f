#pragma once
// The first two dimensions of Sobol's sequence and hash-based Owen scrambling, on binary
// fractions held in 32-bit integers (bit 31 is the first digit). Why the fast forms below equal
// the definitions is shown in docs/notes/samplers.md.

#include <concepts>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"

#if defined(GLINT_AVX2)
#include <immintrin.h>
#endif

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A 32-bit word, or W of them in lanes (UInt<W>): the bit operations below are written once
/// for every width, so the samplers' lane-wise draws are their scalar ones.
template <typename U>
concept Words32 = std::same_as<U, UInt<1>> || std::same_as<U, UInt<8>> || std::same_as<U, UInt<16>>;

namespace detail {

// Bit reversal in SIMD registers by byte shuffles: each word's bytes in reverse order, then each
// byte's bits by two lookups in sixteen-entry tables, one per nibble (the byte with nibbles h, l
// reversed is rev(l), rev(h)). Seven instructions instead of the arithmetic form's twenty, for
// the same words. A table is sixteen bytes as four words (byte 0 the low byte of word 0),
// repeated in every 128-bit lane, the reach of a byte shuffle.
inline constexpr std::uint32_t kByteReversal[4] = {0x00010203u, 0x04050607u, 0x08090a0bu,
                                                   0x0c0d0e0fu};
inline constexpr std::uint32_t kLowNibbleReversed[4] = {0xc0408000u, 0xe060a020u, 0xd0509010u,
                                                        0xf070b030u};
inline constexpr std::uint32_t kHighNibbleReversed[4] = {0x0c040800u, 0x0e060a02u, 0x0d050901u,
                                                         0x0f070b03u};

/// Byte i of each 128-bit lane of the result is byte index[i] (0 .. 15) of that lane of `table`.
#if defined(GLINT_AVX2)
inline UInt<8> shuffle_bytes(UInt<8> table, UInt<8> index) {
  return UInt<8>(_mm256_shuffle_epi8(__m256i(table), __m256i(index)));
}
#endif
#if defined(GLINT_AVX512)
inline UInt<16> shuffle_bytes(UInt<16> table, UInt<16> index) {
  return UInt<16>(_mm512_shuffle_epi8(__m512i(table), __m512i(index)));
}
#endif

/// Whether words in lanes of U can be bit-reversed by byte shuffles in this build.
template <typename U>
inline constexpr bool kShufflesBytes = requires(U u) {
  shuffle_bytes(u, u);
};

// A table's four words repeated across every lane of U, as a constant: a table filled lane by
// lane at run time is not folded at sixteen lanes and costs more than the shuffles save.
template <typename U, std::size_t... I>
constexpr U repeat_table(const std::uint32_t (&words)[4], std::index_sequence<I...>) {
  return U{words[I % 4]...};
}

template <typename U>
constexpr U lane_table(const std::uint32_t (&words)[4]) {
  return repeat_table<U>(words, std::make_index_sequence<kLanesOf<U>>{});
}

template <typename U>
U reverse_bits_by_bytes(U v) {
  static constexpr U kBytes = lane_table<U>(kByteReversal);
  static constexpr U kLow = lane_table<U>(kLowNibbleReversed);
  static constexpr U kHigh = lane_table<U>(kHighNibbleReversed);
  const U bytes = shuffle_bytes(v, kBytes);
  return shuffle_bytes(kLow, bytes & 0x0f0f0f0fu) |
         shuffle_bytes(kHigh, (bytes >> 4) & 0x0f0f0f0fu);
}

/// Bit reversal: turns a binary fraction's digits (most significant first) into an integer's
/// (least significant first) and back.
template <Words32 U>
constexpr U reverse_bits(U v) {
  if constexpr (kShufflesBytes<U>) {
    if (!std::is_constant_evaluated()) return reverse_bits_by_bytes(v);
  }
  v = (v << 16) | (v >> 16);
  v = ((v & 0x00ff00ffu) << 8) | ((v >> 8) & 0x00ff00ffu);
  v = ((v & 0x0f0f0f0fu) << 4) | ((v >> 4) & 0x0f0f0f0fu);
  v = ((v & 0x33333333u) << 2) | ((v >> 2) & 0x33333333u);
  v = ((v & 0x55555555u) << 1) | ((v >> 1) & 0x55555555u);
  return v;
}

/// owen_scramble_reversed with its key's two halves.
template <Words32 U>
constexpr U owen_scramble_halves(U v, U a, U b) {
  v += a;
  v ^= v * 0x9e3779b8u;
  v *= b | 1u;
  v ^= v * 0x7feb352cu;
  v += b;
  v ^= v * 0x846ca68au;
  v ^= v * ((a >> 7) << 1);
  return v;
}

}  // namespace detail

/// Column j of the generator matrix of the second dimension of Sobol's sequence, as a binary
/// fraction (bit 31 is the first digit). That dimension's primitive polynomial is x + 1 with
/// initial direction number m_1 = 1, so Sobol's recurrence reduces to v_j = v_{j-1} ^
/// (v_{j-1} >> 1): row t of column j is C(j, t) mod 2, Pascal's triangle. The sampler uses the
/// faster sobol_second_dimension below; this is the definition it is tested against.
constexpr std::uint32_t sobol_generator_column(int j) {
  std::uint32_t v = 0x80000000u;
  for (int k = 0; k < j; ++k)
    v ^= v >> 1;
  return v;
}

/// The first dimension of Sobol's sequence (van der Corput in base 2), as a binary fraction.
constexpr std::uint32_t sobol_first_dimension(std::uint32_t index) {
  return detail::reverse_bits(index);
}

/// The second dimension of Sobol's sequence, as a binary fraction, with the digits still in
/// reversed (integer) order: a subset-sum transform, one masked shift-xor per bit of a digit
/// position instead of a 32-step matrix product.
template <Words32 U>
constexpr U sobol_second_dimension_reversed(U index) {
  U v = index;
  v ^= (v >> 1) & 0x55555555u;
  v ^= (v >> 2) & 0x33333333u;
  v ^= (v >> 4) & 0x0f0f0f0fu;
  v ^= (v >> 8) & 0x00ff00ffu;
  v ^= (v >> 16) & 0x0000ffffu;
  return v;
}

constexpr std::uint32_t sobol_second_dimension(std::uint32_t index) {
  return detail::reverse_bits(sobol_second_dimension_reversed(index));
}

/// A hash-based Owen scramble of a binary fraction given with its digits reversed (Laine and
/// Karras 2012; Burley 2020): every step changes digit k only by a function of the digits
/// less significant than it, which makes the whole an Owen scramble (preserving every
/// (t, m, s)-net property). Returns the digits still reversed.
template <Words32 U>
constexpr U owen_scramble_reversed(U v, UInt64For<U> key) {
  return detail::owen_scramble_halves(v, low_bits(key), high_bits(key));
}

/// An Owen scramble of a binary fraction in ordinary order (bit 31 the first digit).
constexpr std::uint32_t owen_scramble(std::uint32_t fraction, std::uint64_t key) {
  return detail::reverse_bits(owen_scramble_reversed(detail::reverse_bits(fraction), key));
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
