#pragma once
// The keys a sampler derives its randomness from: one per (pixel, seed), one per dimension; for
// one sample or for lanes of them (UInt<W> pixels and dimensions, UInt64<W> keys).

#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/random.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

namespace detail {

/// One key per (pixel, seed). The two inner hashes are independent, so their latencies
/// overlap: cheaper than hashing the three values in sequence, which start() would pay for
/// every sample. The seed's hash is the same in every lane, computed once.
template <int W>
constexpr UInt64<W> pixel_key(const PixelSamples<W>& s) {
  const UInt64<W> pixel = (widen(s.y) << 32) | widen(s.x);
  return mix_bits(UInt64<W>(mix_bits(pixel) ^ mix_bits(s.seed + kGoldenGamma)));
}

/// A key for one dimension of one pixel. mix_bits is a bijection, so distinct dimensions of a
/// pixel never share a key, and its avalanche decorrelates neighbouring ones.
template <UInt64Type K, typename D>
constexpr K dimension_key(K pixel_key, D dimension, std::uint32_t salt = 0) {
  return mix_bits(
      K(pixel_key + (widen(dimension) * 4u + (std::uint64_t{salt} + 1)) * kGoldenGamma));
}

}  // namespace detail

}  // namespace glint::inline GLINT_ISA_NAMESPACE
