#pragma once
// What both estimators share: finding the next hit and setting it up for shading, gathering
// the point lights there, and the path termination policy. Units (see README): a point light
// of intensity I (W/sr) at distance d gives irradiance I * colour * cos(theta) / d^2; a diffuse
// lobe reflects diffuse * colour / pi of its irradiance as radiance.

#include <cmath>
#include <cstdint>
#include <optional>

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/render/scattering.hpp"
#include "glint/scene/scene.hpp"

namespace glint {

/// Per-thread tallies; plain integers, summed once at the end of a render.
struct TraceCounters {
  std::uint64_t rays = 0;             ///< camera, bounce and shadow rays
  std::uint64_t invalid_samples = 0;  ///< NaN or infinite samples, dropped
};

/// The scene as an estimator sees it, with the policies of Config C that do not depend on
/// how lobes are followed. Cheap to copy (a reference and two values).
template <RenderConfig C>
class PathContext {
 public:
  using SamplerType = typename C::sampler;

  PathContext(const Scene& scene, int max_depth)
      : scene_(scene), background_(scene.background()), max_depth_(max_depth) {}

  // Finding the hit and setting it up are two steps, the set-up after the estimator's test for
  // a miss: done in one function before that test, the same arithmetic is fused into
  // multiply-adds differently once inlined, and the chain's images change in their last bits.

  /// The first sphere along `ray`, if any. Counts the ray.
  std::optional<SphereHit> closest_hit(const Ray& ray, TraceCounters& counters) const {
    ++counters.rays;
    return scene_.closest_hit(ray);
  }

  /// The hit `hit` of `ray`, set up for shading.
  SurfaceInteraction interaction(const Ray& ray, const SphereHit& hit) const {
    const SurfaceHit surface_hit = scene_.surface_hit(ray, hit);
    const SurfaceProperties& surface = scene_.surface(hit.sphere);
    return {surface_hit, &surface, detail::interface_at(ray, surface_hit.outward_normal)};
  }

  /// The ray leaving the hit in `direction`.
  static Ray continue_ray(const SurfaceInteraction& interaction, const Vec3& direction) {
    return ray_leaving_sphere(interaction.hit.point, direction, interaction.hit.sphere,
                              interaction.hit.outward_normal);
  }

  /// Irradiance at the hit from all point lights, through hard shadows, on the side the ray
  /// came from (lights behind it contribute nothing).
  Color direct_irradiance(const SurfaceInteraction& interaction, TraceCounters& counters) const {
    const Vec3& point = interaction.hit.point;
    const Vec3& facing_normal = interaction.at.facing_normal;
    Color irradiance(0.0f);
    for (const PointLight& light : scene_.lights()) {
      const Vec3 to_light = light.position - point;
      const float distance2 = glm::dot(to_light, to_light);
      const float distance = std::sqrt(distance2);
      const Vec3 direction = to_light / distance;
      const float cosine = glm::dot(direction, facing_normal);
      if (!(cosine > 0.0f)) continue;
      ++counters.rays;
      if (scene_.occluded(ray_leaving_sphere(point, direction, interaction.hit.sphere,
                                             interaction.hit.outward_normal, distance)))
        continue;
      irradiance += (light.intensity * cosine / distance2) * light.color;
    }
    return irradiance;
  }

  /// Russian roulette: none if the path ends here, otherwise the weight 1/p that keeps the
  /// estimate unbiased (1 when the policy does not play).
  std::optional<float> roulette_weight(int depth, float throughput, SamplerType& sampler) const {
    if constexpr (C::path_termination::uses_roulette) {
      const float p = C::path_termination::continue_probability(depth, throughput);
      if (p < 1.0f) {
        if (sampler.next_1d() >= p) return std::nullopt;
        return 1.0f / p;
      }
    }
    return 1.0f;
  }

  const Color& background() const { return background_; }
  int max_depth() const { return max_depth_; }

 private:
  const Scene& scene_;
  Color background_;
  int max_depth_;
};

}  // namespace glint
