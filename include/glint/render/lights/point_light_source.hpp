#pragma once
// A point light of the scene as a light (render/light.hpp): intensity I times its colour in
// every direction (W / sr), 4 pi I colour in all. No ray meets it, so only sampling finds it:
// the light arriving at a point is I colour / d^2 from its one direction, and a light path
// leaves it in a direction uniform over the sphere.

#include <cmath>

#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/light.hpp"
#include "glint/scene/emitters.hpp"
#include "glint/scene/scene_description.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class PointLightSource {
 public:
  static constexpr bool kDeltaPosition = true;
  static constexpr bool kAtInfinity = false;

  explicit PointLightSource(const PointLight& light)
      : position_(light.position), intensity_(light.intensity), color_(light.color) {}

  const Vec3& position() const { return position_; }

  /// The light arriving at a Float's lanes of points (F = float: one point): from the
  /// light's direction, I colour / d^2, with "density" one; valid where the point is not the
  /// light's. Draws nothing: the uniform numbers of the interface are not read.
  template <typename F>
  BasicLightSample<F> sample_li(const BasicLightPoint<F>& at, const Vec2For<F>&) const {
    return sample_li(at);
  }
  template <typename F>
  BasicLightSample<F> sample_li(const BasicLightPoint<F>& at) const {
    using V3 = Vec3For<F>;
    const V3 to_light = splat_vector<V3>(position_) - at.point;
    const F distance2 = dot(to_light, to_light);
    const F distance = sqrt(distance2);
    return {to_light / distance,
            (intensity_ / distance2) * splat_vector<V3>(color_),
            splat<F>(1.0f),
            distance,
            splat_vector<V3>(position_),
            splat<UIntFor<F>>(kNoSphere),
            distance2 > 0.0f};
  }

  /// No ray meets a point: no direction has a density.
  float pdf_li(const LightPoint&, const Vec3&, float, const Vec3&) const { return 0.0f; }

  /// A light path's first ray, uniform over the sphere of directions by `u` (`u_point` unused).
  EmittedRay sample_le(Vec2, Vec2 u) const {
    Ray ray;
    ray.origin = position_;
    ray.direction = sample_uniform_sphere(u);
    return {ray, intensity_ * color_, 1.0f, 1.0f, 1.0f / (4.0f * kPi), Vec3(0.0f), kNoSphere};
  }

  EmissionDensity pdf_le(const Vec3&, const Vec3&) const { return {1.0f, 1.0f / (4.0f * kPi)}; }

  Vec3 surface_normal(const Vec3&) const { return Vec3(0.0f); }

  double power() const { return 4.0 * double(kPi) * double(intensity_) * channel_mean(color_); }

 private:
  Vec3 position_;
  float intensity_;
  Color color_;
};

static_assert(Light<PointLightSource>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
