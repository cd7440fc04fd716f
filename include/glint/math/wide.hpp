#pragma once
// The numbers glint's physics is written in, at any width: Float<W>, Int<W>, UInt<W> and
// Mask<W> hold W lanes, one path per lane. At width 1 they are plain float, int32_t, uint32_t
// and bool, so a formula instantiated at width 1 is ordinary scalar code; at widths 8 (one AVX2
// register) and 16 (one AVX-512 register) they are GCC/Clang vector types, whose operators act
// lane by lane and whose comparisons give masks of -1 (true) or 0 per lane. A formula is
// written once, as a template over its Float type, with the operators and the functions below
// (select, min, max, abs, sqrt, copysign, conversions): the same IEEE operations in the same
// order in every lane, so that with -ffp-contract=off (glint's CMake target sets it) every
// width gives the same bits.
//
// Vec2For<F> and Vec3For<F> are the 2- and 3-vectors over F: glm's vec2 and vec3 at width 1,
// Vector2<F> and Vector3<F> (structures of arrays) wider. Templates take vectors as their own
// parameter type and find the Float type with FloatOf, so that callers never name a width.
//
// Vector types are defined whatever the compiler targets: without AVX the compiler carries out
// a 32- or 64-byte vector's operations in narrower registers, slower but with the same results.

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

#if defined(__AVX__) || defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace glint::inline GLINT_ISA_NAMESPACE {

namespace detail {
template <int W>
struct LaneTypes;
template <>
struct LaneTypes<1> {
  using Float = float;
  using Int = std::int32_t;
  using UInt = std::uint32_t;
  using Mask = bool;
};
// Spelt out per width: GCC drops a vector_size whose size depends on a template parameter.
template <>
struct LaneTypes<8> {
  using Float = float __attribute__((vector_size(32)));
  using Int = std::int32_t __attribute__((vector_size(32)));
  using UInt = std::uint32_t __attribute__((vector_size(32)));
  using Mask = Int;  // what comparisons of Float or Int give: -1 or 0 per lane
};
template <>
struct LaneTypes<16> {
  using Float = float __attribute__((vector_size(64)));
  using Int = std::int32_t __attribute__((vector_size(64)));
  using UInt = std::uint32_t __attribute__((vector_size(64)));
  using Mask = Int;
};
}  // namespace detail

template <int W>
using Float = typename detail::LaneTypes<W>::Float;
template <int W>
using Int = typename detail::LaneTypes<W>::Int;
template <int W>
using UInt = typename detail::LaneTypes<W>::UInt;
template <int W>
using Mask = typename detail::LaneTypes<W>::Mask;

/// The number of lanes of a Float, Int, UInt or Mask type.
template <typename T>
inline constexpr int kLanesOf = std::is_scalar_v<T> ? 1 : int(sizeof(T) / 4);

/// The Int, UInt and Mask types of Float type F's width.
template <typename F>
using IntFor = Int<kLanesOf<F>>;
template <typename F>
using UIntFor = UInt<kLanesOf<F>>;
template <typename F>
using MaskFor = Mask<kLanesOf<F>>;

/// Whether T is one of the Float types.
template <typename T>
concept FloatType =
    std::is_same_v<T, Float<1>> || std::is_same_v<T, Float<8>> || std::is_same_v<T, Float<16>>;
/// Whether T is a Float, Int or UInt type of more than one lane (a Mask is an Int there).
template <typename T>
concept WideNumber =
    std::is_same_v<T, Float<8>> || std::is_same_v<T, Int<8>> || std::is_same_v<T, UInt<8>> ||
    std::is_same_v<T, Float<16>> || std::is_same_v<T, Int<16>> || std::is_same_v<T, UInt<16>>;

// ---- lanes: broadcast, access, loads and stores ------------------------------------------

/// `value` in every lane.
template <typename T, typename S>
inline T splat(S value) {
  if constexpr (kLanesOf<T> == 1)
    return T(value);
  else
    return T{} + value;
}

/// Lane i of a value (width 1: the value).
template <typename T>
inline auto lane(const T& value, int i) {
  if constexpr (kLanesOf<T> == 1) {
    (void)i;
    return value;
  } else {
    return value[i];
  }
}
template <typename T, typename S>
inline void set_lane(T& value, int i, S to) {
  if constexpr (kLanesOf<T> == 1) {
    (void)i;
    value = T(to);
  } else {
    value[i] = to;
  }
}

/// kLanesOf<T> consecutive values from `from`, and back.
template <typename T, typename S>
inline T load(const S* from) {
  static_assert(sizeof(S) * kLanesOf<T> == sizeof(T));
  T value;
  std::memcpy(&value, from, sizeof value);
  return value;
}
template <typename T, typename S>
inline void store(S* to, const T& value) {
  static_assert(sizeof(S) * kLanesOf<T> == sizeof(T));
  std::memcpy(to, &value, sizeof value);
}

// ---- masks ---------------------------------------------------------------------------------

/// The mask of type M that is `value` in every lane (true is -1 in a wide lane).
template <typename M>
inline M mask_of(bool value) {
  return splat<M>(value ? -1 : 0);
}

/// Whether any, or every, lane of a mask is true.
inline bool any(bool mask) {
  return mask;
}
inline bool all(bool mask) {
  return mask;
}
template <WideNumber M>
inline bool any(M mask) {
#if defined(__AVX512F__)
  if constexpr (kLanesOf<M> == 16) {
    const __m512i v = std::bit_cast<__m512i>(mask);
    return _mm512_test_epi32_mask(v, v) != 0;
  }
#endif
#if defined(__AVX__)
  if constexpr (kLanesOf<M> == 8) {
    const __m256i v = std::bit_cast<__m256i>(mask);
    return !_mm256_testz_si256(v, v);
  }
#endif
  M folded = mask;
  for (int i = 1; i < kLanesOf<M>; ++i)
    folded[0] |= mask[i];
  return folded[0] != 0;
}
template <WideNumber M>
inline bool all(M mask) {
  return !any(~mask);
}

/// `if_true` in the lanes where `mask` is true, `if_false` in the others.
template <typename T>
inline T select(bool mask, T if_true, T if_false) {
  return mask ? if_true : if_false;
}
template <WideNumber M, WideNumber T>
requires(kLanesOf<M> == kLanesOf<T>) inline T select(M mask, T if_true, T if_false) {
#if defined(__AVX__) && !defined(__AVX512VL__)
  // One blend by the masks' sign bits (all ones or all zeros), where AVX-512 does not make the
  // three-operation form one instruction (vpternlogd).
  if constexpr (kLanesOf<T> == 8) {
    return std::bit_cast<T>(_mm256_blendv_ps(std::bit_cast<__m256>(if_false),
                                             std::bit_cast<__m256>(if_true),
                                             std::bit_cast<__m256>(mask)));
  }
#endif
  if constexpr (std::is_same_v<T, M>) {
    return (if_true & mask) | (if_false & ~mask);
  } else {
    using Bits = decltype(mask);
    return std::bit_cast<T>((std::bit_cast<Bits>(if_true) & mask) |
                            (std::bit_cast<Bits>(if_false) & ~mask));
  }
}

// ---- arithmetic ------------------------------------------------------------------------------

/// std::min and std::max lane by lane, with their rule for NaN: the first argument unless the
/// comparison holds.
template <FloatType F>
inline F min(F a, F b) {
  return select(b < a, b, a);
}
template <FloatType F>
inline F max(F a, F b) {
  return select(a < b, b, a);
}

template <FloatType F>
inline F abs(F x) {
  if constexpr (kLanesOf<F> == 1)
    return std::fabs(x);
  else
    return std::bit_cast<F>(std::bit_cast<IntFor<F>>(x) & 0x7fffffff);
}

/// std::copysign lane by lane (-0 counts as negative).
template <FloatType F>
inline F copysign(F magnitude, F sign) {
  if constexpr (kLanesOf<F> == 1) {
    return std::copysign(magnitude, sign);
  } else {
    using I = IntFor<F>;
    return std::bit_cast<F>((std::bit_cast<I>(magnitude) & 0x7fffffff) |
                            (std::bit_cast<I>(sign) & std::int32_t(0x80000000u)));
  }
}

/// The correctly rounded square root (IEEE), so the same in every lane and at every width.
template <FloatType F>
inline F sqrt(F x) {
  if constexpr (kLanesOf<F> == 1) {
    return std::sqrt(x);
#if defined(__AVX512F__)
  } else if constexpr (kLanesOf<F> == 16) {
    // The masked form: the plain one starts from an undefined register, which GCC 12 reports
    // as used uninitialised.
    const __m512 v = std::bit_cast<__m512>(x);
    return std::bit_cast<F>(_mm512_mask_sqrt_ps(v, __mmask16(0xffff), v));
#endif
#if defined(__AVX__)
  } else if constexpr (kLanesOf<F> == 8) {
    return std::bit_cast<F>(_mm256_sqrt_ps(std::bit_cast<__m256>(x)));
#endif
  } else {
    F result;
    for (int i = 0; i < kLanesOf<F>; ++i)
      result[i] = __builtin_sqrtf(x[i]);
    return result;
  }
}

/// Conversions lane by lane: Int to Float (exact below 2^24) and Float to Int truncated towards
/// zero (for values inside the Int range).
template <typename I>
inline auto to_float(I value) {
  if constexpr (kLanesOf<I> == 1)
    return float(value);
  else
    return __builtin_convertvector(value, Float<kLanesOf<I>>);
}
template <FloatType F>
inline IntFor<F> truncate_to_int(F value) {
  if constexpr (kLanesOf<F> == 1)
    return std::int32_t(value);
  else
    return __builtin_convertvector(value, IntFor<F>);
}

/// The bits of a Float as an Int, and back.
template <FloatType F>
inline IntFor<F> bits_of(F value) {
  return std::bit_cast<IntFor<F>>(value);
}
template <typename I>
inline Float<kLanesOf<I>> float_of_bits(I bits) {
  return std::bit_cast<Float<kLanesOf<I>>>(bits);
}

// ---- vectors ---------------------------------------------------------------------------------

/// Two and three lanes-wide numbers: lane i of x, y (and z) is the vector of path i.
template <typename F>
struct Vector2 {
  F x, y;
};

template <typename F>
struct Vector3 {
  F x, y, z;

  static Vector3 broadcast(const Vec3& v) { return {splat<F>(v.x), splat<F>(v.y), splat<F>(v.z)}; }
  Vec3 lane(int i) const { return {x[i], y[i], z[i]}; }
  void set_lane(int i, const Vec3& v) {
    x[i] = v.x;
    y[i] = v.y;
    z[i] = v.z;
  }

  friend Vector3 operator+(const Vector3& a, const Vector3& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
  }
  friend Vector3 operator-(const Vector3& a, const Vector3& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
  }
  friend Vector3 operator-(const Vector3& a) { return {-a.x, -a.y, -a.z}; }
  friend Vector3 operator*(const Vector3& a, const Vector3& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
  }
  friend Vector3 operator*(float s, const Vector3& a) { return {s * a.x, s * a.y, s * a.z}; }
  friend Vector3 operator*(F s, const Vector3& a) { return {s * a.x, s * a.y, s * a.z}; }
  friend Vector3 operator*(const Vector3& a, F s) { return {a.x * s, a.y * s, a.z * s}; }
  friend Vector3 operator/(const Vector3& a, F s) { return {a.x / s, a.y / s, a.z / s}; }
  Vector3& operator+=(const Vector3& b) { return *this = *this + b; }
  Vector3& operator*=(const Vector3& b) { return *this = *this * b; }
};

/// Lane i of a vector (width 1: the vector).
inline Vec3 lane(const Vec3& v, int) {
  return v;
}
template <typename F>
inline Vec3 lane(const Vector3<F>& v, int i) {
  return v.lane(i);
}
inline void set_lane(Vec3& v, int, const Vec3& to) {
  v = to;
}
template <typename F>
inline void set_lane(Vector3<F>& v, int i, const Vec3& to) {
  v.set_lane(i, to);
}

/// glint::max_component lane by lane (max_of's rule for NaN: the second unless the first is
/// greater).
template <typename F>
inline F max_component(const Vector3<F>& v) {
  const auto max_of = [](F a, F b) { return select(a > b, a, b); };
  return max_of(v.x, max_of(v.y, v.z));
}

/// `v` in every lane of a Vec3 or Vector3 type V.
template <typename V>
inline V splat_vector(const Vec3& v) {
  if constexpr (std::is_same_v<V, Vec3>)
    return v;
  else
    return V::broadcast(v);
}

template <typename F>
using Vec2For = std::conditional_t<kLanesOf<F> == 1, Vec2, Vector2<F>>;
template <typename F>
using Vec3For = std::conditional_t<kLanesOf<F> == 1, Vec3, Vector3<F>>;

/// The Float type of a vector type (Vec2, Vec3, Vector2<F>, Vector3<F>).
template <typename V>
using FloatOf = std::remove_cvref_t<decltype(std::declval<V>().x)>;

/// glm::dot's order of operations: (x + y) + z.
template <typename F>
inline F dot(const Vector3<F>& a, const Vector3<F>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
/// As glm::normalize: times the reciprocal of the length (one division, not three).
template <typename F>
inline Vector3<F> normalize(const Vector3<F>& v) {
  return (1.0f / sqrt(dot(v, v))) * v;
}
template <typename M, typename F>
inline Vector3<F> select(M mask, const Vector3<F>& if_true, const Vector3<F>& if_false) {
  return {select(mask, if_true.x, if_false.x), select(mask, if_true.y, if_false.y),
          select(mask, if_true.z, if_false.z)};
}
inline Vec3 select(bool mask, const Vec3& if_true, const Vec3& if_false) {
  return mask ? if_true : if_false;
}

// ---- halves and lane bits ------------------------------------------------------------------

/// The lower and upper halves of a 16-lane value as 8-lane values, and back.
template <WideNumber T>
requires(kLanesOf<T> == 16) inline auto low_half(T v) {
  return __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7);
}
template <WideNumber T>
requires(kLanesOf<T> == 16) inline auto high_half(T v) {
  return __builtin_shufflevector(v, v, 8, 9, 10, 11, 12, 13, 14, 15);
}
template <WideNumber T>
requires(kLanesOf<T> == 8) inline auto join(T low, T high) {
  return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}

/// The lanes of a mask as bits (bit i: lane i), and the mask of type M whose lane i is bit i
/// of `bits`.
inline std::uint32_t bits_of_mask(bool mask) {
  return mask ? 1u : 0u;
}
template <WideNumber M>
inline std::uint32_t bits_of_mask(M mask) {
#if defined(__AVX__)
  if constexpr (kLanesOf<M> == 8)
    return std::uint32_t(_mm256_movemask_ps(std::bit_cast<__m256>(mask)));
  if constexpr (kLanesOf<M> == 16)
    return bits_of_mask(low_half(mask)) | bits_of_mask(high_half(mask)) << 8;
#endif
  std::uint32_t bits = 0;
  for (int i = 0; i < kLanesOf<M>; ++i)
    bits |= (mask[i] != 0 ? 1u : 0u) << i;
  return bits;
}
template <typename M>
inline M mask_of_bits(std::uint32_t bits) {
  if constexpr (kLanesOf<M> == 1) {
    return (bits & 1u) != 0;
  } else {
    M lane_bit{};
    for (int i = 0; i < kLanesOf<M>; ++i)
      lane_bit[i] = std::int32_t(1u << i);
    return (splat<M>(std::int32_t(bits)) & lane_bit) != 0;
  }
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE

// ---- 64-bit lanes ----------------------------------------------------------------------------
// UInt64<W>: W lanes of 64-bit unsigned integers, for the samplers' hashes and generators.
// Integer arithmetic wraps modulo 2^64 in every lane, so a hash computed in lanes is bit for bit
// the one computed at width 1 (std::uint64_t). Wider, the lanes are held in pieces of one
// register each: 8 lanes with AVX-512 (whose DQ extension multiplies 64-bit lanes in one
// instruction), 4 with AVX2 (three 32-bit multiplications each), 2 otherwise. Pieces rather than
// one vector type of W lanes, because GCC keeps a vector type wider than the registers in
// memory and copies it through general registers when it is a class member: the samplers' draws
// then cost half as much again with AVX2.

namespace glint::inline GLINT_ISA_NAMESPACE {

namespace detail {

#if defined(__AVX512F__)
inline constexpr int kPiece64Lanes = 8;
using Piece64 = std::uint64_t __attribute__((vector_size(64)));
using Piece64Signed = std::int64_t __attribute__((vector_size(64)));
using Piece32 = std::uint32_t __attribute__((vector_size(32)));
#elif defined(__AVX2__)
inline constexpr int kPiece64Lanes = 4;
using Piece64 = std::uint64_t __attribute__((vector_size(32)));
using Piece64Signed = std::int64_t __attribute__((vector_size(32)));
using Piece32 = std::uint32_t __attribute__((vector_size(16)));
#else
inline constexpr int kPiece64Lanes = 2;
using Piece64 = std::uint64_t __attribute__((vector_size(16)));
using Piece64Signed = std::int64_t __attribute__((vector_size(16)));
using Piece32 = std::uint32_t __attribute__((vector_size(8)));
#endif

/// Lanes k*P .. k*P + P - 1 of a vector (P = kPiece64Lanes).
template <int K, typename V>
inline auto piece_of(V v) {
  return [&]<int... I>(std::integer_sequence<int, I...>) {
    return __builtin_shufflevector(v, v, (K * kPiece64Lanes + I)...);
  }
  (std::make_integer_sequence<int, kPiece64Lanes>{});
}

/// W 64-bit lanes in W / kPiece64Lanes registers.
template <int W>
struct Lanes64 {
  static constexpr int kPieces = W / kPiece64Lanes;
  Piece64 piece[kPieces];

  /// f(piece k of a, k) for each piece, k a std::integral_constant.
  template <typename F>
  static Lanes64 map(const Lanes64& a, F f) {
    Lanes64 r;
    [&]<int... K>(std::integer_sequence<int, K...>) {
      ((r.piece[K] = f(a.piece[K], std::integral_constant<int, K>{})), ...);
    }
    (std::make_integer_sequence<int, kPieces>{});
    return r;
  }

  std::uint64_t operator[](int i) const { return piece[i / kPiece64Lanes][i % kPiece64Lanes]; }

  friend Lanes64 operator+(const Lanes64& a, const Lanes64& b) {
    return map(a, [&](Piece64 p, auto k) { return p + b.piece[k]; });
  }
  friend Lanes64 operator*(const Lanes64& a, const Lanes64& b) {
    return map(a, [&](Piece64 p, auto k) { return p * b.piece[k]; });
  }
  friend Lanes64 operator^(const Lanes64& a, const Lanes64& b) {
    return map(a, [&](Piece64 p, auto k) { return p ^ b.piece[k]; });
  }
  friend Lanes64 operator|(const Lanes64& a, const Lanes64& b) {
    return map(a, [&](Piece64 p, auto k) { return p | b.piece[k]; });
  }
  friend Lanes64 operator&(const Lanes64& a, const Lanes64& b) {
    return map(a, [&](Piece64 p, auto k) { return p & b.piece[k]; });
  }
  friend Lanes64 operator+(const Lanes64& a, std::uint64_t b) {
    return map(a, [&](Piece64 p, auto) { return p + b; });
  }
  friend Lanes64 operator*(const Lanes64& a, std::uint64_t b) {
    return map(a, [&](Piece64 p, auto) { return p * b; });
  }
  friend Lanes64 operator^(const Lanes64& a, std::uint64_t b) {
    return map(a, [&](Piece64 p, auto) { return p ^ b; });
  }
  friend Lanes64 operator|(const Lanes64& a, std::uint64_t b) {
    return map(a, [&](Piece64 p, auto) { return p | b; });
  }
  friend Lanes64 operator>>(const Lanes64& a, int shift) {
    return map(a, [&](Piece64 p, auto) { return p >> shift; });
  }
  friend Lanes64 operator<<(const Lanes64& a, int shift) {
    return map(a, [&](Piece64 p, auto) { return p << shift; });
  }
  Lanes64& operator^=(const Lanes64& b) { return *this = *this ^ b; }
  Lanes64& operator*=(std::uint64_t b) { return *this = *this * b; }
};

template <int W>
struct LaneTypes64 {
  using UInt64 = Lanes64<W>;
};
template <>
struct LaneTypes64<1> {
  using UInt64 = std::uint64_t;
};

}  // namespace detail

template <int W>
using UInt64 = typename detail::LaneTypes64<W>::UInt64;

/// Whether T is one of the UInt64 types.
template <typename T>
concept UInt64Type =
    std::is_same_v<T, UInt64<1>> || std::is_same_v<T, UInt64<8>> || std::is_same_v<T, UInt64<16>>;

/// The number of lanes of a UInt64 type (kLanesOf counts 32-bit lanes).
template <UInt64Type T>
inline constexpr int kLanes64Of = int(sizeof(T) / 8);

/// The UInt64 type with as many lanes as the Float, Int or UInt type T.
template <typename T>
using UInt64For = UInt64<kLanesOf<T>>;

/// `value` in every lane of a UInt64 type.
template <UInt64Type U>
constexpr U splat64(std::uint64_t value) {
  return U{} + value;
}

/// Lane i of UInt64<W> set to `to` (glint::lane reads it).
template <int W, typename S>
inline void set_lane(detail::Lanes64<W>& value, int i, S to) {
  value.piece[i / detail::kPiece64Lanes][i % detail::kPiece64Lanes] = std::uint64_t(to);
}

/// A UInt's lanes zero-extended to 64 bits.
template <typename U>
requires std::is_same_v<U, UInt<kLanesOf<U>>>
constexpr UInt64For<U> widen(U value) {
  if constexpr (kLanesOf<U> == 1) {
    return std::uint64_t{value};
  } else {
    using Result = UInt64For<U>;
    return Result::map(Result{}, [&](detail::Piece64, auto k) {
      return __builtin_convertvector(detail::piece_of<k()>(value), detail::Piece64);
    });
  }
}

/// The low 32 bits of each lane, and the high ones.
template <UInt64Type U>
constexpr UInt<kLanes64Of<U>> low_bits(const U& value) {
  constexpr int kWidth = kLanes64Of<U>;
  if constexpr (kWidth == 1) {
    return static_cast<std::uint32_t>(value);
  } else if constexpr (U::kPieces == 1) {
    return __builtin_convertvector(value.piece[0], UInt<kWidth>);
#if defined(__AVX512F__)
  } else if constexpr (U::kPieces == 2) {
    // The even 32-bit words of the two pieces, in one permutation (vpermt2d). Narrowing each
    // piece and joining the halves would go through memory, where the 64-byte load of two
    // 32-byte stores stalls.
    using Words = std::uint32_t __attribute__((vector_size(64)));
    const auto low = std::bit_cast<Words>(value.piece[0]);
    const auto high = std::bit_cast<Words>(value.piece[1]);
    return __builtin_shufflevector(low, high, 0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28,
                                   30);
#endif
#if defined(__AVX2__) && !defined(__AVX512F__)
  } else if constexpr (U::kPieces == 2 || U::kPieces == 4) {
    // Without AVX-512's narrowing moves GCC takes five shuffles for eight lanes; two do it: the
    // even 32-bit words of two pieces, then their 64-bit pairs in lane order.
    const auto eight = [&](int k) {
      const __m256 words =
          _mm256_shuffle_ps(_mm256_castsi256_ps(__m256i(value.piece[k])),
                            _mm256_castsi256_ps(__m256i(value.piece[k + 1])), 0b10'00'10'00);
      return std::bit_cast<UInt<8>>(
          _mm256_permute4x64_epi64(_mm256_castps_si256(words), 0b11'01'10'00));
    };
    if constexpr (U::kPieces == 2) {
      return eight(0);
    } else {
      const UInt<8> low = eight(0), high = eight(2);
      return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14,
                                     15);
    }
#endif
  } else {
    UInt<kWidth> result{};
    for (int k = 0; k < U::kPieces; ++k) {
      const detail::Piece32 piece = __builtin_convertvector(value.piece[k], detail::Piece32);
      std::memcpy(reinterpret_cast<char*>(&result) + k * int(sizeof piece), &piece, sizeof piece);
    }
    return result;
  }
}
template <UInt64Type U>
constexpr UInt<kLanes64Of<U>> high_bits(const U& value) {
  return low_bits(U(value >> 32));
}

/// `if_true` in the lanes where `mask` is true, `if_false` in the others (width 1: the
/// select(bool, T, T) above).
template <WideNumber M, int W>
requires(kLanesOf<M> == W) inline detail::Lanes64<W> select(M mask,
                                                            const detail::Lanes64<W>& if_true,
                                                            const detail::Lanes64<W>& if_false) {
  return detail::Lanes64<W>::map(if_true, [&](detail::Piece64 t, auto k) {
    const auto wide = std::bit_cast<detail::Piece64>(
        __builtin_convertvector(detail::piece_of<k()>(mask), detail::Piece64Signed));
    return (t & wide) | (if_false.piece[k] & ~wide);
  });
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
