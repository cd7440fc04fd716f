#pragma once
// The report's estimator: every lobe, recursively.

#include <optional>

#include "glint/config.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/bsdf.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/materials.hpp"
#include "glint/render/scattering.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Follows every lobe of the hit's Bsdf (a LobewiseBsdf) with a non-zero coefficient, weighted by
/// it: a diffuse lobe gathers the point lights directly (f |cos| Li) and bounces once, and mirror
/// and refraction rays are all traced, so a path branches into a tree (exponential in depth for
/// materials that mix both). Emission is
/// picked up wherever a ray lands (weighted against light sampling when C::light_sampling
/// samples emitters at diffuse hits); C::path_termination may end a branch before the maximum
/// depth. Named by TreePathTracing.
template <typename C>
class TreeEstimator {
  static_assert(RenderConfig<C>);
  static_assert(LobewiseBsdf<BsdfAt<C>, float, typename C::sampler>);

 public:
  using SamplerType = typename C::sampler;
  static constexpr bool kSamplesEmitters = PathContext<C>::kSamplesEmitters;

  explicit TreeEstimator(const PathContext<C>& context) : context_(context) {}

  /// Radiance arriving along `ray` (a camera ray).
  Color radiance(const Ray& ray, SamplerType& sampler, TraceCounters& counters) const {
    return trace(ray, 0, 1.0f, 0.0f, sampler, counters);
  }

 private:
  /// `throughput` is the largest colour component of the path's weight so far, for the
  /// roulette policy; `from_pdf` the density with which the ray's direction was chosen (zero
  /// for a camera ray or a delta lobe), for light sampling.
  Color trace(const Ray& ray, int depth, float throughput, float from_pdf, SamplerType& sampler,
              TraceCounters& counters) const {
    const std::optional<SphereHit> hit = context_.closest_hit(ray, counters);
    if (!hit) return context_.template escaped<float>(true, ray.direction, from_pdf);
    const SurfaceInteraction interaction = context_.interaction(ray, *hit);
    Color radiance = context_.weighted_emission(true, ray, hit->t, interaction, from_pdf);
    // Beyond the last scattering vertex a hit only collects what it found.
    if (!context_.scatters_at(depth)) return radiance;
    const BsdfAt<C> bsdf(interaction, ray.direction);
    float continuation = 1.0f;
    const bool goes_on = context_.bounces_from(depth) &&
                         context_.roulette(true, depth, throughput, sampler, continuation);

    // The lobes in this order, each sampled just before it is traced: the order of the
    // sampler's requests is part of every image.
    if (bsdf.has_lobe(Lobe::diffuse)) {
      TracedLight light(context_.scene());
      // Emitters are sampled only where a bounce may follow, so that both strategies cover
      // the same paths and the image is the one without light sampling (with emitters in the
      // scene one always may: PathContext::bounces_from).
      if constexpr (kSamplesEmitters)
        if (context_.bounces_from(depth)) {
          context_.emitter_rays(
              true, interaction, bsdf,
              [&](const Vec3& direction) { return bsdf.lobe_pdf(Lobe::diffuse, direction); },
              sampler, light, counters);
          if (light.emitter_visible()) radiance += light.emitter_light();
        }
      context_.light_rays(true, interaction, bsdf, light, counters);
      radiance += light.point_light();
      if (goes_on) {
        const ScatterSample bounce =
            bsdf.template sample_lobe<Transport::radiance>(Lobe::diffuse, sampler);
        const float factor = bounce.factor * continuation;
        radiance += bounce.tint *
                    (factor * trace(PathContext<C>::continue_rays(interaction, bounce.direction),
                                    depth + 1, throughput * max_component(bounce.tint) * factor,
                                    bounce.pdf, sampler, counters));
      }
    }
    for (const Lobe lobe : {Lobe::mirror, Lobe::transmission}) {
      if (!goes_on || !bsdf.has_lobe(lobe)) continue;
      const ScatterSample sample = bsdf.template sample_lobe<Transport::radiance>(lobe, sampler);
      const Color weight = (sample.factor * continuation) * sample.tint;
      radiance +=
          weight * trace(PathContext<C>::continue_rays(interaction, sample.direction), depth + 1,
                         throughput * max_component(weight), 0.0f, sampler, counters);
    }
    return radiance;
  }

  PathContext<C> context_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
