#pragma once
// The eight-lane width of math/wide.hpp as the wavefront renderer's stages use it, lane i being
// path i of a block, with what AVX2 adds to the width-generic operations: lane masks as bits,
// transposes, permutations and the packing of lanes into queues, 64-bit lanes for the samplers'
// hashes. Defined only with GLINT_AVX2 (geometry/simd.hpp).

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "glint/geometry/simd.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"

#if defined(GLINT_AVX2)
namespace glint {

inline constexpr int kLaneCount = 8;

using FloatLanes = Float<kLaneCount>;
/// Integers, and the masks comparisons give: -1 (all bits set) where true, 0 where false.
using IntLanes = Int<kLaneCount>;
using UintLanes = UInt<kLaneCount>;

inline FloatLanes broadcast(float value) {
  return FloatLanes{} + value;
}
inline IntLanes broadcast(std::int32_t value) {
  return IntLanes{} + value;
}

inline FloatLanes load_lanes(const float* from) {
  FloatLanes lanes;
  std::memcpy(&lanes, from, sizeof lanes);
  return lanes;
}
inline IntLanes load_lanes(const std::int32_t* from) {
  IntLanes lanes;
  std::memcpy(&lanes, from, sizeof lanes);
  return lanes;
}
inline void store_lanes(float* to, FloatLanes lanes) {
  std::memcpy(to, &lanes, sizeof lanes);
}
inline void store_lanes(std::int32_t* to, IntLanes lanes) {
  std::memcpy(to, &lanes, sizeof lanes);
}

/// Bit i set where lane i of `mask` is true.
inline std::uint32_t lane_bits(IntLanes mask) {
  return std::uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(__m256i(mask))));
}
/// The mask with lane i true where bit i of `bits` is set.
inline IntLanes lanes_of_bits(std::uint32_t bits) {
  return std::bit_cast<IntLanes>(avx2::lane_vector(bits));
}

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
  static constexpr auto kOrders = [] {
    struct Table {
      std::uint64_t order[256];
    } table{};
    for (std::uint32_t m = 0; m < 256; ++m) {
      int n = 0;
      for (std::uint32_t lane = 0; lane < 8; ++lane)
        if (m >> lane & 1u) table.order[m] |= std::uint64_t(lane) << (8 * n++);
    }
    return table;
  }();
  const __m128i bytes = _mm_cvtsi64_si128(std::int64_t(kOrders.order[mask & 0xffu]));
  return std::bit_cast<IntLanes>(_mm256_cvtepu8_epi32(bytes));
}

/// A packing_order rotated by `at` lanes: the lanes it packs, lowest first, in lanes at, at+1,
/// ... (mod 8), where a queue of blocks of eight whose last block holds `at` entries continues.
inline IntLanes rotated_order(IntLanes packing, int at) {
  return permute(packing, (lane_indices() - at) & 7);
}

/// bits_to_unit_float lane by lane: the top 24 bits as a float in [0, 1), exactly.
inline FloatLanes unit_floats(UintLanes bits) {
  return __builtin_convertvector(std::bit_cast<IntLanes>(bits >> 8), FloatLanes) * 0x1p-24f;
}

/// Eight 64-bit integers: lanes 0-3 and 4-7 in two AVX registers (the multiplications are
/// AVX-512's where the compiler targets it, three 32-bit ones each otherwise).
struct Uint64Lanes {
  using Half = std::uint64_t __attribute__((vector_size(32)));
  Half low, high;

  static Uint64Lanes broadcast(std::uint64_t value) { return {Half{} + value, Half{} + value}; }
  /// Zero-extended.
  static Uint64Lanes from(UintLanes v) {
    using Four = std::uint32_t __attribute__((vector_size(16)));
    const Four low4 = __builtin_shufflevector(v, v, 0, 1, 2, 3);
    const Four high4 = __builtin_shufflevector(v, v, 4, 5, 6, 7);
    return {__builtin_convertvector(low4, Half), __builtin_convertvector(high4, Half)};
  }
  /// The low 32 bits of each lane.
  UintLanes low_bits() const {
#if defined(__AVX512VL__)
    using Four = std::uint32_t __attribute__((vector_size(16)));
    const Four a = __builtin_convertvector(low, Four);
    const Four b = __builtin_convertvector(high, Four);
    return __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7);
#else
    // Without AVX-512's narrowing moves, GCC builds this from fifteen instructions; two do it:
    // the even 32-bit words of both halves, then their 64-bit pairs in lane order.
    const __m256 words = _mm256_shuffle_ps(_mm256_castsi256_ps(__m256i(low)),
                                           _mm256_castsi256_ps(__m256i(high)), 0b10'00'10'00);
    return std::bit_cast<UintLanes>(
        _mm256_permute4x64_epi64(_mm256_castps_si256(words), 0b11'01'10'00));
#endif
  }
  UintLanes high_bits() const {
    return (*this >> 32).low_bits();
  }
  std::uint64_t lane(int i) const {
    return i < 4 ? low[i] : high[i - 4];
  }
  void set_lane(int i, std::uint64_t value) {
    if (i < 4)
      low[i] = value;
    else
      high[i - 4] = value;
  }

  friend Uint64Lanes operator+(const Uint64Lanes& a, const Uint64Lanes& b) {
    return {a.low + b.low, a.high + b.high};
  }
  friend Uint64Lanes operator*(const Uint64Lanes& a, const Uint64Lanes& b) {
    return {a.low * b.low, a.high * b.high};
  }
  friend Uint64Lanes operator^(const Uint64Lanes& a, const Uint64Lanes& b) {
    return {a.low ^ b.low, a.high ^ b.high};
  }
  friend Uint64Lanes operator|(const Uint64Lanes& a, const Uint64Lanes& b) {
    return {a.low | b.low, a.high | b.high};
  }
  friend Uint64Lanes operator>>(const Uint64Lanes& a, int shift) {
    return {a.low >> shift, a.high >> shift};
  }
  friend Uint64Lanes operator<<(const Uint64Lanes& a, int shift) {
    return {a.low << shift, a.high << shift};
  }
};

/// `if_true` in the lanes where `mask` is true.
inline Uint64Lanes select(IntLanes mask, const Uint64Lanes& if_true, const Uint64Lanes& if_false) {
  using Four = std::int32_t __attribute__((vector_size(16)));
  using Wide = std::int64_t __attribute__((vector_size(32)));
  const Four low4 = __builtin_shufflevector(mask, mask, 0, 1, 2, 3);
  const Four high4 = __builtin_shufflevector(mask, mask, 4, 5, 6, 7);
  const auto low = std::bit_cast<Uint64Lanes::Half>(__builtin_convertvector(low4, Wide));
  const auto high = std::bit_cast<Uint64Lanes::Half>(__builtin_convertvector(high4, Wide));
  return {(if_true.low & low) | (if_false.low & ~low),
          (if_true.high & high) | (if_false.high & ~high)};
}

using Vec2Lanes = Vector2<FloatLanes>;
/// Eight 3-vectors, one per lane, in structure-of-arrays form.
using Vec3Lanes = Vector3<FloatLanes>;

}  // namespace glint
#endif  // GLINT_AVX2
