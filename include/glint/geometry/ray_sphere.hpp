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

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

struct SphereRoots {
  float near;
  float far;
};

/// The roots of t^2 + 2 b t + c = 0 from a non-negative discriminant b^2 - c, however it was
/// computed: q = -(b + sign(b) sqrt(discriminant)) and c / q, the stable pair.
inline SphereRoots roots_from(float b, float c, float discriminant) {
  const float q = -(b + std::copysign(std::sqrt(discriminant), b));
  const float t0 = c / q;
  return {min_of(t0, q), max_of(t0, q)};
}

/// The quadratic in t of a ray (unit direction) and a sphere, t^2 + 2 b t + c = 0: b = f.d and
/// c = |f|^2 - r^2 for the offset f of the ray's origin from the centre, and its discriminant
/// b^2 - c in the form accurate for the kind of sphere. c is the origin's signed distance from
/// the surface times |f| + r, and b the cosine of the direction with the outward normal there
/// times |f|: what decides a root at the origin itself (see sphere_kernel.hpp).
struct SphereQuadratic {
  float b;
  float c;
  float discriminant;
};

/// The quadratic of a sphere given by its centre and squared radius, with Haines's
/// discriminant r^2 - |f - (f.d)d|^2; false, leaving `q` unset, if the ray's line misses it.
inline bool sphere_quadratic(const Vec3& origin, const Vec3& direction, const Vec3& center,
                             float radius_squared, SphereQuadratic& q) {
  const Vec3 f = origin - center;
  const float b = fused_dot(f, direction);
  const Vec3 perpendicular = fused_minus_scaled(f, b, direction);
  const float discriminant = radius_squared - fused_dot(perpendicular, perpendicular);
  if (!(discriminant >= 0.0f)) return false;
  q = {b, fused_dot(f, f) - radius_squared, discriminant};
  return true;
}

/// Both ray parameters where the ray meets the sphere of squared radius `radius_squared`,
/// near <= far; false if it misses. `direction` must be unit length.
inline bool intersect_sphere_squared_radius(const Vec3& origin, const Vec3& direction,
                                            const Vec3& center, float radius_squared,
                                            SphereRoots& roots) {
  SphereQuadratic q;
  if (!sphere_quadratic(origin, direction, center, radius_squared, q)) return false;
  roots = roots_from(q.b, q.c, q.discriminant);
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

/// The discriminant b^2 - c for an anchored sphere, in whichever of two forms is accurate for
/// this origin. Near the sphere (|c| <= r^2, i.e. |f| <= sqrt(2) r) b^2 - c itself: both terms
/// are accurate, its error is about u (b^2 + |c|) <= 3 u r^2, and far smaller for the grazing
/// rays (b and c small) whose discriminant is small; Haines's r^2 - |f - b d|^2 carries an
/// error of u r^2 whatever the ray. Farther away Haines's form, for the reason it exists (a
/// sphere small next to its distance).
inline float anchored_discriminant(const Vec3& f, const Vec3& direction,
                                   const AnchoredSphere& sphere, float b, float c) {
  if (std::abs(c) <= sphere.radius_squared) return std::fma(b, b, -c);
  const Vec3 perpendicular = fused_minus_scaled(f, b, direction);
  return sphere.radius_squared - fused_dot(perpendicular, perpendicular);
}

/// The quadratic of an anchored sphere (see SphereQuadratic); false, leaving `q` unset, if the
/// ray's line misses it.
inline bool anchored_quadratic(const Vec3& origin, const Vec3& direction,
                               const AnchoredSphere& sphere, SphereQuadratic& q) {
  const Vec3 g = origin - sphere.anchor;
  const Vec3 f = g + sphere.offset;
  const float c = fused_dot(g, f + sphere.offset);
  const float b = fused_dot(f, direction);
  const float discriminant = anchored_discriminant(f, direction, sphere, b, c);
  if (!(discriminant >= 0.0f)) return false;
  q = {b, c, discriminant};
  return true;
}

/// intersect_sphere for an anchored sphere. `direction` must be unit length.
inline bool intersect_anchored_sphere(const Vec3& origin, const Vec3& direction,
                                      const AnchoredSphere& sphere, SphereRoots& roots) {
  SphereQuadratic q;
  if (!anchored_quadratic(origin, direction, sphere, q)) return false;
  roots = roots_from(q.b, q.c, q.discriminant);
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
