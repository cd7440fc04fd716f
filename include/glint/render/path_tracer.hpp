#pragma once
// The radiance estimator, generic over a Config. Units (see README): a point light of
// intensity I (W/sr) at distance d gives irradiance I * colour * cos(theta) / d^2; a diffuse
// lobe reflects diffuse * colour / pi of its irradiance as radiance.
//
// Two material models share the per-hit physics below:
//  - the report's (traces_every_lobe): every lobe contributes, mirror and refraction rays are
//    all traced, so a path is a tree;
//  - the stochastic one: one lobe is chosen per bounce with probability proportional to its
//    coefficient, so a path is a chain with the same expectation.
// In both, a diffuse hit gathers the point lights directly (with hard shadows) and bounces
// once in a random direction; emission is picked up wherever a ray lands.

#include <cmath>
#include <cstdint>

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/math/sampling.hpp"
#include "glint/scene/scene.hpp"

namespace glint {

/// Per-thread tallies; plain integers, summed once at the end of a render.
struct TraceCounters {
  std::uint64_t rays = 0;
};

namespace detail {

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

/// Snell's law; false on total internal reflection.
inline bool refract(const Vec3& direction, const Interface& at, float eta, Vec3& refracted) {
  const float sin2_transmitted = eta * eta * (1.0f - at.cos_incident * at.cos_incident);
  if (sin2_transmitted >= 1.0f) return false;
  const float cos_transmitted = std::sqrt(1.0f - sin2_transmitted);
  refracted = glm::normalize(eta * direction +
                             (eta * at.cos_incident - cos_transmitted) * at.facing_normal);
  return true;
}

}  // namespace detail

template <RenderConfig C>
class PathTracer {
 public:
  using SamplerType = typename C::sampler;

  PathTracer(const Scene& scene, int max_depth)
      : scene_(scene), background_(scene.description().background), max_depth_(max_depth) {}

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
  struct SpecularChoice {
    Vec3 direction;
    bool valid;
  };

  /// The direction light continues in through a transparent surface: refracted, or reflected
  /// on total internal reflection or (fully transparent spheres with Fresnel) with
  /// probability F.
  SpecularChoice transmission(const Ray& ray, const detail::Interface& at,
                              const SurfaceProperties& m, SamplerType& sampler) const {
    const float eta_incident = at.from_inside ? m.ior_inside : m.ior_outside;
    const float eta_transmitted = at.from_inside ? m.ior_outside : m.ior_inside;
    Vec3 refracted;
    if (!detail::refract(ray.direction, at, eta_incident / eta_transmitted, refracted))
      return {detail::reflect(ray.direction, at), true};
    if constexpr (C::fresnel::enabled) {
      if (m.fully_transparent) {
        const float reflectance =
            C::fresnel::reflectance(at.cos_incident, eta_incident, eta_transmitted);
        if (sampler.next_1d() < reflectance) return {detail::reflect(ray.direction, at), true};
      }
    }
    return {refracted, true};
  }

  Color diffuse_albedo(const SurfaceProperties& m, const SurfaceHit& hit) const {
    return m.diffuse * C::shading::color(m.shading, m.diffuse_color, hit.local_direction);
  }

  Ray bounce_ray(const SurfaceHit& hit, const detail::Interface& at, SamplerType& sampler,
                 float& weight) const {
    const DirectionSample sample = C::diffuse_sampling::sample(sampler.next_2d());
    weight = sample.weight;
    const Vec3 direction = Frame::around(at.facing_normal).to_world(sample.local_direction);
    return ray_leaving_sphere(hit.point, direction, hit.sphere, hit.outward_normal);
  }

  /// Russian roulette hook: false ends the path; otherwise `weight` is scaled by 1/p.
  bool survives(int depth, float throughput, SamplerType& sampler, float& weight) const {
    if constexpr (C::termination::uses_roulette) {
      const float p = C::termination::continue_probability(depth, throughput);
      if (p < 1.0f) {
        if (sampler.next_1d() >= p) return false;
        weight /= p;
      }
    }
    return true;
  }

  Color trace_tree(const Ray& ray, int depth, float throughput, SamplerType& sampler,
                   TraceCounters& counters) const {
    ++counters.rays;
    SphereHit hit;
    if (!scene_.intersect(ray, hit)) return background_;
    const SurfaceHit surface = scene_.surface_hit(ray, hit);
    const SurfaceProperties& m = scene_.surface(hit.sphere);
    const detail::Interface at = detail::interface_at(ray, surface.outward_normal);

    Color radiance = m.emission;
    float continuation = 1.0f;
    const bool bounce = depth < max_depth_ && survives(depth, throughput, sampler, continuation);

    if (m.diffuse > 0.0f) {
      const Color albedo = diffuse_albedo(m, surface);
      Color incoming = kInvPi * direct_irradiance(surface.point, at.facing_normal,
                                                  surface.outward_normal, hit.sphere, counters);
      if (bounce) {
        float weight;
        const Ray next = bounce_ray(surface, at, sampler, weight);
        const float factor = weight * kInvPi * continuation;
        incoming +=
            factor * trace_tree(next, depth + 1, throughput * max_component(albedo) * factor,
                                sampler, counters);
      }
      radiance += albedo * incoming;
    }
    if (bounce && m.mirror > 0.0f) {
      const Ray next = ray_leaving_sphere(surface.point, detail::reflect(ray.direction, at),
                                          hit.sphere, surface.outward_normal);
      const Color weight = (m.mirror * continuation) * m.mirror_color;
      radiance += weight * trace_tree(next, depth + 1, throughput * max_component(weight), sampler,
                                      counters);
    }
    if (bounce && m.transparent > 0.0f) {
      const SpecularChoice choice = transmission(ray, at, m, sampler);
      const Ray next =
          ray_leaving_sphere(surface.point, choice.direction, hit.sphere, surface.outward_normal);
      const Color weight = (m.transparent * continuation) * m.transparent_color;
      radiance += weight * trace_tree(next, depth + 1, throughput * max_component(weight), sampler,
                                      counters);
    }
    return radiance;
  }

  Color trace_chain(Ray ray, SamplerType& sampler, TraceCounters& counters) const {
    Color radiance(0.0f);
    Color throughput(1.0f);
    for (int depth = 0;; ++depth) {
      ++counters.rays;
      SphereHit hit;
      if (!scene_.intersect(ray, hit)) {
        radiance += throughput * background_;
        break;
      }
      const SurfaceHit surface = scene_.surface_hit(ray, hit);
      const SurfaceProperties& m = scene_.surface(hit.sphere);
      const detail::Interface at = detail::interface_at(ray, surface.outward_normal);
      radiance += throughput * m.emission;

      Color albedo(0.0f);
      if (m.diffuse > 0.0f) {
        albedo = diffuse_albedo(m, surface);
        radiance += (throughput * albedo) *
                    (kInvPi * direct_irradiance(surface.point, at.facing_normal,
                                                surface.outward_normal, hit.sphere, counters));
      }
      const float total = m.diffuse + m.mirror + m.transparent;
      if (depth >= max_depth_ || !(total > 0.0f)) break;
      float continuation = 1.0f;
      if (!survives(depth, max_component(throughput), sampler, continuation)) break;

      // Choose one lobe with probability coefficient / total; its weight is then
      // coefficient * colour / probability = total * colour (albedo already holds diffuse).
      const float u = sampler.next_1d() * total;
      if (u < m.diffuse) {
        float weight;
        ray = bounce_ray(surface, at, sampler, weight);
        throughput *= albedo * (weight * kInvPi * total / m.diffuse * continuation);
      } else if (u < m.diffuse + m.mirror) {
        ray = ray_leaving_sphere(surface.point, detail::reflect(ray.direction, at), hit.sphere,
                                 surface.outward_normal);
        throughput *= m.mirror_color * (total * continuation);
      } else {
        const SpecularChoice choice = transmission(ray, at, m, sampler);
        ray =
            ray_leaving_sphere(surface.point, choice.direction, hit.sphere, surface.outward_normal);
        throughput *= m.transparent_color * (total * continuation);
      }
    }
    return radiance;
  }

  const Scene& scene_;
  Color background_;
  int max_depth_;
};

}  // namespace glint
