#pragma once
// glint's batched geometry: its lane count and the registers its SIMD kernels compute in. The
// SIMD switches (GLINT_AVX2, GLINT_AVX512, GLINT_NO_SIMD) are glint/instruction_set.hpp's.
//
// The kernels that pair rays with spheres lane by lane (sphere_kernel.hpp, ray_batch_kernel.hpp)
// are written once over a register type L: Lanes1, plain scalars, Lanes8, AVX2's eight floats,
// or Lanes16, AVX-512's sixteen. Each of L's operations is one instruction of its set (or one
// IEEE operation), and they round alike (IEEE single precision, fused where the name says so),
// so a lane gets the same bits at any width. A comparison gives an L::M: a bool at one lane, at
// eight a register of all-ones lanes, at sixteen a k-register, the form each set compares into
// and selects by.

#include <cmath>
#include <cstdint>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The lanes of glint's batched geometry, whatever the instruction set: the rays of a RayBatch,
/// the spheres that a linear set's scan and a BVH leaf group test at once, the floats of the
/// AVX2 registers that hold them, and the eight-lane width of math/lanes.hpp. Every other lane
/// count of the geometry derives from it.
inline constexpr int kBatchWidth = 8;

/// One lane in plain scalars: the register type at which the kernels written over L answer for
/// a single ray and a single sphere (the scalar queries and the BVH's leaves), whatever the
/// instruction set. Each operation rounds as Lanes8's and Lanes16's instruction does: std::fma
/// is exactly rounded (an instruction with FMA, the C library's fmaf without), std::sqrt and
/// the operators are IEEE's, and min and max pick their operands as minps and maxps do.
struct Lanes1 {
  static constexpr int kWidth = 1;
  using F = float;
  using I = std::int32_t;
  using M = bool;
  static constexpr unsigned kAllLanes = 1;

  static F splat(float value) { return value; }
  static I splat(std::int32_t value) { return value; }
  static F zero() { return 0.0f; }

  static F add(F a, F b) { return a + b; }
  static F sub(F a, F b) { return a - b; }
  static F mul(F a, F b) { return a * b; }
  static F div(F a, F b) { return a / b; }
  static F sqrt(F a) { return std::sqrt(a); }
  static F min(F a, F b) { return a < b ? a : b; }  ///< b if either is NaN
  static F max(F a, F b) { return a > b ? a : b; }
  static F fmadd(F a, F b, F c) { return std::fma(a, b, c); }
  static F fnmadd(F a, F b, F c) { return std::fma(-a, b, c); }
  static F fmsub(F a, F b, F c) { return std::fma(a, b, -c); }
  static I add(I a, I b) { return a + b; }
  static I mul(I a, I b) { return a * b; }
  /// Toward zero, as cvttps2dq (for values an int32_t holds).
  static I truncate(F a) { return static_cast<I>(a); }
  static F with_sign_of(F magnitude, F sign) { return std::copysign(magnitude, sign); }
  static F negate(F a) { return -a; }
  static F abs(F a) { return std::fabs(a); }

  static M less(F a, F b) { return a < b; }
  static M less_equal(F a, F b) { return a <= b; }
  static M greater(F a, F b) { return a > b; }
  static M greater_equal(F a, F b) { return a >= b; }
  static M equal(F a, F b) { return a == b; }
  static M not_greater(F a, F b) { return !(a > b); }
  static M not_less(F a, F b) { return !(a < b); }
  static M equal(I a, I b) { return a == b; }
  static M at_least_unsigned(I a, I b) {
    return static_cast<std::uint32_t>(a) >= static_cast<std::uint32_t>(b);
  }

  static M both(M a, M b) { return a && b; }
  static M either(M a, M b) { return a || b; }
  static M and_not(M a, M b) { return a && !b; }
  static unsigned bits(M m) { return m ? 1u : 0u; }
  static M mask_of_bits(unsigned bits) { return (bits & 1u) != 0; }
  static F select(M m, F if_set, F if_clear) { return m ? if_set : if_clear; }
  static I select(M m, I if_set, I if_clear) { return m ? if_set : if_clear; }
  static M select(M m, M if_set, M if_clear) { return m ? if_set : if_clear; }
  static F keep(M m, F a) { return m ? a : 0.0f; }
  static I keep(M m, I a) { return m ? a : 0; }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE

#if defined(GLINT_AVX2)
#include <immintrin.h>
#endif

#if defined(GLINT_AVX2)
namespace glint::inline GLINT_ISA_NAMESPACE::avx2 {

// The AVX2 kernels hold a batch in a __m256 of floats (or of 32-bit integers), one lane each.
static_assert(kBatchWidth == 8, "the AVX2 kernels are written for eight lanes");

/// All ones in the lanes i of an AVX register for which bit i of `mask` is set.
inline __m256i lane_vector(std::uint32_t mask) {
  const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(mask)), bits),
                            bits);
}

/// Eight lanes of AVX2: floats F, 32-bit integers I and masks M (all-ones lanes in a float
/// register).
struct Lanes8 {
  static constexpr int kWidth = kBatchWidth;
  using F = __m256;
  using I = __m256i;
  using M = __m256;
  static constexpr unsigned kAllLanes = (1u << kWidth) - 1;

  static F splat(float value) { return _mm256_set1_ps(value); }
  static I splat(std::int32_t value) { return _mm256_set1_epi32(value); }
  static F zero() { return _mm256_setzero_ps(); }
  static F load(const float* p) { return _mm256_load_ps(p); }
  static I load(const std::uint32_t* p) {
    return _mm256_load_si256(reinterpret_cast<const __m256i*>(p));
  }

  static F add(F a, F b) { return _mm256_add_ps(a, b); }
  static F sub(F a, F b) { return _mm256_sub_ps(a, b); }
  static F mul(F a, F b) { return _mm256_mul_ps(a, b); }
  static F div(F a, F b) { return _mm256_div_ps(a, b); }
  static F sqrt(F a) { return _mm256_sqrt_ps(a); }
  static F min(F a, F b) { return _mm256_min_ps(a, b); }
  static F max(F a, F b) { return _mm256_max_ps(a, b); }
  static F fmadd(F a, F b, F c) { return _mm256_fmadd_ps(a, b, c); }    ///< a b + c
  static F fnmadd(F a, F b, F c) { return _mm256_fnmadd_ps(a, b, c); }  ///< c - a b
  static F fmsub(F a, F b, F c) { return _mm256_fmsub_ps(a, b, c); }    ///< a b - c
  static I add(I a, I b) { return _mm256_add_epi32(a, b); }
  static I mul(I a, I b) { return _mm256_mullo_epi32(a, b); }  ///< the low 32 bits
  static I truncate(F a) { return _mm256_cvttps_epi32(a); }
  /// The sign bit of `sign`'s lanes on `magnitude`'s (which are +0 or more).
  static F with_sign_of(F magnitude, F sign) {
    return _mm256_or_ps(magnitude, _mm256_and_ps(sign, _mm256_set1_ps(-0.0f)));
  }
  static F negate(F a) { return _mm256_xor_ps(a, _mm256_set1_ps(-0.0f)); }
  static F abs(F a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a); }

  static M less(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
  static M less_equal(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
  static M greater(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
  static M greater_equal(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_GE_OQ); }
  static M equal(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_EQ_OQ); }
  /// !(a > b) and !(a < b): true where either is NaN.
  static M not_greater(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_NGT_UQ); }
  static M not_less(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_NLT_UQ); }
  static M equal(I a, I b) { return _mm256_castsi256_ps(_mm256_cmpeq_epi32(a, b)); }
  /// a >= b as unsigned integers.
  static M at_least_unsigned(I a, I b) {
    return _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_min_epu32(a, b), b));
  }

  static M both(M a, M b) { return _mm256_and_ps(a, b); }
  static M either(M a, M b) { return _mm256_or_ps(a, b); }
  static M and_not(M a, M b) { return _mm256_andnot_ps(b, a); }  ///< a and not b
  static unsigned bits(M m) { return unsigned(_mm256_movemask_ps(m)); }
  static M mask_of_bits(unsigned bits) { return _mm256_castsi256_ps(lane_vector(bits)); }
  /// `if_set` where `m` is set, `if_clear` elsewhere (masks too: M is F).
  static F select(M m, F if_set, F if_clear) { return _mm256_blendv_ps(if_clear, if_set, m); }
  static I select(M m, I if_set, I if_clear) {
    return _mm256_castps_si256(
        _mm256_blendv_ps(_mm256_castsi256_ps(if_clear), _mm256_castsi256_ps(if_set), m));
  }
  /// `a` where `m` is set, +0 elsewhere.
  static F keep(M m, F a) { return _mm256_and_ps(m, a); }
  static I keep(M m, I a) { return _mm256_and_si256(_mm256_castps_si256(m), a); }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::avx2
#endif

#if defined(GLINT_AVX512)
namespace glint::inline GLINT_ISA_NAMESPACE::avx2 {

/// Sixteen lanes of AVX-512: Lanes8's operations on 512-bit registers, masks in k-registers.
struct Lanes16 {
  static constexpr int kWidth = 2 * kBatchWidth;
  using F = __m512;
  using I = __m512i;
  using M = __mmask16;
  static constexpr unsigned kAllLanes = (1u << kWidth) - 1;

  static F splat(float value) { return _mm512_set1_ps(value); }
  static I splat(std::int32_t value) { return _mm512_set1_epi32(value); }
  static F zero() { return _mm512_setzero_ps(); }
  static F load(const float* p) { return _mm512_loadu_ps(p); }
  static I load(const std::uint32_t* p) { return _mm512_loadu_si512(p); }
  /// Eight lanes from `low`, eight from `high`.
  static F join(const float* low, const float* high) {
    return _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_load_ps(low)), _mm256_load_ps(high), 1);
  }
  static I join(const std::uint32_t* low, const std::uint32_t* high) {
    return _mm512_inserti32x8(
        _mm512_castsi256_si512(_mm256_load_si256(reinterpret_cast<const __m256i*>(low))),
        _mm256_load_si256(reinterpret_cast<const __m256i*>(high)), 1);
  }

  static F add(F a, F b) { return _mm512_add_ps(a, b); }
  static F sub(F a, F b) { return _mm512_sub_ps(a, b); }
  static F mul(F a, F b) { return _mm512_mul_ps(a, b); }
  static F div(F a, F b) { return _mm512_div_ps(a, b); }
  // (The masked forms with every lane set are the plain instructions; GCC 12's plain
  // intrinsics start from an undefined register, which -Wmaybe-uninitialized reports.)
  static F sqrt(F a) { return _mm512_mask_sqrt_ps(a, M(kAllLanes), a); }
  static F min(F a, F b) { return _mm512_mask_min_ps(a, M(kAllLanes), a, b); }
  static F max(F a, F b) { return _mm512_mask_max_ps(a, M(kAllLanes), a, b); }
  static F fmadd(F a, F b, F c) { return _mm512_fmadd_ps(a, b, c); }
  static F fnmadd(F a, F b, F c) { return _mm512_fnmadd_ps(a, b, c); }
  static F fmsub(F a, F b, F c) { return _mm512_fmsub_ps(a, b, c); }
  static I add(I a, I b) { return _mm512_add_epi32(a, b); }
  static I mul(I a, I b) { return _mm512_mullo_epi32(a, b); }
  static I truncate(F a) { return _mm512_maskz_cvttps_epi32(M(kAllLanes), a); }
  static F with_sign_of(F magnitude, F sign) {
    return _mm512_or_ps(magnitude, _mm512_and_ps(sign, _mm512_set1_ps(-0.0f)));
  }
  static F negate(F a) { return _mm512_xor_ps(a, _mm512_set1_ps(-0.0f)); }
  static F abs(F a) { return _mm512_andnot_ps(_mm512_set1_ps(-0.0f), a); }

  static M less(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ); }
  static M less_equal(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ); }
  static M greater(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ); }
  static M greater_equal(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_GE_OQ); }
  static M equal(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_EQ_OQ); }
  static M not_greater(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_NGT_UQ); }
  static M not_less(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_NLT_UQ); }
  static M equal(I a, I b) { return _mm512_cmpeq_epi32_mask(a, b); }
  static M at_least_unsigned(I a, I b) { return _mm512_cmpge_epu32_mask(a, b); }

  static M both(M a, M b) { return M(a & b); }
  static M either(M a, M b) { return M(a | b); }
  static M and_not(M a, M b) { return M(a & ~b); }
  static unsigned bits(M m) { return unsigned(m); }
  static M mask_of_bits(unsigned bits) { return M(bits); }
  static F select(M m, F if_set, F if_clear) { return _mm512_mask_blend_ps(m, if_clear, if_set); }
  static I select(M m, I if_set, I if_clear) {
    return _mm512_mask_blend_epi32(m, if_clear, if_set);
  }
  static M select(M m, M if_set, M if_clear) { return M((if_set & m) | (if_clear & ~m)); }
  static F keep(M m, F a) { return _mm512_maskz_mov_ps(m, a); }
  static I keep(M m, I a) { return _mm512_maskz_mov_epi32(m, a); }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::avx2
#endif
