#pragma once
// Warps from uniform samples in [0,1)^2 to the distributions the renderer needs, each written
// once for every width (math/wide.hpp): a warp called with a Vec2 is scalar code, with a
// Vector2 of Float<8> or Float<16> it warps that many samples at once, to the same bits lane
// by lane. glint owns these rather than using <random> distributions, whose output differs
// between standard libraries, and their sin, cos and log are glint's own for the same reason.

#include "glint/instruction_set.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// An orthonormal basis around a unit normal (Duff et al. 2017, "Building an Orthonormal
/// Basis, Revisited"): branch-free apart from the sign, no normalisation needed. V is Vec3 or
/// a Vector3 of lanes.
template <typename V>
struct BasicFrame {
  V tangent;
  V bitangent;
  V normal;

  static BasicFrame around(const V& n) {
    using F = FloatOf<V>;
    const F sign = copysign(splat<F>(1.0f), n.z);
    const F a = -1.0f / (sign + n.z);
    const F b = n.x * n.y * a;
    return {V{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, V{b, sign + n.y * n.y * a, -n.y},
            n};
  }
  V to_world(const V& local) const {
    return local.x * tangent + local.y * bitangent + local.z * normal;
  }
};
using Frame = BasicFrame<Vec3>;

namespace detail {
/// The unit vector at angle 2 pi u from the x axis in the xy plane, scaled by `radius`, with
/// `z`: the last step of every direction warp below.
template <FloatType F>
inline Vec3For<F> around_z(F u, F radius, F z) {
  F sine, cosine;
  sincos((2.0f * kPi) * u, sine, cosine);
  return Vec3For<F>{radius * cosine, radius * sine, z};
}
}  // namespace detail

/// Uniform on the hemisphere z >= 0; pdf 1/(2 pi).
template <typename V2>
inline Vec3For<FloatOf<V2>> sample_uniform_hemisphere(const V2& u) {
  using F = FloatOf<V2>;
  const F z = u.x;
  return detail::around_z(u.y, sqrt(max(splat<F>(0.0f), 1.0f - z * z)), z);
}
inline constexpr float kUniformHemispherePdf = 0.5f * kInvPi;

/// Cosine-weighted on the hemisphere z >= 0 (Malley's method); pdf cos(theta)/pi.
template <typename V2>
inline Vec3For<FloatOf<V2>> sample_cosine_hemisphere(const V2& u) {
  using F = FloatOf<V2>;
  return detail::around_z(u.y, sqrt(u.x), sqrt(max(splat<F>(0.0f), 1.0f - u.x)));
}

/// Uniform on the unit sphere; pdf 1/(4 pi).
template <typename V2>
inline Vec3For<FloatOf<V2>> sample_uniform_sphere(const V2& u) {
  using F = FloatOf<V2>;
  const F z = 1.0f - 2.0f * u.x;
  return detail::around_z(u.y, sqrt(max(splat<F>(0.0f), 1.0f - z * z)), z);
}

/// Uniform over the directions within angle theta_max of +z, the cone being given by
/// 1 - cos(theta_max) (in (0, 2]) rather than by the cosine, which rounds to 1 for the small
/// cones that distant lamps subtend. Its pdf is uniform_cone_pdf(one_minus_cos_max).
template <typename V2>
inline Vec3For<FloatOf<V2>> sample_uniform_cone(const V2& u, FloatOf<V2> one_minus_cos_max) {
  using F = FloatOf<V2>;
  const F one_minus_cos = u.x * one_minus_cos_max;
  return detail::around_z(u.y, sqrt(max(splat<F>(0.0f), one_minus_cos * (2.0f - one_minus_cos))),
                          1.0f - one_minus_cos);
}

/// 1 / solid angle of the cone: 1 / (2 pi (1 - cos theta_max)).
template <FloatType F>
inline F uniform_cone_pdf(F one_minus_cos_max) {
  return 1.0f / (2.0f * kPi * one_minus_cos_max);
}

/// Uniform on the unit disc (polar: radius sqrt(u.x), angle 2 pi u.y); pdf 1/pi.
template <typename V2>
inline V2 sample_uniform_disc(const V2& u) {
  const Vec3For<FloatOf<V2>> point = detail::around_z(u.y, sqrt(u.x), splat<FloatOf<V2>>(0.0f));
  return V2{point.x, point.y};
}

/// Two independent standard normal values (Box-Muller). u.x is mapped to (0, 1] so that the
/// logarithm stays finite.
template <typename V2>
inline V2 sample_standard_normal_pair(const V2& u) {
  using F = FloatOf<V2>;
  const F radius = sqrt(-2.0f * log(1.0f - u.x));
  F sine, cosine;
  sincos((2.0f * kPi) * u.y, sine, cosine);
  return V2{radius * cosine, radius * sine};
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
