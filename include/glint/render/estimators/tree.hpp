#pragma once
// The report's estimator: every lobe, recursively.

#include <optional>

#include "glint/config.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/scattering.hpp"

namespace glint {

/// Follows every lobe with a non-zero coefficient, weighted by it: a diffuse hit gathers the
/// point lights directly and bounces once, and mirror and refraction rays are all traced, so a
/// path branches into a tree (exponential in depth for materials that mix both). Emission is
/// picked up wherever a ray lands (weighted against light sampling when C::light_sampling
/// samples emitters at diffuse hits); C::path_termination may end a branch before the maximum
/// depth. Named by ReportMaterialModel.
template <typename C>
class TreeEstimator {
  static_assert(RenderConfig<C>);

 public:
  using SamplerType = typename C::sampler;
  using Origin = typename PathContext<C>::Origin;
  static constexpr bool kSamplesEmitters = PathContext<C>::kSamplesEmitters;

  explicit TreeEstimator(const PathContext<C>& context) : context_(context) {}

  /// Radiance arriving along `ray` (a camera ray).
  Color radiance(const Ray& ray, SamplerType& sampler, TraceCounters& counters) const {
    return trace(ray, 0, 1.0f, Origin{}, sampler, counters);
  }

 private:
  /// `throughput` is the largest colour component of the path's weight so far, for the
  /// roulette policy; `from` is where the ray started, for light sampling.
  Color trace(const Ray& ray, int depth, float throughput, [[maybe_unused]] const Origin& from,
              SamplerType& sampler, TraceCounters& counters) const {
    const std::optional<SphereHit> hit = context_.closest_hit(ray, counters);
    if (!hit) return context_.background();
    const SurfaceInteraction interaction = context_.interaction(ray, *hit);
    const ReportMaterial<C> material(interaction, ray.direction);

    Color radiance;
    if constexpr (kSamplesEmitters)
      radiance = context_.weighted_emission(ray, *hit, interaction, from);
    else
      radiance = interaction.material().emission;
    std::optional<float> continuation;
    if (depth < context_.max_depth())
      continuation = context_.roulette_weight(depth, throughput, sampler);

    // The lobes in this order, each sampled just before it is traced: the order of the
    // sampler's requests is part of every image. The two delta lobes are written out rather
    // than shared in a helper: `radiance += weight * trace(...)` is fused into a multiply-add
    // only where it is inlined, so a helper that is not changes images.
    if (material.has_lobe(Lobe::diffuse)) {
      // Emitters are sampled only where a bounce may follow, so that both strategies cover
      // the same paths and the image is the one without light sampling.
      if constexpr (kSamplesEmitters)
        if (depth < context_.max_depth())
          radiance += context_.sample_emitter(
              interaction, material,
              [&](const Vec3& direction) { return material.lobe_pdf(Lobe::diffuse, direction); },
              sampler, counters);
      Color incoming = kInvPi * context_.direct_irradiance(interaction, counters);
      if (continuation) {
        const ScatterSample bounce = material.sample_lobe(Lobe::diffuse, sampler);
        const float factor = bounce.factor * *continuation;
        Origin origin{};
        if constexpr (kSamplesEmitters) origin = PathContext<C>::origin_of(bounce);
        incoming += factor * trace(PathContext<C>::continue_ray(interaction, bounce.direction),
                                   depth + 1, throughput * max_component(bounce.tint) * factor,
                                   origin, sampler, counters);
      }
      radiance += material.albedo() * incoming;
    }
    if (continuation && material.has_lobe(Lobe::mirror)) {
      const ScatterSample mirror = material.sample_lobe(Lobe::mirror, sampler);
      const Color weight = (mirror.factor * *continuation) * mirror.tint;
      radiance +=
          weight * trace(PathContext<C>::continue_ray(interaction, mirror.direction), depth + 1,
                         throughput * max_component(weight), Origin{}, sampler, counters);
    }
    if (continuation && material.has_lobe(Lobe::transmission)) {
      const ScatterSample transmission = material.sample_lobe(Lobe::transmission, sampler);
      const Color weight = (transmission.factor * *continuation) * transmission.tint;
      radiance += weight * trace(PathContext<C>::continue_ray(interaction, transmission.direction),
                                 depth + 1, throughput * max_component(weight), Origin{}, sampler,
                                 counters);
    }
    return radiance;
  }

  PathContext<C> context_;
};

}  // namespace glint
