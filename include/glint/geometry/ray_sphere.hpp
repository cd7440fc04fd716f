#pragma once
// Ray/sphere intersection that stays accurate in single precision for spheres of any size,
// following Haines et al., "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing
// Gems, 2019): the discriminant is r^2 - |f - (f.d)d|^2 (the squared distance from the centre
// to the ray subtracted from r^2), which does not cancel catastrophically the way b^2 - c does
// when the sphere is far away or huge; the roots come from the numerically stable quadratic
// form q = -(b + sign(b) sqrt(disc)), t = {q, c/q}.

#include <cmath>

#include "glint/math/vector.hpp"

namespace glint {

struct SphereRoots {
  float near;
  float far;
};

/// Both ray parameters where the ray meets the sphere of squared radius `radius_squared`,
/// near <= far; false if it misses. `direction` must be unit length.
inline bool intersect_sphere_squared_radius(const Vec3& origin, const Vec3& direction,
                                            const Vec3& center, float radius_squared,
                                            SphereRoots& roots) {
  const Vec3 f = origin - center;
  const float b = glm::dot(f, direction);
  const Vec3 perpendicular = f - b * direction;
  const float discriminant = radius_squared - glm::dot(perpendicular, perpendicular);
  if (!(discriminant >= 0.0f)) return false;
  const float c = glm::dot(f, f) - radius_squared;
  const float q = -(b + std::copysign(std::sqrt(discriminant), b));
  const float t0 = c / q;
  const float t1 = q;
  roots.near = min_of(t0, t1);
  roots.far = max_of(t0, t1);
  return true;
}

/// The same for a sphere given by its radius.
inline bool intersect_sphere(const Vec3& origin, const Vec3& direction, const Vec3& center,
                             float radius, SphereRoots& roots) {
  return intersect_sphere_squared_radius(origin, direction, center, radius * radius, roots);
}

/// Where a ray that starts on the sphere's surface and heads inwards leaves it again. Exact for
/// an origin on the surface, and free of the cancellation that solving the quadratic would have
/// there (one root is zero).
inline float far_side_distance(const Vec3& origin_on_surface, const Vec3& direction,
                               const Vec3& center) {
  return 2.0f * glm::dot(center - origin_on_surface, direction);
}

}  // namespace glint
