#pragma once
// The eight-lane width of math/wide.hpp as the wavefront renderer's stages use it, lane i being
// path i of a block, with what AVX2 adds to the width-generic operations: transposes,
// permutations and the packing of lanes into queues. Defined only with GLINT_AVX2
// (geometry/simd.hpp).

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "glint/geometry/simd.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"

#if defined(GLINT_AVX2)
namespace glint::inline GLINT_ISA_NAMESPACE {

/// The lanes of a block of paths: those of a RayBatch, so that a path's lane is its ray's.
inline constexpr int kLaneCount = kBatchWidth;

using FloatLanes = Float<kLaneCount>;
/// Integers, and the masks comparisons give: -1 (all bits set) where true, 0 where false.
using IntLanes = Int<kLaneCount>;
using UintLanes = UInt<kLaneCount>;

/// The columns of eight rows of eight floats: column j holds rows[i][j] in lane i. Eight
/// consecutive fields of eight records in eight loads and 24 shuffles, rather than 64 scalar
/// copies.
inline void load_columns(const float* const (&rows)[kLaneCount],
                         FloatLanes (&columns)[kLaneCount]) {
  __m256 r[kLaneCount];
  for (int i = 0; i < kLaneCount; ++i)
    r[i] = _mm256_loadu_ps(rows[i]);
  // Pairs of rows interleaved, then quadruples, then the halves of the register swapped in.
  __m256 pair[kLaneCount], quad[kLaneCount];
  for (int i = 0; i < kLaneCount; i += 2) {
    pair[i] = _mm256_unpacklo_ps(r[i], r[i + 1]);
    pair[i + 1] = _mm256_unpackhi_ps(r[i], r[i + 1]);
  }
  for (int i = 0; i < kLaneCount; i += 4) {
    quad[i] = _mm256_shuffle_ps(pair[i], pair[i + 2], _MM_SHUFFLE(1, 0, 1, 0));
    quad[i + 1] = _mm256_shuffle_ps(pair[i], pair[i + 2], _MM_SHUFFLE(3, 2, 3, 2));
    quad[i + 2] = _mm256_shuffle_ps(pair[i + 1], pair[i + 3], _MM_SHUFFLE(1, 0, 1, 0));
    quad[i + 3] = _mm256_shuffle_ps(pair[i + 1], pair[i + 3], _MM_SHUFFLE(3, 2, 3, 2));
  }
  for (int j = 0; j < 4; ++j) {
    columns[j] = std::bit_cast<FloatLanes>(_mm256_permute2f128_ps(quad[j], quad[j + 4], 0x20));
    columns[j + 4] = std::bit_cast<FloatLanes>(_mm256_permute2f128_ps(quad[j], quad[j + 4], 0x31));
  }
}

/// The most rows load_columns transposes at once: eight, sixteen with AVX-512.
#if defined(GLINT_AVX512)
inline constexpr int kMaxColumnRows = 2 * kLaneCount;
#else
inline constexpr int kMaxColumnRows = kLaneCount;
#endif

#if defined(GLINT_AVX512)
/// load_columns for sixteen rows, into sixteen lanes: column j holds rows[i][j] in lane i. Rows
/// i and i + 8 share a 512-bit register, one in each half, so that one transpose of eight such
/// registers transposes both halves at once (its in-lane shuffles act on every 128 bits; the
/// last step's exchange of 128-bit pieces becomes a two-source permutation): sixteen loads and
/// 24 shuffles, where two transposes of eight and the joining of their columns take 48 and
/// eight more.
inline void load_columns(const float* const (&rows)[2 * kLaneCount],
                         Float<2 * kLaneCount> (&columns)[kLaneCount]) {
  __m512 r[kLaneCount];
  for (int i = 0; i < kLaneCount; ++i)
    r[i] = _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_loadu_ps(rows[i])),
                              _mm256_loadu_ps(rows[i + kLaneCount]), 1);
  __m512 pair[kLaneCount], quad[kLaneCount];
  // (The masked forms with every lane set are the plain instructions; GCC 12's plain
  // intrinsics start from an undefined register, which -Wmaybe-uninitialized reports.)
  constexpr __mmask16 kAll = 0xffff;
  for (int i = 0; i < kLaneCount; i += 2) {
    pair[i] = _mm512_mask_unpacklo_ps(r[i], kAll, r[i], r[i + 1]);
    pair[i + 1] = _mm512_mask_unpackhi_ps(r[i], kAll, r[i], r[i + 1]);
  }
  for (int i = 0; i < kLaneCount; i += 4) {
    quad[i] = _mm512_shuffle_ps(pair[i], pair[i + 2], _MM_SHUFFLE(1, 0, 1, 0));
    quad[i + 1] = _mm512_shuffle_ps(pair[i], pair[i + 2], _MM_SHUFFLE(3, 2, 3, 2));
    quad[i + 2] = _mm512_shuffle_ps(pair[i + 1], pair[i + 3], _MM_SHUFFLE(1, 0, 1, 0));
    quad[i + 3] = _mm512_shuffle_ps(pair[i + 1], pair[i + 3], _MM_SHUFFLE(3, 2, 3, 2));
  }
  // The 128-bit pieces 0 and 2 (1 and 3) of quad[j] and quad[j + 4], alternately: in each half,
  // the low (high) pieces of the two, as _mm256_permute2f128_ps does for eight lanes.
  const __m512i low_pieces =
      _mm512_setr_epi32(0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25, 26, 27);
  const __m512i high_pieces =
      _mm512_setr_epi32(4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15, 28, 29, 30, 31);
  for (int j = 0; j < 4; ++j) {
    columns[j] = std::bit_cast<Float<2 * kLaneCount>>(
        _mm512_permutex2var_ps(quad[j], low_pieces, quad[j + 4]));
    columns[j + 4] = std::bit_cast<Float<2 * kLaneCount>>(
        _mm512_permutex2var_ps(quad[j], high_pieces, quad[j + 4]));
  }
}
#endif

/// Lane j of the result is lane order[j] of `v` (order's lanes in 0 .. 7).
inline FloatLanes permute(FloatLanes v, IntLanes order) {
  return std::bit_cast<FloatLanes>(_mm256_permutevar8x32_ps(__m256(v), __m256i(order)));
}
inline IntLanes permute(IntLanes v, IntLanes order) {
  return std::bit_cast<IntLanes>(_mm256_permutevar8x32_epi32(__m256i(v), __m256i(order)));
}

/// 0, 1, ... 7: each lane's index.
inline IntLanes lane_indices() {
  return IntLanes{0, 1, 2, 3, 4, 5, 6, 7};
}

/// The order that packs the lanes of `mask` (bit i for lane i) into the lowest lanes, lowest
/// first: permute(v, packing_order(mask)) holds them in lanes 0 .. popcount(mask)-1 (the
/// other lanes are unspecified). Appending eight paths' queued rays to a queue lane-wise, in
/// the order a loop over the lanes would append them.
inline IntLanes packing_order(std::uint32_t mask) {
  // For each of the 256 masks, the indices of its set bits, one per byte, lowest first.
  constexpr std::uint32_t kMasks = 1u << kLaneCount;
  static constexpr auto kOrders = [] {
    struct Table {
      std::uint64_t order[kMasks];
    } table{};
    for (std::uint32_t m = 0; m < kMasks; ++m) {
      int n = 0;
      for (std::uint32_t lane = 0; lane < std::uint32_t(kLaneCount); ++lane)
        if (m >> lane & 1u) table.order[m] |= std::uint64_t(lane) << (8 * n++);
    }
    return table;
  }();
  const __m128i bytes = _mm_cvtsi64_si128(std::int64_t(kOrders.order[mask & (kMasks - 1u)]));
  return std::bit_cast<IntLanes>(_mm256_cvtepu8_epi32(bytes));
}

/// A packing_order rotated by `at` lanes: the lanes it packs, lowest first, in lanes at, at+1,
/// ... (mod 8), where a queue of blocks of eight whose last block holds `at` entries continues.
inline IntLanes rotated_order(IntLanes packing, int at) {
  return permute(packing, (lane_indices() - at) & (kLaneCount - 1));
}

/// Eight 3-vectors, one per lane, in structure-of-arrays form.
using Vec3Lanes = Vector3<FloatLanes>;

}  // namespace glint::inline GLINT_ISA_NAMESPACE
#endif  // GLINT_AVX2
