#pragma once
// One lobe per bounce, iteratively; the step of a path from one hit to the next, written once
// for one path and for a Float's lanes of paths.

#include <optional>

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/bsdf.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/materials.hpp"
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
/// are traced: where the point lights are gathered, with the throughput there.
template <typename F>
struct PendingLight {
  MaskFor<F> direct;
  Vec3For<F> throughput;
};

/// Follows one direction per bounce, sampled by the hit's Bsdf (for the report's material, one
/// lobe chosen with probability proportional to its coefficient), so a path is a chain with the
/// expectation of the report's tree at linear cost. A hit whose Bsdf has a density gathers the
/// point lights directly as f |cos| Li (and samples an emissive sphere when C::light_sampling says
/// so); emission is picked up wherever a ray lands, weighted against that light sampling;
/// C::path_termination may end a path before the maximum depth. Named by PathTracing.
///
/// step() is the whole of a bounce: the scalar renderer calls it for one path with the light
/// rays traced at once, the wavefront renderer for a SIMD register's paths with the light rays
/// queued; the same operations in the same order give every width the same image.
template <typename C>
class ChainEstimator {
  static_assert(RenderConfig<C>);
  static_assert(Bsdf<BsdfAt<C>, float, typename C::sampler>);

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
      path.radiance = add_light(path.radiance, pending, light.point_light(),
                                light.emitter_visible(), light.emitter_light());
      if (!going_on) return path.radiance;
    }
  }

  /// One bounce of the paths of `lanes`, whose rays met spheres `sphere` at distances `t`
  /// (kNoSphere: none): the background or the emission found, the light rays of a hit whose Bsdf
  /// has a density to `queue` (their light is added by add_light), roulette, the sampled
  /// direction and the next ray.
  /// Returns the paths that go on; the others' radiance is final once add_light has run.
  template <typename F, typename Draws, typename Queue>
  MaskFor<F> step(MaskFor<F> lanes, PathLanes<F>& path, F t, UIntFor<F> sphere, Draws& draws,
                  Queue& queue, PendingLight<F>& pending, TraceCounters& counters) const {
    using M = MaskFor<F>;
    using V3 = Vec3For<F>;
    static_assert(LightRayQueue<Queue, F>);
    pending.direct = mask_of<M>(false);
    const M hits = lanes && sphere != kNoSphere;
    const M escapes = lanes && !hits;
    if (any(escapes))
      path.radiance =
          select(escapes,
                 path.radiance +
                     path.throughput * context_.escaped(escapes, path.ray.direction, path.from_pdf),
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
    const BsdfAt<C, F> bsdf(it, path.ray.direction, scatters);

    // Light: the point lights' shadow rays and the emitter sample, where the Bsdf has a density.
    // Emitters are sampled only where a bounce may follow, so that both strategies cover the
    // same paths; with emitters in the scene one always may (PathContext::bounces_from).
    const M gathers = scatters && bsdf.has_density();
    if (any(gathers)) {
      pending = {gathers, path.throughput};
      context_.light_rays(gathers, it, bsdf, queue, counters);
      if constexpr (kSamplesEmitters) {
        const M bounce_may_follow = gathers && context_.bounces_from(path.depth);
        if (any(bounce_may_follow))
          context_.emitter_rays(
              bounce_may_follow, it, bsdf, [&](const V3& direction) { return bsdf.pdf(direction); },
              draws, queue, counters);
      }
    }

    // Roulette, then the next direction.
    F continuation;
    const M going_on =
        context_.roulette(scatters && context_.bounces_from(path.depth) && bsdf.scatters(),
                          path.depth, max_component(path.throughput), draws, continuation);
    if (!any(going_on)) return going_on;
    const BasicScatterSample<F> next = bsdf.template sample<Transport::radiance>(draws, going_on);
    if constexpr (kSamplesEmitters)
      path.from_pdf = select(going_on, select(next.delta, splat<F>(0.0f), next.pdf), path.from_pdf);
    path.ray = select(going_on, PathContext<C>::continue_rays(it, next.direction), path.ray);
    path.throughput = select(going_on, path.throughput * (next.tint * (next.factor * continuation)),
                             path.throughput);
    path.depth = select(going_on, path.depth + 1, path.depth);
    return going_on;
  }

  /// `radiance` with the light that a step's rays brought: the point lights' light reflected
  /// back along the path (`point_light`) where the step gathered them, and the emitter sample's
  /// `emitter_light` where it arrived (`emitter_visible`).
  template <typename F>
  static Vec3For<F> add_light(Vec3For<F> radiance, const PendingLight<F>& pending,
                              const Vec3For<F>& point_light, MaskFor<F> emitter_visible,
                              const Vec3For<F>& emitter_light) {
    radiance = select(pending.direct, radiance + pending.throughput * point_light, radiance);
    return select(emitter_visible, radiance + pending.throughput * emitter_light, radiance);
  }

 private:
  PathContext<C> context_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
