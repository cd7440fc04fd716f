#pragma once
// Where light scatters: the hit a ray found with everything shading needs there, the side of the
// surface the ray arrives on, and the mirror and Snell directions. The materials
// (render/materials/) are built on it.
//
// Everything here is written once over a Float type (math/wide.hpp): float for one path, a
// SIMD vector for a Float's lanes of paths, which the wavefront renderer shades together.
// Sample values are drawn through next_1d(draws, mask) and next_2d(draws, mask): from a
// sampler at width 1, from a block of samplers wider, only for the lanes of the mask.

#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/scene/scene.hpp"
#include "glint/scene/surface_lanes.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A sample value for the lanes of `mask` (the others get unspecified values): `draws` is a
/// Sampler at width 1, or a block of W paths' samplers with next_1d(mask) and next_2d(mask).
template <Sampler S>
float next_1d(S& sampler, bool mask) {
  return mask ? sampler.next_1d() : 0.0f;
}
template <Sampler S>
Vec2 next_2d(S& sampler, bool mask) {
  return mask ? sampler.next_2d() : Vec2(0.0f);
}
template <typename Block, WideNumber M>
auto next_1d(Block& block, M mask) {
  return block.next_1d(mask);
}
template <typename Block, WideNumber M>
auto next_2d(Block& block, M mask) {
  return block.next_2d(mask);
}

namespace detail {

/// The side of a surface a ray arrives on, lane by lane.
template <typename V3>
struct BasicInterface {
  V3 facing_normal;          ///< unit normal on the side the ray came from
  FloatOf<V3> cos_incident;  ///< cosine between the reversed ray and facing_normal, in [0, 1]
  MaskFor<FloatOf<V3>> from_inside;
};
using Interface = BasicInterface<Vec3>;

template <typename V3>
BasicInterface<V3> interface_at(const V3& direction, const V3& outward_normal) {
  const auto cos_out = dot(direction, outward_normal);
  const auto from_inside = cos_out > 0.0f;
  return {select(from_inside, -outward_normal, outward_normal), abs(cos_out), from_inside};
}

template <typename V3>
V3 reflect(const V3& direction, const BasicInterface<V3>& at) {
  return direction + (2.0f * at.cos_incident) * at.facing_normal;
}

/// The refracted direction by Snell's law (eta = incident index / transmitted index) and the
/// lanes of total internal reflection, whose direction is unspecified.
template <typename V3>
struct Refraction {
  V3 direction;
  MaskFor<FloatOf<V3>> total_internal;
};
template <typename V3>
Refraction<V3> refract(const V3& direction, const BasicInterface<V3>& at, FloatOf<V3> eta) {
  using F = FloatOf<V3>;
  const F sin2_transmitted = eta * eta * (1.0f - at.cos_incident * at.cos_incident);
  const F cos_transmitted = sqrt(max(splat<F>(0.0f), 1.0f - sin2_transmitted));
  return {normalize(eta * direction + (eta * at.cos_incident - cos_transmitted) * at.facing_normal),
          sin2_transmitted >= 1.0f};
}

}  // namespace detail

/// The unit outward normal at `point` of a sphere centred at `center`: the hit's, and whatever
/// rebuilds it later from the point (a bounce's MIS weight), in one expression, so that they
/// agree to the bit.
template <typename V3>
V3 outward_normal_at(const V3& point, const V3& center) {
  return normalize(point - center);
}

/// Where a Float's lanes of rays met the scene, with everything shading needs there: the
/// geometry, the spheres' properties and the side each ray came from.
template <typename F>
struct BasicSurfaceInteraction {
  using V3 = Vec3For<F>;
  V3 point;
  V3 outward_normal;  ///< also the direction from the centre, which sphere shading reads
  UIntFor<F> sphere;
  SurfaceLanes<F> surface;
  detail::BasicInterface<V3> at;
  /// The scene the spheres belong to: what shading looks up beyond their properties (textures).
  const Scene* scene = nullptr;

  /// The hits at distances `t` along `rays` of spheres `sphere`, in the lanes of `lanes`.
  static BasicSurfaceInteraction at_hit(const Scene& scene, const V3& origin, const V3& direction,
                                        F t, UIntFor<F> sphere, MaskFor<F> lanes) {
    BasicSurfaceInteraction it;
    it.scene = &scene;
    it.sphere = sphere;
    it.surface = gather_surfaces<F>(scene, sphere, lanes);
    it.point = origin + t * direction;
    it.outward_normal = outward_normal_at(it.point, it.surface.center);
    it.at = detail::interface_at(direction, it.outward_normal);
    return it;
  }
};
using SurfaceInteraction = BasicSurfaceInteraction<float>;

}  // namespace glint::inline GLINT_ISA_NAMESPACE
