#pragma once
// Warps from uniform samples in [0,1)^2 to the distributions the renderer needs. glint owns
// these rather than using <random> distributions, whose output differs between standard
// libraries.

#include <cmath>

#include "glint/math/vector.hpp"

namespace glint {

/// An orthonormal basis around a unit normal (Duff et al. 2017, "Building an Orthonormal
/// Basis, Revisited"): branch-free apart from the sign, no normalisation needed.
struct Frame {
  Vec3 tangent;
  Vec3 bitangent;
  Vec3 normal;

  static Frame around(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x),
            Vec3(b, sign + n.y * n.y * a, -n.y), n};
  }
  Vec3 to_world(const Vec3& local) const {
    return local.x * tangent + local.y * bitangent + local.z * normal;
  }
};

/// Uniform on the hemisphere z >= 0; pdf 1/(2 pi).
inline Vec3 sample_uniform_hemisphere(Vec2 u) {
  const float z = u.x;
  const float r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float kUniformHemispherePdf = 0.5f * kInvPi;

/// Cosine-weighted on the hemisphere z >= 0 (Malley's method); pdf cos(theta)/pi.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::fmax(0.0f, 1.0f - u.x))};
}

/// Two independent standard normal values (Box-Muller). u.x is mapped to (0, 1] so that the
/// logarithm stays finite.
inline Vec2 sample_standard_normal_pair(Vec2 u) {
  const float radius = std::sqrt(-2.0f * std::log(1.0f - u.x));
  const float phi = 2.0f * kPi * u.y;
  return {radius * std::cos(phi), radius * std::sin(phi)};
}

}  // namespace glint
