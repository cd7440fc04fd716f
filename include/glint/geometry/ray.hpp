#pragma once

#include <cstdint>
#include <limits>
#include <type_traits>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

inline constexpr std::uint32_t kNoSphere = std::numeric_limits<std::uint32_t>::max();
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// A ray with a unit direction. A ray that starts on a sphere's surface remembers that sphere
/// and whether it heads into it: leaving outwards it cannot meet that (convex) sphere again,
/// heading inwards it meets only the far side. This replaces the usual self-intersection
/// epsilon with an exact rule (see Scene::closest_hit). Another sphere that passes through its
/// origin to within the rounding of a hit point (where spheres cross) is decided the same way,
/// by the direction: met at t = 0 if the ray heads into it, else not at all (sphere_kernel.hpp).
struct Ray {
  Vec3 origin{0.0f};
  Vec3 direction{0.0f, 0.0f, 1.0f};
  float t_min = 0.0f;
  float t_max = kInfinity;
  std::uint32_t origin_sphere = kNoSphere;
  bool heads_into_origin_sphere = false;

  Vec3 at(float t) const { return origin + t * direction; }
};

/// A ray leaving sphere `sphere` at `point`, into the sphere if `heads_into_sphere`.
inline Ray ray_leaving_sphere(const Vec3& point, const Vec3& direction, std::uint32_t sphere,
                              bool heads_into_sphere, float t_max = kInfinity) {
  Ray ray;
  ray.origin = point;
  ray.direction = direction;
  ray.t_max = t_max;
  ray.origin_sphere = sphere;
  ray.heads_into_origin_sphere = heads_into_sphere;
  return ray;
}

/// A ray leaving sphere `sphere` at `point`, whose outward normal there is `outward_normal`.
inline Ray ray_leaving_sphere(const Vec3& point, const Vec3& direction, std::uint32_t sphere,
                              const Vec3& outward_normal, float t_max = kInfinity) {
  return ray_leaving_sphere(point, direction, sphere, glm::dot(direction, outward_normal) < 0.0f,
                            t_max);
}

/// Ray's fields for a Float's lanes of rays (lane i: ray i).
template <typename F>
struct RayLanes {
  Vec3For<F> origin;
  Vec3For<F> direction;
  F t_min;
  F t_max;
  UIntFor<F> origin_sphere;
  MaskFor<F> heads_into_origin_sphere;
};

/// The rays of a Float's lanes: a Ray at width 1.
template <typename F>
using RayFor = std::conditional_t<kLanesOf<F> == 1, Ray, RayLanes<F>>;

template <typename M, typename F>
RayLanes<F> select(M mask, const RayLanes<F>& if_true, const RayLanes<F>& if_false) {
  return {select(mask, if_true.origin, if_false.origin),
          select(mask, if_true.direction, if_false.direction),
          select(mask, if_true.t_min, if_false.t_min),
          select(mask, if_true.t_max, if_false.t_max),
          select(mask, if_true.origin_sphere, if_false.origin_sphere),
          select(mask, if_true.heads_into_origin_sphere, if_false.heads_into_origin_sphere)};
}
inline Ray select(bool mask, const Ray& if_true, const Ray& if_false) {
  return mask ? if_true : if_false;
}

/// The rays leaving spheres `sphere` at `point` in `direction`, whose outward normals there
/// are `outward_normal`, up to `t_max` (a Ray at width 1: ray_leaving_sphere).
template <typename V3>
RayFor<FloatOf<V3>> rays_leaving_spheres(const V3& point, const V3& direction,
                                         UIntFor<FloatOf<V3>> sphere, const V3& outward_normal,
                                         FloatOf<V3> t_max) {
  using F = FloatOf<V3>;
  return {point, direction, splat<F>(0.0f), t_max, sphere, dot(direction, outward_normal) < 0.0f};
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
