#pragma once
// Eight floats or ints in one AVX register: the arithmetic the wavefront renderer's stages do
// for eight paths at once, lane i being path i of a block. GCC and Clang vector extensions give
// the operators (+ - * / and comparisons, which yield -1 or 0 per lane); the few operations
// they lack are written here: select, the minimum and maximum with std::min/max's rule for NaN,
// sqrt and sin/cos. Defined only with GLINT_AVX2 (geometry/simd.hpp): without AVX a 32-byte
// vector has no register, and passing one would change the calling convention. Everything
// lane-wise (the warps' and policies' lane forms) sits under the same switch.
//
// Not IEEE-identical to the scalar code: sin and cos are polynomials (within 2 ulp of the
// library's over the angles the warps use), and the compiler fuses multiply-adds in its own way.

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "glint/geometry/simd.hpp"
#include "glint/math/vector.hpp"

#if defined(GLINT_AVX2)
namespace glint {

inline constexpr int kLaneCount = 8;

using FloatLanes = float __attribute__((vector_size(32)));
/// Integers, and the masks comparisons give: -1 (all bits set) where true, 0 where false.
using IntLanes = std::int32_t __attribute__((vector_size(32)));
using UintLanes = std::uint32_t __attribute__((vector_size(32)));

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

/// `if_true` where `mask` is true, `if_false` elsewhere.
inline FloatLanes select(IntLanes mask, FloatLanes if_true, FloatLanes if_false) {
  return std::bit_cast<FloatLanes>((std::bit_cast<IntLanes>(if_true) & mask) |
                                   (std::bit_cast<IntLanes>(if_false) & ~mask));
}
inline IntLanes select(IntLanes mask, IntLanes if_true, IntLanes if_false) {
  return (if_true & mask) | (if_false & ~mask);
}
inline UintLanes select(IntLanes mask, UintLanes if_true, UintLanes if_false) {
  const auto m = std::bit_cast<UintLanes>(mask);
  return (if_true & m) | (if_false & ~m);
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

/// std::min and std::max lane by lane, with their rule for NaN: the first argument unless the
/// comparison holds.
inline FloatLanes min_lanes(FloatLanes a, FloatLanes b) {
  return select(b < a, b, a);
}
inline FloatLanes max_lanes(FloatLanes a, FloatLanes b) {
  return select(a < b, b, a);
}

inline FloatLanes abs_lanes(FloatLanes x) {
  return std::bit_cast<FloatLanes>(std::bit_cast<IntLanes>(x) & 0x7fffffff);
}
/// std::copysign(magnitude, sign) lane by lane (-0 counts as negative).
inline FloatLanes copysign_lanes(FloatLanes magnitude, FloatLanes sign) {
  return std::bit_cast<FloatLanes>((std::bit_cast<IntLanes>(magnitude) & 0x7fffffff) |
                                   (std::bit_cast<IntLanes>(sign) & std::int32_t(0x80000000u)));
}

inline FloatLanes sqrt_lanes(FloatLanes x) {
  return _mm256_sqrt_ps(x);
}

/// sin(x) and cos(x) for 0 <= x <= 2^16 (the warps' angles are in [0, 2 pi]): the argument is
/// reduced to [-pi/4, pi/4] around a multiple of pi/2 in three parts (Cody and Waite), then
/// minimax polynomials of degree 7 and 8 (those of Cephes' sinf and cosf).
inline void sincos_lanes(FloatLanes x, FloatLanes& sine, FloatLanes& cosine) {
  const IntLanes octant = __builtin_convertvector(x * 1.27323954473516f, IntLanes);
  const IntLanes even = (octant + 1) & ~1;  // the nearest multiple of pi/2, in units of pi/4
  const FloatLanes k = __builtin_convertvector(even, FloatLanes);
  const FloatLanes r =
      ((x - k * 0.78515625f) - k * 2.4187564849853515625e-4f) - k * 3.77489497744594108e-8f;
  const FloatLanes r2 = r * r;
  const FloatLanes sin_r =
      ((-1.9515295891e-4f * r2 + 8.3321608736e-3f) * r2 - 1.6666654611e-1f) * r2 * r + r;
  const FloatLanes cos_r =
      ((2.443315711809948e-5f * r2 - 1.388731625493765e-3f) * r2 + 4.166664568298827e-2f) * r2 *
          r2 -
      0.5f * r2 + 1.0f;
  const IntLanes quadrant = even >> 1;
  const IntLanes swap = (quadrant & 1) != 0;
  const FloatLanes s = select(swap, cos_r, sin_r);
  const FloatLanes c = select(swap, sin_r, cos_r);
  // sin is negative in quadrants 2 and 3, cos in 1 and 2.
  const IntLanes sin_sign = (quadrant & 2) << 30;
  const IntLanes cos_sign = ((quadrant + 1) & 2) << 30;
  sine = std::bit_cast<FloatLanes>(std::bit_cast<IntLanes>(s) ^ sin_sign);
  cosine = std::bit_cast<FloatLanes>(std::bit_cast<IntLanes>(c) ^ cos_sign);
}

/// The natural logarithm of x for positive normal x: x = m 2^e with m in [sqrt(1/2), sqrt(2)),
/// then Cephes logf's polynomial for log(m) and log(2) in two parts.
inline FloatLanes log_lanes(FloatLanes x) {
  const IntLanes bits = std::bit_cast<IntLanes>(x);
  IntLanes exponent = ((bits >> 23) & 0xff) - 126;
  FloatLanes m = std::bit_cast<FloatLanes>((bits & 0x007fffff) | 0x3f000000);  // [0.5, 1)
  const IntLanes small = m < 0.707106781186547524f;
  exponent += small;  // -1 where small
  m = select(small, m + m, m) - 1.0f;
  const FloatLanes e = __builtin_convertvector(exponent, FloatLanes);
  const FloatLanes z = m * m;
  FloatLanes y = 7.0376836292e-2f * m - 1.1514610310e-1f;
  y = y * m + 1.1676998740e-1f;
  y = y * m - 1.2420140846e-1f;
  y = y * m + 1.4249322787e-1f;
  y = y * m - 1.6668057665e-1f;
  y = y * m + 2.0000714765e-1f;
  y = y * m - 2.4999993993e-1f;
  y = y * m + 3.3333331174e-1f;
  y = y * m * z;
  y += -2.12194440e-4f * e;
  y += -0.5f * z;
  return m + y + 0.693359375f * e;
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

struct Vec2Lanes {
  FloatLanes x, y;
};

/// Eight 3-vectors, one per lane, in structure-of-arrays form.
struct Vec3Lanes {
  FloatLanes x, y, z;

  static Vec3Lanes broadcast(const Vec3& v) {
    return {glint::broadcast(v.x), glint::broadcast(v.y), glint::broadcast(v.z)};
  }
  Vec3 lane(int i) const { return {x[i], y[i], z[i]}; }
  void set_lane(int i, const Vec3& v) {
    x[i] = v.x;
    y[i] = v.y;
    z[i] = v.z;
  }

  friend Vec3Lanes operator+(const Vec3Lanes& a, const Vec3Lanes& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
  }
  friend Vec3Lanes operator-(const Vec3Lanes& a, const Vec3Lanes& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
  }
  friend Vec3Lanes operator-(const Vec3Lanes& a) { return {-a.x, -a.y, -a.z}; }
  friend Vec3Lanes operator*(const Vec3Lanes& a, const Vec3Lanes& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
  }
  friend Vec3Lanes operator*(float s, const Vec3Lanes& a) { return {s * a.x, s * a.y, s * a.z}; }
  friend Vec3Lanes operator*(FloatLanes s, const Vec3Lanes& a) {
    return {s * a.x, s * a.y, s * a.z};
  }
  friend Vec3Lanes operator*(const Vec3Lanes& a, FloatLanes s) {
    return {a.x * s, a.y * s, a.z * s};
  }
  friend Vec3Lanes operator/(const Vec3Lanes& a, FloatLanes s) {
    return {a.x / s, a.y / s, a.z / s};
  }
  Vec3Lanes& operator+=(const Vec3Lanes& b) { return *this = *this + b; }
  Vec3Lanes& operator*=(const Vec3Lanes& b) { return *this = *this * b; }
};

inline FloatLanes dot(const Vec3Lanes& a, const Vec3Lanes& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
/// As glm::normalize: times the reciprocal of the length (one division, not three).
inline Vec3Lanes normalize(const Vec3Lanes& v) {
  return (1.0f / sqrt_lanes(dot(v, v))) * v;
}
inline Vec3Lanes select(IntLanes mask, const Vec3Lanes& if_true, const Vec3Lanes& if_false) {
  return {select(mask, if_true.x, if_false.x), select(mask, if_true.y, if_false.y),
          select(mask, if_true.z, if_false.z)};
}
/// glint::max_component lane by lane, with max_of's rule for NaN.
inline FloatLanes max_component(const Vec3Lanes& v) {
  const auto max_of = [](FloatLanes a, FloatLanes b) { return select(a > b, a, b); };
  return max_of(v.x, max_of(v.y, v.z));
}

}  // namespace glint
#endif  // GLINT_AVX2
