#pragma once
// An emissive sphere as a light (render/light.hpp): radiance leaves both sides of its surface,
// as every sphere's does. Written once over the width type: BasicSphereLight<F> holds a Float's
// lanes of lights (the ones a light sample chose for each lane's point), SphereLight one light.
//
// From a point it draws directions uniformly in the cone the sphere subtends where the point
// sees it from outside (the visible cap, exactly), and through a uniform point of its area from
// inside (every point of it is visible); a point on its outer surface sees none of it. Light
// paths start at a uniform point of its area, on a side chosen with probability 1/2, in a
// direction distributed as the cosine about that side's normal.

#include <cmath>
#include <cstdint>

#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/light.hpp"
#include "glint/scene/emitters.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// How a point sees a sphere light, which decides how directions towards it are drawn.
enum class SphereLightView : std::uint8_t {
  outside,  ///< uniformly in the cone the sphere subtends
  inside,   ///< through a uniform point on the sphere's area
  none,     ///< the point is on the light's outer surface: no direction from it reaches it
};

/// How a Float's lanes of points see their lights, as masks: `outside` where the point sees the
/// sphere from outside, `none` where it lies on its outer surface, inside otherwise.
template <typename F>
struct SphereLightViews {
  MaskFor<F> outside;
  MaskFor<F> none;
};

namespace detail {
/// 1 - cos of the half-angle a sphere of radius `radius` subtends at distance `distance` from
/// its centre: sin^2 / (1 + cos), which keeps its precision for small, distant spheres.
template <FloatType F>
inline F cone_one_minus_cos_max(F radius, F distance) {
  const F sin2_max = min(splat<F>(1.0f), (radius / distance) * (radius / distance));
  const F cos2_max =
      max(splat<F>(0.0f), (distance - radius) * (distance + radius)) / (distance * distance);
  return sin2_max / (1.0f + sqrt(cos2_max));
}
}  // namespace detail

template <typename F>
struct BasicSphereLight {
  static constexpr bool kDeltaPosition = false;
  static constexpr bool kAtInfinity = false;

  Vec3For<F> center;
  F radius;
  Vec3For<F> radiance;
  UIntFor<F> sphere;  ///< index of the sphere in the scene

  BasicSphereLight() = default;
  BasicSphereLight(const Vec3For<F>& c, F r, const Vec3For<F>& l, UIntFor<F> s)
      : center(c), radius(r), radiance(l), sphere(s) {}
  /// The light of one of a scene's emitters.
  explicit BasicSphereLight(const SphereEmitter& e) requires(kLanesOf<F> == 1)
      : center(e.center), radius(e.radius), radiance(e.radiance), sphere(e.sphere) {}

  F area() const { return 4.0f * kPi * radius * radius; }

  /// How each lane's point sees its light.
  SphereLightViews<F> views_from(const BasicLightPoint<F>& at) const {
    const auto on_light = at.sphere == sphere;
    const Vec3For<F> offset = at.point - center;
    return {!on_light && dot(offset, offset) > radius * radius, on_light && !at.from_inside};
  }
  /// How one point sees the light.
  SphereLightView view_from(const LightPoint& at) const requires(kLanesOf<F> == 1) {
    const SphereLightViews<float> view = views_from(at);
    return view.outside ? SphereLightView::outside
           : view.none  ? SphereLightView::none
                        : SphereLightView::inside;
  }

  /// A direction towards the light from the points of `lanes`, drawn by `u`, with the light
  /// arriving along it (valid where the point can see the light and the sample does not
  /// degenerate). Each way of drawing is computed only where some lane of `lanes` takes it.
  BasicLightSample<F> sample_li(const BasicLightPoint<F>& at, const Vec2For<F>& u,
                                MaskFor<F> lanes = mask_of<MaskFor<F>>(true)) const {
    const SphereLightViews<F> view = views_from(at);
    // Lanes not sampled count as outside, so that they alone never make the area branch run.
    return sample_li(at.point, !lanes || view.outside, view.none, u);
  }

  /// sample_li for points that see the light as `outside` and `none` say (inside elsewhere).
  BasicLightSample<F> sample_li(const Vec3For<F>& point, MaskFor<F> outside, MaskFor<F> none,
                                const Vec2For<F>& u) const {
    using V3 = Vec3For<F>;
    BasicLightSample<F> sample{
        splat_vector<V3>(Vec3(0.0f)), radiance, splat<F>(0.0f), splat<F>(kInfinity),
        splat_vector<V3>(Vec3(0.0f)), sphere,   outside};
    if (any(outside)) {
      const V3 to_center = center - point;
      const F distance = sqrt(dot(to_center, to_center));
      const F one_minus_cos_max = detail::cone_one_minus_cos_max(radius, distance);
      sample.direction = BasicFrame<V3>::around(to_center / distance)
                             .to_world(sample_uniform_cone(u, one_minus_cos_max));
      sample.pdf = uniform_cone_pdf(one_minus_cos_max);
    }
    if (!all(outside)) {
      const V3 normal = sample_uniform_sphere(u);
      const V3 to_light = center + radius * normal - point;
      const F distance2 = dot(to_light, to_light);
      const V3 direction = to_light / sqrt(distance2);
      const F cosine = abs(dot(direction, normal));
      const F area_pdf = distance2 / ((4.0f * kPi * radius * radius) * cosine);
      sample.direction = select(outside, sample.direction, direction);
      sample.pdf = select(outside, sample.pdf, area_pdf);
      sample.valid = outside || (!none && distance2 > 0.0f && cosine > 0.0f);
    }
    return sample;
  }

  /// The density with which sample_li gives `direction` from `at`, where the ray along it meets
  /// this sphere first at `distance`, with outward normal `normal` there.
  float pdf_li(const LightPoint& at, const Vec3& direction, float distance,
               const Vec3& normal) const requires(kLanesOf<F> == 1) {
    return pdf_li(at.point, view_from(at), direction, distance, normal);
  }
  /// pdf_li for a point that sees the light as `view` says.
  float pdf_li(const Vec3& point, SphereLightView view, const Vec3& direction, float distance,
               const Vec3& normal) const requires(kLanesOf<F> == 1) {
    switch (view) {
      case SphereLightView::outside: {
        const Vec3 to_center = center - point;
        return uniform_cone_pdf(
            detail::cone_one_minus_cos_max(radius, std::sqrt(glm::dot(to_center, to_center))));
      }
      case SphereLightView::inside: {
        const float cosine = std::fabs(glm::dot(direction, normal));
        return cosine > 0.0f ? distance * distance / (area() * cosine) : 0.0f;
      }
      case SphereLightView::none:
        break;
    }
    return 0.0f;
  }

  /// A light path's first ray: a uniform point of the area by `u_point`, then a side with
  /// probability 1/2 and a direction distributed as the cosine about its normal, by `u`.
  EmittedRay sample_le(Vec2 u_point, Vec2 u) const requires(kLanesOf<F> == 1) {
    const Vec3 normal = sample_uniform_sphere(u_point);
    const Vec3 point = center + radius * normal;
    const bool outwards = u.x < 0.5f;
    const Vec2 u_side(outwards ? 2.0f * u.x : 2.0f * u.x - 1.0f, u.y);
    const Vec3 side = outwards ? normal : -normal;
    const Vec3 direction =
        BasicFrame<Vec3>::around(side).to_world(sample_cosine_hemisphere(u_side));
    const float cosine = std::fabs(glm::dot(direction, normal));
    return {ray_leaving_sphere(point, direction, sphere, !outwards),
            radiance,
            cosine,
            1.0f / area(),
            0.5f * kInvPi * cosine,
            normal,
            sphere};
  }

  /// The densities of sample_le for a ray leaving a point of outward normal `normal` in
  /// `direction`.
  EmissionDensity pdf_le(const Vec3& normal, const Vec3& direction) const
      requires(kLanesOf<F> == 1) {
    return {1.0f / area(), 0.5f * kInvPi * std::fabs(glm::dot(normal, direction))};
  }

  Vec3 surface_normal(const Vec3& point) const requires(kLanesOf<F> == 1) {
    return glm::normalize(point - center);
  }

  /// Radiance from both sides of the whole area: 2 pi L A.
  double power() const requires(kLanesOf<F> == 1) {
    return 2.0 * double(kPi) * double(area()) * channel_mean(radiance);
  }
};

using SphereLight = BasicSphereLight<float>;
static_assert(Light<SphereLight>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
