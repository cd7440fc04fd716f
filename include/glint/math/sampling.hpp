#pragma once
// Warps from uniform samples in [0,1)^2 to the distributions the renderer needs. glint owns
// these rather than using <random> distributions, whose output differs between standard
// libraries. Clamps use std::max, not std::fmax: the same value for every input here (NaN
// gives 0 either way), but fmax is a library call unless the compiler may ignore NaNs.

#include <algorithm>
#include <cmath>

#include "glint/math/lanes.hpp"
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

#if defined(GLINT_AVX2)
/// Frame for eight normals at once.
struct FrameLanes {
  Vec3Lanes tangent;
  Vec3Lanes bitangent;
  Vec3Lanes normal;

  static FrameLanes around(const Vec3Lanes& n) {
    const FloatLanes sign = copysign_lanes(broadcast(1.0f), n.z);
    const FloatLanes a = -1.0f / (sign + n.z);
    const FloatLanes b = n.x * n.y * a;
    return {
        {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  Vec3Lanes to_world(const Vec3Lanes& local) const {
    return local.x * tangent + local.y * bitangent + local.z * normal;
  }
};
#endif

#if defined(GLINT_AVX2)
/// The unit vector at angle 2 pi u from the x axis in the xy plane, scaled by `radius`, with
/// `z`: the last step of every warp below.
inline Vec3Lanes around_z(FloatLanes u, FloatLanes radius, FloatLanes z) {
  FloatLanes sine, cosine;
  sincos_lanes((2.0f * kPi) * u, sine, cosine);
  return {radius * cosine, radius * sine, z};
}
#endif

/// Uniform on the hemisphere z >= 0; pdf 1/(2 pi).
inline Vec3 sample_uniform_hemisphere(Vec2 u) {
  const float z = u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
#if defined(GLINT_AVX2)
inline Vec3Lanes sample_uniform_hemisphere_lanes(Vec2Lanes u) {
  const FloatLanes z = u.x;
  return around_z(u.y, sqrt_lanes(max_lanes(broadcast(0.0f), 1.0f - z * z)), z);
}
#endif
inline constexpr float kUniformHemispherePdf = 0.5f * kInvPi;

/// Cosine-weighted on the hemisphere z >= 0 (Malley's method); pdf cos(theta)/pi.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}
#if defined(GLINT_AVX2)
inline Vec3Lanes sample_cosine_hemisphere_lanes(Vec2Lanes u) {
  return around_z(u.y, sqrt_lanes(u.x), sqrt_lanes(max_lanes(broadcast(0.0f), 1.0f - u.x)));
}
#endif

/// Uniform on the unit sphere; pdf 1/(4 pi).
inline Vec3 sample_uniform_sphere(Vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
#if defined(GLINT_AVX2)
inline Vec3Lanes sample_uniform_sphere_lanes(Vec2Lanes u) {
  const FloatLanes z = 1.0f - 2.0f * u.x;
  return around_z(u.y, sqrt_lanes(max_lanes(broadcast(0.0f), 1.0f - z * z)), z);
}
#endif

/// Uniform over the directions within angle theta_max of +z, the cone being given by
/// 1 - cos(theta_max) (in (0, 2]) rather than by the cosine, which rounds to 1 for the small
/// cones that distant lamps subtend. Its pdf is uniform_cone_pdf(one_minus_cos_max).
inline Vec3 sample_uniform_cone(Vec2 u, float one_minus_cos_max) {
  const float one_minus_cos = u.x * one_minus_cos_max;
  const float z = 1.0f - one_minus_cos;
  const float r = std::sqrt(std::max(0.0f, one_minus_cos * (2.0f - one_minus_cos)));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
#if defined(GLINT_AVX2)
inline Vec3Lanes sample_uniform_cone_lanes(Vec2Lanes u, FloatLanes one_minus_cos_max) {
  const FloatLanes one_minus_cos = u.x * one_minus_cos_max;
  return around_z(u.y,
                  sqrt_lanes(max_lanes(broadcast(0.0f), one_minus_cos * (2.0f - one_minus_cos))),
                  1.0f - one_minus_cos);
}
#endif

/// 1 / solid angle of the cone: 1 / (2 pi (1 - cos theta_max)).
inline float uniform_cone_pdf(float one_minus_cos_max) {
  return 1.0f / (2.0f * kPi * one_minus_cos_max);
}
#if defined(GLINT_AVX2)
inline FloatLanes uniform_cone_pdf_lanes(FloatLanes one_minus_cos_max) {
  return 1.0f / (2.0f * kPi * one_minus_cos_max);
}
#endif

/// Two independent standard normal values (Box-Muller). u.x is mapped to (0, 1] so that the
/// logarithm stays finite.
inline Vec2 sample_standard_normal_pair(Vec2 u) {
  const float radius = std::sqrt(-2.0f * std::log(1.0f - u.x));
  const float phi = 2.0f * kPi * u.y;
  return {radius * std::cos(phi), radius * std::sin(phi)};
}
#if defined(GLINT_AVX2)
inline Vec2Lanes sample_standard_normal_pair_lanes(Vec2Lanes u) {
  const FloatLanes radius = sqrt_lanes(-2.0f * log_lanes(1.0f - u.x));
  FloatLanes sine, cosine;
  sincos_lanes((2.0f * kPi) * u.y, sine, cosine);
  return {radius * cosine, radius * sine};
}
#endif

}  // namespace glint
