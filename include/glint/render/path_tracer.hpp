#pragma once
// PathTracer<Config>: the radiance estimator, generic over a Config. Units (see README): a point
// light of intensity I (W/sr) at distance d gives irradiance I * colour * cos(theta) / d^2; a
// diffuse lobe reflects diffuse * colour / pi of its irradiance as radiance.

#include <cmath>
#include <cstdint>
#include <optional>

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/math/sampling.hpp"
#include "glint/scene/scene.hpp"

namespace glint {

/// Per-thread tallies; plain integers, summed once at the end of a render.
struct TraceCounters {
  std::uint64_t rays = 0;             ///< camera, bounce and shadow rays
  std::uint64_t invalid_samples = 0;  ///< NaN or infinite samples, dropped
};

namespace detail {

/// The side of a surface a ray arrives on.
struct Interface {
  Vec3 facing_normal;  ///< unit normal on the side the ray came from
  float cos_incident;  ///< cosine between the reversed ray and facing_normal, in [0, 1]
  bool from_inside;
};

inline Interface interface_at(const Ray& ray, const Vec3& outward_normal) {
  const float cos_out = glm::dot(ray.direction, outward_normal);
  const bool from_inside = cos_out > 0.0f;
  return {from_inside ? -outward_normal : outward_normal, std::fabs(cos_out), from_inside};
}

inline Vec3 reflect(const Vec3& direction, const Interface& at) {
  return direction + (2.0f * at.cos_incident) * at.facing_normal;
}

/// The refracted direction by Snell's law (eta = incident index / transmitted index); none on
/// total internal reflection.
inline std::optional<Vec3> refract(const Vec3& direction, const Interface& at, float eta) {
  const float sin2_transmitted = eta * eta * (1.0f - at.cos_incident * at.cos_incident);
  if (sin2_transmitted >= 1.0f) return std::nullopt;
  const float cos_transmitted = std::sqrt(1.0f - sin2_transmitted);
  return glm::normalize(eta * direction +
                        (eta * at.cos_incident - cos_transmitted) * at.facing_normal);
}

}  // namespace detail

/// Estimates the radiance arriving along camera rays, with the policies of Config C.
///
/// Two estimators share the per-hit physics below, chosen by C::material_model:
///  - the tree (ReportMaterialModel, the report's): every lobe with a non-zero coefficient
///    contributes, weighted by it; mirror and refraction rays are all traced, so a path
///    branches into a tree, exponential in depth for materials that mix both;
///  - the chain (StochasticMaterialModel): one lobe per bounce, chosen with probability
///    proportional to its coefficient, so a path is a chain with the same expectation.
/// In both, a diffuse hit gathers the point lights directly (with hard shadows) and bounces
/// once in a direction drawn by C::diffuse_sampling; emission is picked up wherever a ray
/// lands, and C::path_termination may end a path before the maximum depth.
template <RenderConfig C>
class PathTracer {
 public:
  using SamplerType = typename C::sampler;

  PathTracer(const Scene& scene, int max_depth)
      : scene_(scene), background_(scene.background()), max_depth_(max_depth) {}

  /// Radiance arriving along `ray` (a camera ray).
  Color radiance(const Ray& ray, SamplerType& sampler, TraceCounters& counters) const {
    if constexpr (C::material_model::traces_every_lobe)
      return trace_tree(ray, 0, 1.0f, sampler, counters);
    else
      return trace_chain(ray, sampler, counters);
  }

  /// Irradiance at a point of sphere `sphere` from all point lights, through hard shadows.
  /// `facing_normal` is the side being shaded: lights behind it contribute nothing.
  Color direct_irradiance(const Vec3& point, const Vec3& facing_normal, const Vec3& outward_normal,
                          std::uint32_t sphere, TraceCounters& counters) const {
    Color irradiance(0.0f);
    for (const PointLight& light : scene_.lights()) {
      const Vec3 to_light = light.position - point;
      const float distance2 = glm::dot(to_light, to_light);
      const float distance = std::sqrt(distance2);
      const Vec3 direction = to_light / distance;
      const float cosine = glm::dot(direction, facing_normal);
      if (!(cosine > 0.0f)) continue;
      ++counters.rays;
      if (scene_.occluded(ray_leaving_sphere(point, direction, sphere, outward_normal, distance)))
        continue;
      irradiance += (light.intensity * cosine / distance2) * light.color;
    }
    return irradiance;
  }

 private:
  /// A diffuse bounce: the ray and its weight cos(theta) / pdf.
  struct Bounce {
    Ray ray;
    float weight;
  };

  /// The direction light continues in through a transparent surface: refracted, or reflected
  /// on total internal reflection or (fully transparent spheres with Fresnel) with
  /// probability F.
  Vec3 transmitted_direction(const Ray& ray, const detail::Interface& at,
                             const SurfaceProperties& surface, SamplerType& sampler) const {
    const float ior_inside = surface.material.ior;
    const float eta_incident = at.from_inside ? ior_inside : surface.ior_outside;
    const float eta_transmitted = at.from_inside ? surface.ior_outside : ior_inside;
    const std::optional<Vec3> refracted =
        detail::refract(ray.direction, at, eta_incident / eta_transmitted);
    if (!refracted) return detail::reflect(ray.direction, at);
    if constexpr (C::fresnel::enabled) {
      if (surface.fully_transparent) {
        const float reflectance =
            C::fresnel::reflectance(at.cos_incident, eta_incident, eta_transmitted);
        if (sampler.next_1d() < reflectance) return detail::reflect(ray.direction, at);
      }
    }
    return *refracted;
  }

  /// Diffuse coefficient times the sphere's colour at the hit point.
  static Color diffuse_albedo(const SurfaceProperties& surface, const SurfaceHit& hit) {
    const Material& m = surface.material;
    return m.diffuse *
           C::sphere_shading::color(surface.shading, m.diffuse_color, hit.local_direction);
  }

  Bounce diffuse_bounce(const SurfaceHit& hit, const detail::Interface& at,
                        SamplerType& sampler) const {
    const DirectionSample sample = C::diffuse_sampling::sample(sampler.next_2d());
    const Vec3 direction = Frame::around(at.facing_normal).to_world(sample.local_direction);
    return {ray_leaving_sphere(hit.point, direction, hit.sphere, hit.outward_normal),
            sample.weight};
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

  /// The report's estimator: every lobe, recursively. `throughput` is the largest colour
  /// component of the path's weight so far, for the roulette policy.
  Color trace_tree(const Ray& ray, int depth, float throughput, SamplerType& sampler,
                   TraceCounters& counters) const {
    ++counters.rays;
    const std::optional<SphereHit> hit = scene_.closest_hit(ray);
    if (!hit) return background_;
    const SurfaceHit surface_hit = scene_.surface_hit(ray, *hit);
    const SurfaceProperties& surface = scene_.surface(hit->sphere);
    const Material& m = surface.material;
    const detail::Interface at = detail::interface_at(ray, surface_hit.outward_normal);

    Color radiance = m.emission;
    std::optional<float> continuation;
    if (depth < max_depth_) continuation = roulette_weight(depth, throughput, sampler);

    if (m.diffuse > 0.0f) {
      const Color albedo = diffuse_albedo(surface, surface_hit);
      Color incoming =
          kInvPi * direct_irradiance(surface_hit.point, at.facing_normal,
                                     surface_hit.outward_normal, hit->sphere, counters);
      if (continuation) {
        const Bounce bounce = diffuse_bounce(surface_hit, at, sampler);
        const float factor = bounce.weight * kInvPi * *continuation;
        incoming +=
            factor * trace_tree(bounce.ray, depth + 1, throughput * max_component(albedo) * factor,
                                sampler, counters);
      }
      radiance += albedo * incoming;
    }
    if (continuation && m.mirror > 0.0f) {
      const Ray next = ray_leaving_sphere(surface_hit.point, detail::reflect(ray.direction, at),
                                          hit->sphere, surface_hit.outward_normal);
      const Color weight = (m.mirror * *continuation) * m.mirror_color;
      radiance += weight * trace_tree(next, depth + 1, throughput * max_component(weight), sampler,
                                      counters);
    }
    if (continuation && m.transparent > 0.0f) {
      const Ray next =
          ray_leaving_sphere(surface_hit.point, transmitted_direction(ray, at, surface, sampler),
                             hit->sphere, surface_hit.outward_normal);
      const Color weight = (m.transparent * *continuation) * m.transparent_color;
      radiance += weight * trace_tree(next, depth + 1, throughput * max_component(weight), sampler,
                                      counters);
    }
    return radiance;
  }

  /// One lobe per bounce, iteratively.
  Color trace_chain(Ray ray, SamplerType& sampler, TraceCounters& counters) const {
    Color radiance(0.0f);
    Color throughput(1.0f);
    for (int depth = 0;; ++depth) {
      ++counters.rays;
      const std::optional<SphereHit> hit = scene_.closest_hit(ray);
      if (!hit) {
        radiance += throughput * background_;
        break;
      }
      const SurfaceHit surface_hit = scene_.surface_hit(ray, *hit);
      const SurfaceProperties& surface = scene_.surface(hit->sphere);
      const Material& m = surface.material;
      const detail::Interface at = detail::interface_at(ray, surface_hit.outward_normal);
      radiance += throughput * m.emission;

      Color albedo(0.0f);
      if (m.diffuse > 0.0f) {
        albedo = diffuse_albedo(surface, surface_hit);
        radiance += (throughput * albedo) *
                    (kInvPi * direct_irradiance(surface_hit.point, at.facing_normal,
                                                surface_hit.outward_normal, hit->sphere, counters));
      }
      const float total = m.diffuse + m.mirror + m.transparent;
      if (depth >= max_depth_ || !(total > 0.0f)) break;
      const std::optional<float> continuation =
          roulette_weight(depth, max_component(throughput), sampler);
      if (!continuation) break;

      // Choose one lobe with probability coefficient / total; its weight is then
      // coefficient * colour / probability = total * colour (albedo already holds diffuse).
      const float u = sampler.next_1d() * total;
      if (u < m.diffuse) {
        const Bounce bounce = diffuse_bounce(surface_hit, at, sampler);
        ray = bounce.ray;
        throughput *= albedo * (bounce.weight * kInvPi * total / m.diffuse * *continuation);
      } else if (u < m.diffuse + m.mirror) {
        ray = ray_leaving_sphere(surface_hit.point, detail::reflect(ray.direction, at), hit->sphere,
                                 surface_hit.outward_normal);
        throughput *= m.mirror_color * (total * *continuation);
      } else {
        ray =
            ray_leaving_sphere(surface_hit.point, transmitted_direction(ray, at, surface, sampler),
                               hit->sphere, surface_hit.outward_normal);
        throughput *= m.transparent_color * (total * *continuation);
      }
    }
    return radiance;
  }

  const Scene& scene_;
  Color background_;
  int max_depth_;
};

}  // namespace glint
