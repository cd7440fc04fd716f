#pragma once
// sin, cos, atan2, log and exp of glint's own, one polynomial for every width: the C library's
// functions differ between libraries, versions and machines, and a vectorised library's between its
// scalar and vector forms, so a pixel that depended on them would depend on more than the scene,
// the settings and the seed. Accurate to about an ulp over the arguments the warps use.

#include <bit>
#include <cmath>
#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// sin(x) and cos(x) for 0 <= x <= 2^16 (the warps' angles are in [0, 2 pi)): the argument is
/// reduced to [-pi/4, pi/4] around a multiple of pi/2 in three parts (Cody and Waite), then
/// minimax polynomials of degree 7 and 8 (those of Cephes' sinf and cosf).
template <FloatType F>
inline void sincos(F x, F& sine, F& cosine) {
  using I = IntFor<F>;
  const I octant = truncate_to_int(x * 1.27323954473516f);
  const I even = (octant + 1) & ~1;  // the nearest multiple of pi/2, in units of pi/4
  const F k = to_float(even);
  const F r = ((x - k * 0.78515625f) - k * 2.4187564849853515625e-4f) - k * 3.77489497744594108e-8f;
  const F r2 = r * r;
  const F sin_r =
      ((-1.9515295891e-4f * r2 + 8.3321608736e-3f) * r2 - 1.6666654611e-1f) * r2 * r + r;
  const F cos_r =
      ((2.443315711809948e-5f * r2 - 1.388731625493765e-3f) * r2 + 4.166664568298827e-2f) * r2 *
          r2 -
      0.5f * r2 + 1.0f;
  const I quadrant = even >> 1;
  const MaskFor<F> swap = (quadrant & 1) != 0;
  const F s = select(swap, cos_r, sin_r);
  const F c = select(swap, sin_r, cos_r);
  // sin is negative in quadrants 2 and 3, cos in 1 and 2.
  const I sin_sign = (quadrant & 2) << 30;
  const I cos_sign = ((quadrant + 1) & 2) << 30;
  sine = float_of_bits(bits_of(s) ^ sin_sign);
  cosine = float_of_bits(bits_of(c) ^ cos_sign);
}

/// atan2(y, x) in [-pi, pi] for finite y and x (0 where both are zero): the smaller magnitude
/// over the larger gives an angle in [0, pi/4], reduced to [-pi/8, pi/8] by the addition formula
/// around pi/4, then Cephes atanf's odd polynomial; the octant is restored by reflections, which
/// are exact. The mapping of directions to a texture's coordinates reads it.
template <FloatType F>
inline F atan2(F y, F x) {
  const F ax = abs(x), ay = abs(y);
  const F larger = max(ax, ay);
  const MaskFor<F> origin = larger == 0.0f;
  const F a = select(origin, splat<F>(0.0f), min(ax, ay) / select(origin, splat<F>(1.0f), larger));
  const MaskFor<F> upper = a > 0.414213562373095f;  // tan(pi/8)
  const F t = select(upper, (a - 1.0f) / (a + 1.0f), a);
  const F z = t * t;
  const F p =
      ((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f;
  F angle = p * z * t + t;
  angle = select(upper, angle + 0.785398163397448f, angle);
  angle = select(ay > ax, 1.57079632679490f - angle, angle);
  angle = select(x < 0.0f, 3.14159265358979f - angle, angle);
  return copysign(angle, y);
}

/// The natural logarithm of x for positive normal x: x = m 2^e with m in [sqrt(1/2), sqrt(2)),
/// then Cephes logf's polynomial for log(m) and log(2) in two parts.
template <FloatType F>
inline F log(F x) {
  using I = IntFor<F>;
  const I bits = bits_of(x);
  I exponent = ((bits >> 23) & 0xff) - 126;
  F m = float_of_bits((bits & 0x007fffff) | 0x3f000000);  // [0.5, 1)
  const MaskFor<F> small = m < 0.707106781186547524f;
  exponent = select(small, exponent - 1, exponent);
  m = select(small, m + m, m) - 1.0f;
  const F e = to_float(exponent);
  const F z = m * m;
  F y = 7.0376836292e-2f * m - 1.1514610310e-1f;
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

/// e^x for one float, x <= 88: x = k ln 2 + r with |r| <= ln 2 / 2 (ln 2 in two parts), Cephes
/// expf's polynomial for e^r, then the exact scaling by 2^k. Below about -103 the result is 0.
inline float exponential(float x) {
  if (x < -103.0f) return 0.0f;
  const float k = std::nearbyint(x * 1.44269504088896341f);
  const float r = (x - k * 0.693359375f) + k * 2.12194440e-4f;
  const float r2 = r * r;
  float p = 1.9875691500e-4f * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  const float e_r = p * r2 + r + 1.0f;
  // 2^k is a float for every k here (-149 to 127: subnormal below -126), and one correctly
  // rounded product by it is what std::ldexp gives, without its call.
  const int power = int(k);
  const std::uint32_t bits =
      power >= -126 ? std::uint32_t(power + 127) << 23 : std::uint32_t(1) << (power + 149);
  return e_r * std::bit_cast<float>(bits);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
