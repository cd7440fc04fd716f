#pragma once
// What both estimators share: finding the next hit and setting it up for shading, gathering
// the point lights there, sampling the emissive spheres and weighting the emission a bounce
// finds (C::light_sampling), and path termination. Units (docs/library.md): a point light
// of intensity I (W/sr) at distance d gives irradiance I * colour * cos(theta) / d^2; a diffuse
// lobe reflects diffuse * colour / pi of its irradiance as radiance.

#include <cmath>
#include <cstdint>
#include <optional>
#include <type_traits>

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

/// How the ray that reached a hit was chosen, which light sampling needs to weigh the emission
/// found there. (Where it started is the ray's own origin and origin sphere.)
struct BounceOrigin {
  /// Density of the ray's direction per unit solid angle; zero for a camera ray and for a
  /// delta lobe, whose emission is not shared with light sampling (weight one).
  float pdf = 0.0f;
};

/// What the estimators carry instead of a BounceOrigin when C::light_sampling does not sample
/// emitters: nothing.
struct NoBounceOrigin {};

/// The scene as an estimator sees it, with the policies of Config C that do not depend on
/// how lobes are followed. Cheap to copy (a reference and two values).
template <RenderConfig C>
class PathContext {
 public:
  using SamplerType = typename C::sampler;
  static constexpr bool kSamplesEmitters = C::light_sampling::samples_emitters;
  /// BounceOrigin when emitters are sampled, otherwise the empty NoBounceOrigin.
  using Origin = std::conditional_t<kSamplesEmitters, BounceOrigin, NoBounceOrigin>;

  PathContext(const Scene& scene, int max_depth)
      : scene_(scene),
        background_(scene.background()),
        max_depth_(max_depth),
        has_emitters_(!scene.emitters().empty()) {}

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
    Color irradiance(0.0f);
    for_each_light_ray(interaction, [&](const Ray& shadow_ray, const Color& light_irradiance) {
      ++counters.rays;
      if (!scene_.occluded(shadow_ray)) irradiance += light_irradiance;
    });
    return irradiance;
  }

  /// For each point light on the side the ray came from, in the scene's order: visit(shadow
  /// ray, the irradiance the light gives where that ray is not blocked). direct_irradiance sums
  /// them; a batched renderer queues the rays.
  template <typename Visit>
  void for_each_light_ray(const SurfaceInteraction& interaction, Visit&& visit) const {
    const Vec3& point = interaction.hit.point;
    const Vec3& facing_normal = interaction.at.facing_normal;
    for (const PointLight& light : scene_.lights()) {
      const Vec3 to_light = light.position - point;
      const float distance2 = glm::dot(to_light, to_light);
      const float distance = std::sqrt(distance2);
      const Vec3 direction = to_light / distance;
      const float cosine = glm::dot(direction, facing_normal);
      if (!(cosine > 0.0f)) continue;
      visit(ray_leaving_sphere(point, direction, interaction.hit.sphere,
                               interaction.hit.outward_normal, distance),
            (light.intensity * cosine / distance2) * light.color);
    }
  }

  /// How a ray leaving by the lobe sampled as `sample` was chosen.
  static BounceOrigin origin_of(const ScatterSample& sample) {
    return {sample.delta ? 0.0f : sample.pdf};
  }

  /// The emission at `interaction`, reached by `ray` chosen as `origin`, with its MIS weight
  /// (one for a camera ray or a delta lobe).
  Color weighted_emission(const Ray& ray, const SphereHit& hit,
                          const SurfaceInteraction& interaction, const BounceOrigin& origin) const {
    const std::uint32_t index = interaction.surface->emitter;
    if (index == kNotAnEmitter) return interaction.material().emission;
    return interaction.material().emission * emission_weight(ray, hit, interaction, index, origin);
  }

  /// The MIS weight of the emission of emitter `index` at `interaction`.
  float emission_weight(const Ray& ray, const SphereHit& hit, const SurfaceInteraction& interaction,
                        std::uint32_t index, const BounceOrigin& origin) const {
    if (!(origin.pdf > 0.0f)) return 1.0f;
    const SphereEmitter& emitter = scene_.emitters()[index];
    // The ray started on its origin sphere; if that is the emitter it hit, it left it inwards
    // (a ray leaving a sphere outwards cannot meet it again), so the point saw it from inside.
    const EmitterView view = emitter.view_from(ray.origin, ray.origin_sphere, true);
    const float light_pdf = scene_.emitters().probability(index) *
                            emitter.direction_pdf(ray.origin, view, ray.direction, hit.t,
                                                  interaction.hit.outward_normal);
    return C::light_sampling::bounce_weight(origin.pdf, light_pdf);
  }

  /// Light from one emissive sphere reaching `interaction` and reflected by `material`'s
  /// diffuse lobe, with its MIS weight; `bounce_pdf(direction)` is the density with which the
  /// estimator's own bounce would have chosen that direction. One emitter, chosen by power;
  /// one next_1d and one next_2d whenever the scene has emitters, none otherwise (so a scene
  /// without emitters renders exactly as without light sampling).
  template <typename BouncePdf>
  Color sample_emitter(const SurfaceInteraction& interaction, const ReportMaterial<C>& material,
                       BouncePdf&& bounce_pdf, SamplerType& sampler,
                       TraceCounters& counters) const {
    const std::optional<EmitterRay> sample =
        emitter_ray(interaction, material, bounce_pdf, sampler);
    if (!sample) return Color(0.0f);
    const std::optional<SphereHit> hit = closest_hit(sample->ray, counters);
    if (!hit || hit->sphere != sample->emitter_sphere) return Color(0.0f);
    return sample->light;
  }

  /// A ray towards a point sampled on an emissive sphere, and the light it brings.
  struct EmitterRay {
    Ray ray;
    /// The light arrives if the first sphere along the ray is this one: a shadow ray with the
    /// emitter's distance as its end would have to beat the rounding of that distance.
    std::uint32_t emitter_sphere;
    Color light;  ///< what sample_emitter returns when it arrives
  };

  /// sample_emitter's sampling, without the visibility test: none if nothing can arrive.
  /// Draws what sample_emitter draws.
  template <typename BouncePdf>
  std::optional<EmitterRay> emitter_ray(const SurfaceInteraction& interaction,
                                        const ReportMaterial<C>& material, BouncePdf&& bounce_pdf,
                                        SamplerType& sampler) const {
    if (!has_emitters_) return std::nullopt;
    const EmitterTable& emitters = scene_.emitters();
    const float u_choice = sampler.next_1d();
    const Vec2 u_direction = sampler.next_2d();
    const EmitterTable::Choice choice = emitters.choose(u_choice);
    const SphereEmitter& emitter = emitters[choice.index];
    const EmitterView view = emitter.view_from(interaction.hit.point, interaction.hit.sphere,
                                               interaction.at.from_inside);
    const std::optional<EmitterDirection> sample =
        emitter.sample_direction(interaction.hit.point, view, u_direction);
    if (!sample || !(sample->pdf > 0.0f)) return std::nullopt;
    const Color reflected = material.evaluate(sample->direction);
    if (reflected == Color(0.0f)) return std::nullopt;
    const float light_pdf = choice.probability * sample->pdf;
    const float weight = C::light_sampling::light_weight(light_pdf, bounce_pdf(sample->direction));
    return EmitterRay{continue_ray(interaction, sample->direction), emitter.sphere,
                      reflected * emitter.radiance * (weight / light_pdf)};
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
  bool has_emitters_;
};

}  // namespace glint
