#pragma once
// The scene's background as a light (render/light.hpp): light arriving from every direction,
// infinitely far away, from an image or of one colour. From a point it draws a direction in
// proportion to the image's light, or uniformly for a colour (Environment::sample), and the light
// arrives where the ray escapes the scene (the path tracers draw from an image only: a colour
// comes as well by their bounces). Light paths enter the scene along a drawn direction through a
// uniform point of the disc of the scene's bounding sphere that faces it (Scene::bounds), so that
// every point of the scene's content is reached by parallel rays of every direction; a light
// path whose disc point something hides from the light (a floor the disc dips below, the walls of
// a closed room) carries nothing, which the bidirectional estimators test.
//
// Units: radiance (W / (m^2 sr)). A light path's first vertex lies on that disc: its density is
// per unit area of the disc, 1 / (pi r^2), and its direction's per unit solid angle, as a point
// sees the image.

#include <cmath>
#include <cstdint>

#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/light.hpp"
#include "glint/scene/environment.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class EnvironmentLight {
 public:
  static constexpr bool kDeltaPosition = false;
  static constexpr bool kAtInfinity = true;

  /// The environment of `scene`: its image, or its colour.
  explicit EnvironmentLight(const Scene& scene)
      : environment_(&scene.environment()), bounds_(scene.bounds()) {}

  const Environment& environment() const { return *environment_; }

  /// A direction drawn in proportion to the image's light by `u`, with the radiance from it,
  /// for each lane of `lanes` of a Float's lanes of points (the same bits at every width). The
  /// light arrives where the ray escapes: sphere kNoSphere at infinite distance.
  template <typename F>
  BasicLightSample<F> sample_li(const BasicLightPoint<F>& at, const Vec2For<F>& u,
                                MaskFor<F> lanes = mask_of<MaskFor<F>>(true)) const {
    using V3 = Vec3For<F>;
    BasicLightSample<F> sample{splat_vector<V3>(Vec3(0.0f, 0.0f, 1.0f)),
                               splat_vector<V3>(Color(0.0f)),
                               splat<F>(0.0f),
                               splat<F>(kInfinity),
                               at.point,
                               splat<UIntFor<F>>(kNoSphere),
                               mask_of<MaskFor<F>>(false)};
    if constexpr (kLanesOf<F> == 1) {
      if (lanes) {
        const Environment::DirectionSample drawn = environment_->sample(u);
        sample.direction = drawn.direction;
        sample.pdf = drawn.pdf;
        sample.radiance = environment_->radiance_at(drawn.uv);
        sample.valid = drawn.pdf > 0.0f;
      }
    } else {
      for (int i = 0; i < kLanesOf<F>; ++i) {
        if (!lane(lanes, i)) continue;
        const BasicLightSample<float> one =
            sample_li(BasicLightPoint<float>{lane(at.point, i), kNoSphere, false},
                      Vec2(lane(u.x, i), lane(u.y, i)));
        set_lane(sample.direction, i, one.direction);
        set_lane(sample.radiance, i, one.radiance);
        set_lane(sample.pdf, i, one.pdf);
        sample.valid[i] = one.valid ? -1 : 0;  // a mask lane is all ones or all zeros
      }
    }
    return sample;
  }

  /// The density with which sample_li gives `direction`: the same from every point.
  float pdf_li(const LightPoint&, const Vec3& direction, float, const Vec3&) const {
    return environment_->pdf(direction);
  }

  /// A light path's first ray: a direction towards the light drawn by `u`, and the ray along
  /// its reverse from a uniform point, by `u_point`, of the disc of the bounding sphere facing
  /// that direction.
  EmittedRay sample_le(Vec2 u_point, Vec2 u) const {
    const Environment::DirectionSample drawn = environment_->sample(u);
    const Vec3 towards = drawn.direction;
    const Frame frame = Frame::around(towards);
    const Vec2 disc = sample_uniform_disc(u_point);
    Ray ray;
    ray.origin = bounds_.center +
                 bounds_.radius * (towards + disc.x * frame.tangent + disc.y * frame.bitangent);
    ray.direction = -towards;
    // A draw at a pole of the image has no density to divide by (a sampler may give u = 0
    // exactly): the path carries nothing.
    if (!(drawn.pdf > 0.0f))
      return {ray, Color(0.0f), 1.0f, disc_pdf(), 1.0f, Vec3(0.0f), kNoSphere};
    return {ray,      environment_->radiance_at(drawn.uv), 1.0f, disc_pdf(), drawn.pdf, Vec3(0.0f),
            kNoSphere};
  }

  /// The densities of sample_le for a ray travelling in `direction` (`normal` unused: the
  /// disc faces every ray it starts).
  EmissionDensity pdf_le(const Vec3&, const Vec3& direction) const {
    return {disc_pdf(), environment_->pdf(-direction)};
  }

  /// The density per unit area, on the disc sample_le starts light paths from, of the light path
  /// that reaches `point` along the reverse of unit direction `towards` (towards the light):
  /// that of sample_le where the point lies within the disc's cylinder and not before the disc,
  /// zero elsewhere (no light path reaches it).
  float disc_density(const Vec3& towards, const Vec3& point) const {
    const Vec3 offset = point - bounds_.center;
    const float along = glm::dot(offset, towards);
    const Vec3 across = offset - along * towards;
    const float radius2 = bounds_.radius * bounds_.radius;
    return along <= bounds_.radius && glm::dot(across, across) <= radius2 ? disc_pdf() : 0.0f;
  }

  /// A light path never starts on a surface of the environment.
  Vec3 surface_normal(const Vec3&) const { return Vec3(0.0f); }

  /// The power that crosses the bounding sphere's disc from every direction: pi r^2 times the
  /// radiance integrated over the sphere of directions, 4 pi times its mean.
  double power() const {
    const double radius = double(bounds_.radius);
    return double(kPi) * radius * radius * 4.0 * double(kPi) * environment_->mean_radiance();
  }

 private:
  float disc_pdf() const { return 1.0f / (kPi * bounds_.radius * bounds_.radius); }

  const Environment* environment_;
  BoundingSphere bounds_;
};

static_assert(Light<EnvironmentLight>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
