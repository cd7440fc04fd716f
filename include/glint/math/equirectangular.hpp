#pragma once
// The equirectangular (latitude-longitude) map between unit directions and the unit square, as
// an image texture on a sphere reads it. The directions are given in a frame whose +y is the
// north pole and whose +z meets the middle of the image; u grows eastward, towards +x, so that
// the image seen from outside along -z is not mirrored. Computed with glint's own inverse
// trigonometry (math/elementary_functions.hpp): a texel lookup is the same on every machine.

#include "glint/instruction_set.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// (u, v) of unit direction `d`: u = 1/2 + longitude / (2 pi), the longitude atan2(x, z) in
/// [-pi, pi]; v = polar angle / pi, 0 at the north pole (+y, the image's top row) and 1 at the
/// south pole.
inline Vec2 equirectangular_uv(const Vec3& d) {
  constexpr float kInvTwoPi = 0.5f * kInvPi;
  const float longitude = atan2(d.x, d.z);
  const float polar = atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y);
  return {0.5f + longitude * kInvTwoPi, polar * kInvPi};
}

/// The unit direction at (u, v) in [0, 1]^2: the inverse of equirectangular_uv.
inline Vec3 equirectangular_direction(const Vec2& uv) {
  constexpr float kTwoPi = 2.0f * kPi;
  // sincos takes non-negative angles: the longitude's is offset by pi and the sign turned back.
  float sin_longitude = 0.0f, cos_longitude = 0.0f, sin_polar = 0.0f, cos_polar = 0.0f;
  sincos(uv.x * kTwoPi, sin_longitude, cos_longitude);
  sincos(uv.y * kPi, sin_polar, cos_polar);
  return {-sin_longitude * sin_polar, cos_polar, -cos_longitude * sin_polar};
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
