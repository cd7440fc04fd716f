#pragma once
// The keys a sampler derives its randomness from: one per (pixel, seed), one per dimension.

#include <cstdint>

#include "glint/math/random.hpp"
#include "glint/policy/concepts.hpp"

namespace glint {

namespace detail {

/// One key per (pixel, seed). The two inner hashes are independent, so their latencies
/// overlap: cheaper than hashing the three values in sequence, which start() would pay for
/// every sample.
constexpr std::uint64_t pixel_key(const PixelSample& s) {
  const std::uint64_t pixel = (std::uint64_t{s.y} << 32) | s.x;
  return mix_bits(mix_bits(pixel) ^ mix_bits(s.seed + kGoldenGamma));
}
#if defined(GLINT_AVX2)
inline Uint64Lanes pixel_key(const PixelSampleLanes& s) {
  const Uint64Lanes pixel = (Uint64Lanes::from(s.y) << 32) | Uint64Lanes::from(s.x);
  return mix_bits(mix_bits(pixel) ^ Uint64Lanes::broadcast(mix_bits(s.seed + kGoldenGamma)));
}
#endif

/// A key for one dimension of one pixel. mix_bits is a bijection, so distinct dimensions of a
/// pixel never share a key, and its avalanche decorrelates neighbouring ones.
constexpr std::uint64_t dimension_key(std::uint64_t pixel_key, std::uint32_t dimension,
                                      std::uint32_t salt = 0) {
  return mix_bits(pixel_key + (std::uint64_t{dimension} * 4 + salt + 1) * kGoldenGamma);
}
#if defined(GLINT_AVX2)
inline Uint64Lanes dimension_key(const Uint64Lanes& pixel_key, UintLanes dimension,
                                 std::uint32_t salt) {
  const Uint64Lanes d = Uint64Lanes::from(dimension);
  return mix_bits(pixel_key + ((d << 2) + Uint64Lanes::broadcast(std::uint64_t{salt} + 1)) *
                                  Uint64Lanes::broadcast(kGoldenGamma));
}
#endif

}  // namespace detail

}  // namespace glint
