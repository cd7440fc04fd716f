#pragma once
// One lobe per bounce, iteratively.

#include <optional>

#include "glint/config.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/scattering.hpp"

namespace glint {

/// Follows one lobe per bounce, chosen with probability proportional to its coefficient
/// (ReportMaterial::sample), so a path is a chain with the expectation of the tree at linear
/// cost. A diffuse hit gathers the point lights directly (and samples an emissive sphere when
/// C::light_sampling says so); emission is picked up wherever a ray lands, weighted against
/// that light sampling; C::path_termination may end a path before the maximum depth. Named by
/// StochasticMaterialModel.
template <typename C>
class ChainEstimator {
  static_assert(RenderConfig<C>);

 public:
  using SamplerType = typename C::sampler;
  static constexpr bool kSamplesEmitters = PathContext<C>::kSamplesEmitters;

  explicit ChainEstimator(const PathContext<C>& context) : context_(context) {}

  /// Radiance arriving along `ray` (a camera ray).
  Color radiance(Ray ray, SamplerType& sampler, TraceCounters& counters) const {
    Color radiance(0.0f);
    Color throughput(1.0f);
    [[maybe_unused]] typename PathContext<C>::Origin from{};
    for (int depth = 0;; ++depth) {
      const std::optional<SphereHit> hit = context_.closest_hit(ray, counters);
      if (!hit) {
        radiance += throughput * context_.background();
        break;
      }
      const SurfaceInteraction interaction = context_.interaction(ray, *hit);
      if constexpr (kSamplesEmitters)
        radiance += throughput * context_.weighted_emission(ray, *hit, interaction, from);
      else
        radiance += throughput * interaction.material().emission;
      const ReportMaterial<C> material(interaction, ray.direction);
      if (material.has_lobe(Lobe::diffuse)) {
        radiance += (throughput * material.albedo()) *
                    (kInvPi * context_.direct_irradiance(interaction, counters));
        // Only where a bounce may follow, so that both strategies cover the same paths.
        if constexpr (kSamplesEmitters)
          if (depth < context_.max_depth())
            radiance +=
                throughput * context_.sample_emitter(
                                 interaction, material,
                                 [&](const Vec3& direction) { return material.pdf(direction); },
                                 sampler, counters);
      }
      if (depth >= context_.max_depth() || !material.scatters()) break;
      const std::optional<float> continuation =
          context_.roulette_weight(depth, max_component(throughput), sampler);
      if (!continuation) break;

      const ScatterSample next = material.sample(sampler);
      if constexpr (kSamplesEmitters) from = PathContext<C>::origin_of(next);
      ray = PathContext<C>::continue_ray(interaction, next.direction);
      throughput *= next.tint * (next.factor * *continuation);
    }
    return radiance;
  }

 private:
  PathContext<C> context_;
};

}  // namespace glint
