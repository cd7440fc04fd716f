#pragma once
// The interface every light of a scene offers its estimators, in the manner of pbrt-v4's Light:
// light arriving at a point (sample_li, pdf_li), light leaving the light (sample_le, pdf_le),
// and its power, by which a light selection weighs it. An estimator that asks only this of a
// light renders every kind of light; render/scene_lights.hpp holds a scene's lights, one list per
// kind, and visits the one a selection chooses.
//
// Units: radiance for a light with a surface (W / (m^2 sr)), radiant intensity for a light at a
// point (W / sr). A density is per unit solid angle for a direction and per unit area for a
// point on a surface; a light at a point (kDeltaPosition) has no density to compare, and its
// position "density" is one.
//
// The kinds and their order are one fact, written in render/scene_lights.hpp (SceneLightKinds).

#include <concepts>
#include <cstdint>

#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Where a light is seen from, for a Float's lanes of points (F = float: one point): a point on
/// sphere `sphere` (kNoSphere: on none), on the side `from_inside` says. A light that is a
/// sphere sees a point on its own surface only from inside.
template <typename F>
struct BasicLightPoint {
  Vec3For<F> point;
  UIntFor<F> sphere;
  MaskFor<F> from_inside;
};
using LightPoint = BasicLightPoint<float>;

/// Light arriving at a point from a light, lane by lane: from unit `direction`, with radiance
/// `radiance` (for a light at a point: its intensity over the squared distance), drawn with
/// density `pdf` per unit solid angle (one for a light at a point, which only sampling finds).
/// The light arrives unless something blocks it: where `sphere` is kNoSphere, anything closer
/// than `distance` (the light is at `point`); else the light is that sphere's surface and the
/// first sphere the ray meets must be it (a shadow ray ending at the light would have to beat
/// the rounding of its distance).
template <typename F>
struct BasicLightSample {
  Vec3For<F> direction;
  Vec3For<F> radiance;
  F pdf;
  F distance;
  Vec3For<F> point;  ///< where `sphere` is kNoSphere
  UIntFor<F> sphere;
  MaskFor<F> valid;  ///< false where nothing can arrive (the point cannot see the light)
};
using LightSample = BasicLightSample<float>;

/// The first ray of a light path: it leaves `ray.origin` (on the light; its outward normal
/// `normal` there, zero for a light at a point) with radiance (or intensity) `radiance`
/// along the ray, `cosine` the |cos| between the ray and `normal` (one at a point), the point
/// drawn with density `position_pdf` per unit area and the direction with `direction_pdf` per
/// unit solid angle. A light path carries radiance x cosine / (choice x position_pdf x
/// direction_pdf) along its first ray.
struct EmittedRay {
  Ray ray;
  Color radiance;
  float cosine;
  float position_pdf;
  float direction_pdf;
  Vec3 normal;
  std::uint32_t sphere;  ///< the light's sphere, or kNoSphere

  /// The emission at the ray's origin over the densities of the light (chosen with probability
  /// `choice`) and of the point: a light path's weight at its first vertex.
  Color origin_weight(float choice) const { return radiance / (choice * position_pdf); }
  /// What the light path carries along the ray.
  Color ray_weight(float choice) const { return origin_weight(choice) * (cosine / direction_pdf); }
};

/// The densities with which sample_le gives a point and a direction from it.
struct EmissionDensity {
  float position;
  float direction;
};

/// A light an estimator can sample from a point and start light paths from.
///  - `kDeltaPosition`: the light is a point, which no ray meets: only sampling finds it.
///  - `kAtInfinity`: the light lies infinitely far away (the environment): its light arrives
///    where a ray escapes, its density is per unit solid angle, and a light path's first point
///    lies on a disc facing its direction, with a density per unit area of the disc.
///  - `sample_li(at, u)`: light arriving at `at` from a direction drawn by `u`.
///  - `pdf_li(at, direction, distance, normal)`: the density with which sample_li gives
///    `direction`, where the ray from `at` along it meets the light at `distance` with outward
///    normal `normal` there (zero for a light at a point).
///  - `sample_le(u_point, u_direction)` and `pdf_le(normal, direction)`: a light path's first
///    ray and its densities, for a ray leaving the light's point of outward normal `normal`.
///  - `surface_normal(point)`: the outward normal at a point of the light's surface (zero for
///    a light at a point), for a vertex that a sample's ray found on it.
///  - `power()`: the light's emitted power (mean of the channels), in watts.
template <typename L>
concept Light = requires(const L& light, const LightPoint& at, Vec2 u, const Vec3& v, float t) {
  { L::kDeltaPosition } -> std::convertible_to<bool>;
  { L::kAtInfinity } -> std::convertible_to<bool>;
  { light.sample_li(at, u) } -> std::same_as<LightSample>;
  { light.pdf_li(at, v, t, v) } -> std::same_as<float>;
  { light.sample_le(u, u) } -> std::same_as<EmittedRay>;
  { light.pdf_le(v, v) } -> std::same_as<EmissionDensity>;
  { light.surface_normal(v) } -> std::same_as<Vec3>;
  { light.power() } -> std::same_as<double>;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
