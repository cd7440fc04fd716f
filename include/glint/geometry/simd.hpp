#pragma once
// glint's batched geometry: its lane count and the AVX2 helpers its kernels share. The SIMD
// switches (GLINT_AVX2, GLINT_SSE41, GLINT_NO_SIMD) are glint/instruction_set.hpp's.

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The lanes of glint's batched geometry, whatever the instruction set: the rays of a RayBatch,
/// the spheres that a linear set's scan and a BVH leaf group test at once, the floats of the
/// AVX2 registers that hold them, and the eight-lane width of math/lanes.hpp. Every other lane
/// count of the geometry derives from it.
inline constexpr int kBatchWidth = 8;

}  // namespace glint::inline GLINT_ISA_NAMESPACE

#if defined(GLINT_AVX2) || defined(GLINT_SSE41)
#include <immintrin.h>
#endif

#if defined(GLINT_AVX2)
#include <cstdint>

namespace glint::inline GLINT_ISA_NAMESPACE::avx2 {

// The AVX2 kernels hold a batch in a __m256 of floats (or of 32-bit integers), one lane each.
static_assert(kBatchWidth == 8, "the AVX2 kernels are written for eight lanes");

/// All ones in the lanes i of an AVX register for which bit i of `mask` is set.
inline __m256i lane_vector(std::uint32_t mask) {
  const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(mask)), bits),
                            bits);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::avx2
#endif
