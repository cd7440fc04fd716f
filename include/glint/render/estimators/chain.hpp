#pragma once
// One lobe per bounce, iteratively; the step of a path from one hit to the next, written once
// for one path and for a Float's lanes of paths.

#include <optional>

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/scattering.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A Float's lanes of paths between two bounces (lane i: path i).
template <typename F>
struct PathLanes {
  RayFor<F> ray;  ///< the ray whose hit is shaded next
  Vec3For<F> throughput;
  Vec3For<F> radiance;
  IntFor<F> depth;
  /// Density of the ray's direction per unit solid angle; zero for a camera ray and for a
  /// delta lobe, whose emission is not shared with light sampling (weight one). Read only when
  /// emitters are sampled.
  F from_pdf;
};

/// What a step leaves for the light of its rays, added by ChainEstimator::add_light once they
/// are traced: where the point lights are gathered, with the throughput and the albedo there.
template <typename F>
struct PendingLight {
  MaskFor<F> direct;
  Vec3For<F> throughput;
  Vec3For<F> albedo;
};

/// Follows one lobe per bounce, chosen with probability proportional to its coefficient
/// (ReportMaterial::sample), so a path is a chain with the expectation of the tree at linear
/// cost. A diffuse hit gathers the point lights directly (and samples an emissive sphere when
/// C::light_sampling says so); emission is picked up wherever a ray lands, weighted against
/// that light sampling; C::path_termination may end a path before the maximum depth. Named by
/// PathTracing.
///
/// step() is the whole of a bounce: the scalar renderer calls it for one path with the light
/// rays traced at once, the wavefront renderer for a SIMD register's paths with the light rays
/// queued; the same operations in the same order give every width the same image.
template <typename C>
class ChainEstimator {
  static_assert(RenderConfig<C>);

 public:
  using SamplerType = typename C::sampler;
  static constexpr bool kSamplesEmitters = PathContext<C>::kSamplesEmitters;

  explicit ChainEstimator(const PathContext<C>& context) : context_(context) {}

  const PathContext<C>& context() const { return context_; }

  /// Radiance arriving along `ray` (a camera ray).
  Color radiance(const Ray& ray, SamplerType& sampler, TraceCounters& counters) const {
    PathLanes<float> path{ray, Color(1.0f), Color(0.0f), 0, 0.0f};
    for (;;) {
      const std::optional<SphereHit> hit = context_.closest_hit(path.ray, counters);
      const SphereHit found = hit.value_or(SphereHit{});
      TracedLight light(context_.scene());
      PendingLight<float> pending{};
      const bool going_on =
          step(true, path, found.t, found.sphere, sampler, light, pending, counters);
      path.radiance = add_light(path.radiance, pending, light.irradiance(), light.emitter_visible(),
                                light.emitter_light());
      if (!going_on) return path.radiance;
    }
  }

  /// One bounce of the paths of `lanes`, whose rays met spheres `sphere` at distances `t`
  /// (kNoSphere: none): the background or the emission found, the light rays of a diffuse hit
  /// to `queue` (their light is added by add_light), roulette, the lobe and the next ray.
  /// Returns the paths that go on; the others' radiance is final once add_light has run.
  template <typename F, typename Draws, typename Queue>
  MaskFor<F> step(MaskFor<F> lanes, PathLanes<F>& path, F t, UIntFor<F> sphere, Draws& draws,
                  Queue& queue, PendingLight<F>& pending, TraceCounters& counters) const {
    using M = MaskFor<F>;
    using V3 = Vec3For<F>;
    static_assert(LightRayQueue<Queue, F>);
    pending.direct = mask_of<M>(false);
    const M hits = lanes && sphere != kNoSphere;
    path.radiance = select(
        lanes && !hits, path.radiance + path.throughput * splat_vector<V3>(context_.background()),
        path.radiance);
    if (!any(hits)) return hits;

    const BasicSurfaceInteraction<F> it = BasicSurfaceInteraction<F>::at_hit(
        context_.scene(), path.ray.origin, path.ray.direction, t, sphere, hits);
    path.radiance =
        select(hits,
               path.radiance + path.throughput *
                                   context_.weighted_emission(hits, path.ray, t, it, path.from_pdf),
               path.radiance);
    // Beyond the last scattering vertex a hit only collects what it found.
    const M scatters = hits && context_.scatters_at(path.depth);
    if (!any(scatters)) return scatters;
    const ReportMaterial<C, F> material(it, path.ray.direction, scatters);

    // Light: the point lights' shadow rays and the emitter sample, at diffuse hits. Emitters
    // are sampled only where a bounce may follow, so that both strategies cover the same paths;
    // with emitters in the scene one always may (PathContext::bounces_from).
    const M diffuse = scatters && material.has_lobe(Lobe::diffuse);
    if (any(diffuse)) {
      pending = {diffuse, path.throughput, material.albedo()};
      context_.light_rays(diffuse, it, queue, counters);
      if constexpr (kSamplesEmitters) {
        const M bounce_may_follow = diffuse && context_.bounces_from(path.depth);
        if (any(bounce_may_follow))
          context_.emitter_rays(
              bounce_may_follow, it, material,
              [&](const V3& direction) { return material.pdf(direction); }, draws, queue, counters);
      }
    }

    // Roulette, then the lobe.
    F continuation;
    const M going_on =
        context_.roulette(scatters && context_.bounces_from(path.depth) && material.scatters(),
                          path.depth, max_component(path.throughput), draws, continuation);
    if (!any(going_on)) return going_on;
    const BasicScatterSample<F> next = material.sample(draws, going_on);
    if constexpr (kSamplesEmitters)
      path.from_pdf = select(going_on, select(next.delta, splat<F>(0.0f), next.pdf), path.from_pdf);
    path.ray = select(going_on, PathContext<C>::continue_rays(it, next.direction), path.ray);
    path.throughput = select(going_on, path.throughput * (next.tint * (next.factor * continuation)),
                             path.throughput);
    path.depth = select(going_on, path.depth + 1, path.depth);
    return going_on;
  }

  /// `radiance` with the light that a step's rays brought: the point lights' `irradiance`
  /// reflected where the step gathered them, and the emitter sample's `emitter_light` where
  /// it arrived (`emitter_visible`).
  template <typename F>
  static Vec3For<F> add_light(Vec3For<F> radiance, const PendingLight<F>& pending,
                              const Vec3For<F>& irradiance, MaskFor<F> emitter_visible,
                              const Vec3For<F>& emitter_light) {
    radiance =
        select(pending.direct,
               radiance + (pending.throughput * pending.albedo) * (kInvPi * irradiance), radiance);
    return select(emitter_visible, radiance + pending.throughput * emitter_light, radiance);
  }

 private:
  PathContext<C> context_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
