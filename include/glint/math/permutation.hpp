#pragma once
// Keyed permutations of {0, ..., n-1}, evaluated one element at a time without storing them.
// The design (a Feistel network, cycle walking, a rotation) is explained in
// docs/notes/samplers.md.

#include <bit>
#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/random.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

namespace detail {

/// A 32-bit hash with low bias (the "lowbias32" constants found by Wellons' hash prospector),
/// used as the round function of permute_index.
constexpr std::uint32_t hash_u32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/// Element i of a permutation of {0, ..., n-1} chosen by `key`, computed without storing the
/// permutation. A keyed bijection on the next power of two is cycle-walked back into range
/// (each walk step is accepted with probability > 1/2), then rotated by an offset drawn from
/// an independent hash: the bijection decorrelates the images of different elements, and the
/// rotation makes the image of each single element exactly uniform over keys, which is what
/// keeps a sampler that uses only some of the strata unbiased.
/// Rounds of the Feistel network, in pairs (see docs/notes/samplers.md for why four rounds).
inline constexpr std::uint32_t kFeistelRoundPairs = 2;

constexpr std::uint32_t permute_index(std::uint32_t i, std::uint32_t n, std::uint64_t key) {
  if (n <= 1) return 0;
  const int bits = std::bit_width(n - 1);
  const int low_bits = bits / 2;
  const std::uint32_t low_mask = (1u << low_bits) - 1u;
  const std::uint32_t high_mask = (1u << (bits - low_bits)) - 1u;
  const auto a = static_cast<std::uint32_t>(key);
  const auto b = static_cast<std::uint32_t>(key >> 32);
  std::uint32_t low = i & low_mask;
  std::uint32_t high = (i >> low_bits) & high_mask;
  do {
    for (std::uint32_t round = 0; round < kFeistelRoundPairs; ++round) {
      high ^= hash_u32(low ^ (a + round * 0x9e3779b9u)) & high_mask;
      low ^= hash_u32(high ^ (b + round * 0x9e3779b9u)) & low_mask;
    }
  } while (((high << low_bits) | low) >= n);
  const std::uint32_t permuted = (high << low_bits) | low;
  const std::uint64_t offset_bits = mix_bits(key ^ kGoldenGamma);
  const auto offset = static_cast<std::uint32_t>(((offset_bits >> 32) * n) >> 32);
  const std::uint32_t rotated = permuted + offset;
  return rotated >= n ? rotated - n : rotated;
}

}  // namespace detail

}  // namespace glint::inline GLINT_ISA_NAMESPACE
