#pragma once
// Ray/sphere intersection that stays accurate in single precision for spheres of any size,
// following Haines et al., "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing
// Gems, 2019): the discriminant is r^2 - |f - (f.d)d|^2 (the squared distance from the centre
// to the ray subtracted from r^2), which does not cancel catastrophically the way b^2 - c does
// when the sphere is far away or huge; the roots come from the numerically stable quadratic
// form q = -(b + sign(b) sqrt(disc)), t = {q, c/q}.
//
// That still leaves c = |f|^2 - r^2, which cancels for an origin near the surface of a huge
// sphere: its error, about u r^2 (u = 2^-24), moves the near root by u r / 2 whatever the ray,
// so a camera 0.001 above a floor of radius 1e5 sees through it. An AnchoredSphere removes the
// cancellation by measuring from a point of the surface instead of from the centre (see there).

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "glint/geometry/simd.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

// The formulas are written once over a register type L (simd.hpp): for one ray and one sphere
// at Lanes1, and lane by lane in the SIMD kernels (sphere_kernel.hpp), which so give each ray
// the bits that the scalar form gives it.

/// A ray's origin and unit direction in each lane of L's registers.
template <class L>
struct LineLanes {
  typename L::F ox, oy, oz, dx, dy, dz;
};

/// A sphere given by its centre and squared radius in each lane.
template <class L>
struct BasicSphereLanes {
  typename L::F cx, cy, cz, r2;
};

/// The quadratic in t of a ray (unit direction) and a sphere, t^2 + 2 b t + c = 0: b = f.d and
/// c = |f|^2 - r^2 for the offset f of the ray's origin from the centre, and its discriminant
/// b^2 - c in the form accurate for the kind of sphere. c is the origin's signed distance from
/// the surface times |f| + r, and b the cosine of the direction with the outward normal there
/// times |f|: what decides a root at the origin itself (see sphere_kernel.hpp).
template <class L>
struct QuadraticLanes {
  typename L::F b, c, discriminant;
};

/// The quadratic of a sphere given by its centre, with Haines's discriminant
/// r^2 - |f - (f.d)d|^2, lane by lane.
template <class L>
inline QuadraticLanes<L> quadratic(const LineLanes<L>& ray, const BasicSphereLanes<L>& sphere) {
  using F = typename L::F;
  const F fx = L::sub(ray.ox, sphere.cx);
  const F fy = L::sub(ray.oy, sphere.cy);
  const F fz = L::sub(ray.oz, sphere.cz);
  const F b = L::fmadd(fx, ray.dx, L::fmadd(fy, ray.dy, L::mul(fz, ray.dz)));
  const F px = L::fnmadd(b, ray.dx, fx);
  const F py = L::fnmadd(b, ray.dy, fy);
  const F pz = L::fnmadd(b, ray.dz, fz);
  const F perp2 = L::fmadd(px, px, L::fmadd(py, py, L::mul(pz, pz)));
  const F c = L::sub(L::fmadd(fx, fx, L::fmadd(fy, fy, L::mul(fz, fz))), sphere.r2);
  return {b, c, L::sub(sphere.r2, perp2)};
}

/// Both roots of each lane's quadratic, near <= far.
template <class L>
struct RootLanes {
  typename L::F near, far;
};

/// The roots of each lane's quadratic from a discriminant >= 0 however it was computed:
/// q = -(b + sign(b) sqrt(discriminant)) and c / q, the stable pair. (A negative discriminant
/// counts as 0.)
template <class L>
inline RootLanes<L> roots_of(const QuadraticLanes<L>& quadratic) {
  using F = typename L::F;
  const F root = L::sqrt(L::max(quadratic.discriminant, L::zero()));
  const F q = L::negate(L::add(quadratic.b, L::with_sign_of(root, quadratic.b)));
  const F t0 = L::div(quadratic.c, q);
  return {L::min(t0, q), L::max(t0, q)};
}

/// Where a ray meets a sphere, near <= far.
using SphereRoots = RootLanes<Lanes1>;

/// The quadratic of one ray and one sphere.
using SphereQuadratic = QuadraticLanes<Lanes1>;

/// A ray's line as the formulas read it at width 1.
inline LineLanes<Lanes1> line_lane(const Vec3& origin, const Vec3& direction) {
  return {origin.x, origin.y, origin.z, direction.x, direction.y, direction.z};
}

/// Both ray parameters where the ray meets the sphere of squared radius `radius_squared`,
/// near <= far; false if it misses. `direction` must be unit length.
inline bool intersect_sphere_squared_radius(const Vec3& origin, const Vec3& direction,
                                            const Vec3& center, float radius_squared,
                                            SphereRoots& roots) {
  const SphereQuadratic q =
      quadratic(line_lane(origin, direction),
                BasicSphereLanes<Lanes1>{center.x, center.y, center.z, radius_squared});
  if (!(q.discriminant >= 0.0f)) return false;
  roots = roots_of(q);
  return true;
}

/// The same for a sphere given by its radius.
inline bool intersect_sphere(const Vec3& origin, const Vec3& direction, const Vec3& center,
                             float radius, SphereRoots& roots) {
  return intersect_sphere_squared_radius(origin, direction, center, radius * radius, roots);
}

/// A sphere given by the point of its surface nearest a reference point (the anchor) and the
/// offset of the anchor from the centre, m = r n (n the outward unit normal there). With g the
/// offset of a ray's origin from the anchor and f = g + m its offset from the centre,
///   c = |f|^2 - r^2 = g.(g + 2m) = g.(f + m)   and   b = f.d,
/// and c no longer cancels: its error scales with u r |g| instead of u r^2 (u = 2^-24), which
/// moves the near root by about u |g| instead of u r. That is exact enough for a camera a
/// millimetre above a planet-sized floor, as long as the rays start near the anchor (which is
/// why it is the surface point nearest the camera), and never worse than the centre's form.
/// The offset is rounded to float; the sphere is the one of radius |m| through the anchor,
/// which differs from the described sphere by about the rounding of its centre.
struct AnchoredSphere {
  Vec3 anchor;
  Vec3 offset;           ///< anchor - centre
  float radius_squared;  ///< |offset|^2
};

/// The sphere (center, radius) anchored at its surface point nearest `reference`. Computed in
/// double, then rounded, so that the anchor and the offset are as exact as float allows.
inline AnchoredSphere anchor_sphere(const Vec3& center, float radius, const Vec3& reference) {
  const glm::dvec3 to_reference = glm::dvec3(reference) - glm::dvec3(center);
  const double distance = glm::length(to_reference);
  // From the centre itself every surface point is nearest: any will do.
  const glm::dvec3 normal = distance > 0.0 ? to_reference / distance : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 offset = double(radius) * normal;
  AnchoredSphere sphere;
  sphere.anchor = Vec3(glm::dvec3(center) + offset);
  sphere.offset = Vec3(offset);
  const glm::dvec3 rounded_offset(sphere.offset);
  sphere.radius_squared = static_cast<float>(glm::dot(rounded_offset, rounded_offset));
  return sphere;
}

/// An anchored sphere in each lane.
template <class L>
struct BasicAnchoredLanes {
  typename L::F ax, ay, az, mx, my, mz, r2;
};

inline BasicAnchoredLanes<Lanes1> anchored_lane(const AnchoredSphere& sphere) {
  return {sphere.anchor.x, sphere.anchor.y, sphere.anchor.z,      sphere.offset.x,
          sphere.offset.y, sphere.offset.z, sphere.radius_squared};
}

/// The quadratic of an anchored sphere, lane by lane: b = f.d and c = g.(f + m) (see
/// AnchoredSphere), and the discriminant b^2 - c in whichever of two forms is accurate for the
/// lane's origin. Near the sphere (|c| <= r^2, i.e. |f| <= sqrt(2) r) b^2 - c itself: both
/// terms are accurate, its error is about u (b^2 + |c|) <= 3 u r^2, and far smaller for the
/// grazing rays (b and c small) whose discriminant is small; Haines's r^2 - |f - b d|^2 carries
/// an error of u r^2 whatever the ray. Farther away Haines's form, for the reason it exists (a
/// sphere small next to its distance). Rays from inside a room are near all of its walls: when
/// every lane is near, Haines's form is not computed. NaN anchors (padding lanes) count as near
/// (an unordered comparison) and give a NaN discriminant.
template <class L>
struct AnchoredQuadraticLanes : QuadraticLanes<L> {
  typename L::F gx, gy, gz;  ///< g, the offset of the origin from the anchor

  /// |g|^2, the squared distance of the origin from the anchor.
  typename L::F from_anchor_squared() const {
    return L::fmadd(gx, gx, L::fmadd(gy, gy, L::mul(gz, gz)));
  }
};

template <class L>
inline AnchoredQuadraticLanes<L> quadratic(const LineLanes<L>& ray,
                                           const BasicAnchoredLanes<L>& sphere) {
  using F = typename L::F;
  using M = typename L::M;
  const F gx = L::sub(ray.ox, sphere.ax);
  const F gy = L::sub(ray.oy, sphere.ay);
  const F gz = L::sub(ray.oz, sphere.az);
  const F fx = L::add(gx, sphere.mx);
  const F fy = L::add(gy, sphere.my);
  const F fz = L::add(gz, sphere.mz);
  const F c = L::fmadd(gx, L::add(fx, sphere.mx),
                       L::fmadd(gy, L::add(fy, sphere.my), L::mul(gz, L::add(fz, sphere.mz))));
  const F b = L::fmadd(fx, ray.dx, L::fmadd(fy, ray.dy, L::mul(fz, ray.dz)));
  const F near_form = L::fmsub(b, b, c);
  const M near = L::not_greater(L::abs(c), sphere.r2);
  F discriminant = near_form;
  if (L::bits(near) != L::kAllLanes) {
    const F px = L::fnmadd(b, ray.dx, fx);
    const F py = L::fnmadd(b, ray.dy, fy);
    const F pz = L::fnmadd(b, ray.dz, fz);
    const F perp2 = L::fmadd(px, px, L::fmadd(py, py, L::mul(pz, pz)));
    discriminant = L::select(near, near_form, L::sub(sphere.r2, perp2));
  }
  return {{b, c, discriminant}, gx, gy, gz};
}

/// intersect_sphere for an anchored sphere. `direction` must be unit length.
inline bool intersect_anchored_sphere(const Vec3& origin, const Vec3& direction,
                                      const AnchoredSphere& sphere, SphereRoots& roots) {
  const SphereQuadratic q = quadratic(line_lane(origin, direction), anchored_lane(sphere));
  if (!(q.discriminant >= 0.0f)) return false;
  roots = roots_of(q);
  return true;
}

/// Where a ray that starts on the sphere's surface and heads inwards leaves it again. Exact for
/// an origin on the surface, and free of the cancellation that solving the quadratic would have
/// there (one root is zero).
inline float far_side_distance(const Vec3& origin_on_surface, const Vec3& direction,
                               const Vec3& center) {
  return 2.0f * glm::dot(center - origin_on_surface, direction);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
