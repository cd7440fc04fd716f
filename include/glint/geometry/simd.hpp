#pragma once
// The one SIMD switch of glint. Kernels test the macros below, never the compiler's own
// (__AVX2__, __SSE4_1__, ...), so that defining GLINT_NO_SIMD turns every one of them back to
// its scalar reference:
//
//   GLINT_AVX2    8-wide AVX2 + FMA kernels (SphereSet)
//   GLINT_SSE41   4-wide SSE4.1 kernels (the BVH's box test)
//
// Each is defined when the compiler targets that instruction set (e.g. -march=native) and
// GLINT_NO_SIMD is not defined.

namespace glint {

/// The lanes of glint's batched geometry, whatever the instruction set: the rays of a RayBatch,
/// the spheres that a linear set's scan and a BVH leaf group test at once, the floats of the
/// AVX2 registers that hold them, and the eight-lane width of math/lanes.hpp. Every other lane
/// count of the geometry derives from it.
inline constexpr int kBatchWidth = 8;

}  // namespace glint

#if !defined(GLINT_NO_SIMD)
#if defined(__AVX2__) && defined(__FMA__)
#define GLINT_AVX2 1
#endif
#if defined(__SSE4_1__)
#define GLINT_SSE41 1
#endif
#endif

#if defined(GLINT_AVX2) || defined(GLINT_SSE41)
#include <immintrin.h>
#endif

#if defined(GLINT_AVX2)
#include <cstdint>

namespace glint::avx2 {

// The AVX2 kernels hold a batch in a __m256 of floats (or of 32-bit integers), one lane each.
static_assert(kBatchWidth == 8, "the AVX2 kernels are written for eight lanes");

/// All ones in the lanes i of an AVX register for which bit i of `mask` is set.
inline __m256i lane_vector(std::uint32_t mask) {
  const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(mask)), bits),
                            bits);
}

}  // namespace glint::avx2
#endif
