#pragma once
// What an acceleration structure over spheres answers, and the one order in which hits
// compete: nearer first, and at exactly equal distance the lower sphere id. The order is total,
// so the answer does not depend on which structure, which traversal order or which SIMD lane
// found a hit, nor on the order in which a caller consults several structures.

#include <concepts>
#include <cstddef>
#include <cstdint>

#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

struct SphereHit {
  float t = kInfinity;
  std::uint32_t sphere = kNoSphere;
};

/// Whether hit `a` wins over hit `b`.
inline bool comes_before(const SphereHit& a, const SphereHit& b) {
  return a.t < b.t || (a.t == b.t && a.sphere < b.sphere);
}

/// The hit a closest-hit query has to beat. A caller's hit competes in hit order; t_max, like
/// a hit that names no sphere, is an open bound: paired with id 0, before which no id comes,
/// it admits no tie.
inline SphereHit hit_to_beat(const Ray& ray, const SphereHit& hit) {
  if (hit.sphere != kNoSphere && hit.t < ray.t_max) return hit;
  return {min_of(ray.t_max, hit.t), 0};
}

/// A structure of spheres queried by rays. Both queries skip the ray's origin sphere (the
/// caller applies the rule of Ray for it) and consider t in (ray.t_min, ray.t_max) only, and
/// t = 0 for a sphere that a ray leaving another one enters at its origin (sphere_kernel.hpp).
///  - closest_hit(ray, hit): the first sphere in hit order that comes before `hit` (see
///    hit_to_beat); if there is one, stores it in `hit` and returns true.
///  - any_hit(ray): whether any sphere is hit at all.
template <class A>
concept SphereAccelerator = requires(const A& a, const Ray& ray, SphereHit& hit) {
  { a.closest_hit(ray, hit) } -> std::same_as<bool>;
  { a.any_hit(ray) } -> std::same_as<bool>;
  { a.empty() } -> std::same_as<bool>;
  { a.size() } -> std::same_as<std::size_t>;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
