#pragma once
// Where light paths start: a light of the scene chosen in proportion to its power, a point on
// it and a direction it emits in, with the weight that makes the path an unbiased estimate of
// the light it carries. Point lights and emissive spheres are the scene's lights; the background
// is not one of them (a scene whose background is not black cannot be light traced, see
// LightEmission::supports).
//
// Units, as the camera paths see them (render/estimators/path_context.hpp): a point light of
// intensity I and colour c emits I c watts per steradian in every direction, 4 pi I c in all; an
// emissive sphere of radiance L emits L from both sides of its surface, pi L per unit area on
// each side, 2 pi L times its area in all.

#include <cmath>
#include <cstdint>
#include <vector>

#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/vector.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The start of a light path: a point on a light and the light's emission there over the
/// densities of having chosen them.
struct LightOrigin {
  Vec3 point;
  /// The outward normal of the emissive sphere at the point; zero for a point light.
  Vec3 normal;
  std::uint32_t sphere;  ///< the emissive sphere the point lies on; kNoSphere for a point light
  /// For a sphere: its radiance over (probability of the light x density of the point per unit
  /// area). For a point light: its intensity times colour over the probability of the light.
  Color weight;
  /// The density of having chosen the point: the light's probability, per unit area on a
  /// sphere.
  float density;
  bool is_point_light() const { return sphere == kNoSphere; }
};

/// The first ray of a light path and the weight it carries: the light's emission along it over
/// the densities of the choices that made it (light, point, direction), cosine included.
struct LightRay {
  Ray ray;
  Color weight;
};

/// The scene's lights as light paths see them.
class LightEmission {
 public:
  explicit LightEmission(const Scene& scene) : scene_(&scene) {
    std::vector<double> power;
    for (std::uint32_t i = 0; i < scene.lights().size(); ++i) {
      const PointLight& light = scene.lights()[i];
      lights_.push_back({Kind::point, i});
      power.push_back(4.0 * double(kPi) * double(light.intensity) * channel_mean(light.color));
    }
    for (std::uint32_t i = 0; i < scene.emitters().size(); ++i) {
      const SphereEmitter& e = scene.emitters()[i];
      lights_.push_back({Kind::sphere, i});
      power.push_back(2.0 * double(kPi) * double(e.area()) * channel_mean(e.radiance));
    }
    double total = 0.0;
    for (const double p : power)
      total += p;
    empty_ = !(total > 0.0);
    cumulative_choice(power, cdf_, probability_);
  }

  /// Whether the scene has no light with power: then no light path carries anything.
  bool empty() const { return empty_; }

  /// A light chosen in proportion to power: a point light (`index` in the scene's point lights)
  /// or an emissive sphere (`index` in its emitters), with the probability of the choice.
  struct Choice {
    bool point_light;
    std::uint32_t index;
    float probability;
  };
  /// The light for a uniform number u in [0, 1), as sample_origin chooses it. Requires !empty().
  Choice choose(float u) const {
    const std::size_t entry = choice_of(cdf_, u);
    return {lights_[entry].kind == Kind::point, lights_[entry].index, probability_[entry]};
  }

  /// The density with which sample_origin chooses a point of emitter `emitter`, per unit area.
  float sphere_density(std::uint32_t emitter) const {
    return probability_[scene_->lights().size() + emitter] / scene_->emitters()[emitter].area();
  }

  /// Density per unit solid angle of sample_ray's direction from a point light.
  static float point_direction_pdf() { return 1.0f / (4.0f * kPi); }
  /// Density per unit solid angle of sample_ray's `direction` from a point of a sphere of
  /// outward normal `normal` there: a side with probability 1/2, then the cosine about it.
  static float sphere_direction_pdf(const Vec3& normal, const Vec3& direction) {
    return 0.5f * kInvPi * std::fabs(glm::dot(normal, direction));
  }
  /// Density per unit solid angle of sample_ray's `direction` from `origin`.
  static float direction_pdf(const LightOrigin& origin, const Vec3& direction) {
    return origin.is_point_light() ? point_direction_pdf()
                                   : sphere_direction_pdf(origin.normal, direction);
  }

  /// Whether light paths carry all of the scene's light: its background is black.
  static bool supports(const Scene& scene) {
    const Color background = scene.background();
    return background.r == 0.0f && background.g == 0.0f && background.b == 0.0f;
  }

  /// A light chosen by `u_choice` in proportion to power, and a point on it: uniformly on an
  /// emissive sphere's area by `u_point` (unused for a point light). Requires !empty().
  LightOrigin sample_origin(float u_choice, Vec2 u_point) const {
    const std::size_t index = choice_of(cdf_, u_choice);
    const Entry& light = lights_[index];
    const float probability = probability_[index];
    if (light.kind == Kind::point) {
      const PointLight& point = scene_->lights()[light.index];
      return {point.position, Vec3(0.0f), kNoSphere, (point.intensity * point.color) / probability,
              probability};
    }
    const SphereEmitter& e = scene_->emitters()[light.index];
    const Vec3 normal = sample_uniform_sphere(u_point);
    return {e.center + e.radius * normal, normal, e.sphere, e.radiance * (e.area() / probability),
            probability / e.area()};
  }

  /// A direction for the light leaving `origin`, by `u`: uniform over the sphere of directions
  /// from a point light; from a sphere, one side chosen with probability 1/2, then a direction
  /// distributed as the cosine about that side's normal.
  static LightRay sample_ray(const LightOrigin& origin, Vec2 u) {
    if (origin.is_point_light()) {
      Ray ray;
      ray.origin = origin.point;
      ray.direction = sample_uniform_sphere(u);
      return {ray, origin.weight * (4.0f * kPi)};
    }
    const bool outwards = u.x < 0.5f;
    const Vec2 u_side(outwards ? 2.0f * u.x : 2.0f * u.x - 1.0f, u.y);
    const Vec3 side = outwards ? origin.normal : -origin.normal;
    const Vec3 direction =
        BasicFrame<Vec3>::around(side).to_world(sample_cosine_hemisphere(u_side));
    // Radiance x cos over (cos / pi x 1/2): the cosine cancels.
    return {ray_leaving_sphere(origin.point, direction, origin.sphere, !outwards),
            origin.weight * (2.0f * kPi)};
  }

 private:
  enum class Kind : std::uint8_t { point, sphere };
  struct Entry {
    Kind kind;
    std::uint32_t index;  ///< in the scene's point lights or its emitters
  };

  const Scene* scene_;
  std::vector<Entry> lights_;
  std::vector<float> cdf_;  ///< of the choice by power (cumulative_choice)
  std::vector<float> probability_;
  bool empty_ = true;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
