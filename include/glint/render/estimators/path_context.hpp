#pragma once
// What the camera-path estimators share: finding the next hit and setting it up for shading, the
// rays towards the point lights there, sampling the emissive spheres and the environment's image
// and weighting the emission and the environment a bounce finds (C::light_sampling), and the path
// termination policy. Written once over a Float
// type (math/wide.hpp): one path at width 1, a Float's lanes of paths wider. Units (see
// docs/library.md): a point light of intensity I (W/sr) at distance d brings radiance
// I * colour / d^2 from its one direction, which the hit's Bsdf reflects as f |cos| of it.
//
// Path length, one meaning for every light and every estimator: max_depth is the number of
// bounces after the camera ray, so light reaches the camera after at most max_depth + 1
// scattering vertices, whether it comes from a point light, an emissive sphere or the
// background. A ray's depth is the number of scattering vertices before its hit; a hit at depth
// max_depth gathers its light and bounces once more, and the hit of that bounce (depth
// max_depth + 1) only collects the emission or background it finds.

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/emitter_choice.hpp"
#include "glint/render/bsdf.hpp"
#include "glint/render/light.hpp"
#include "glint/render/lights/environment_light.hpp"
#include "glint/render/lights/point_light_source.hpp"
#include "glint/render/lights/sphere_light.hpp"
#include "glint/render/scattering.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Whether a ray can meet light: the scene has emissive spheres or a background that is not
/// black. Where it cannot, the bounce from a path's last scattering vertex would find nothing,
/// and the estimators leave it out.
inline bool rays_can_find_light(const Scene& scene) {
  return !scene.emitters().empty() || !scene.environment().is_black();
}

/// Per-thread tallies; plain integers, summed once at the end of a render.
struct TraceCounters {
  std::uint64_t rays = 0;             ///< camera, bounce and shadow rays
  std::uint64_t invalid_samples = 0;  ///< NaN or infinite samples, dropped
};

/// Where the light rays of a shading step go: traced at once (TracedLight) or queued for a
/// batched trace (the wavefront renderer). shadow_rays: rays towards point lights, bringing
/// `light` (the radiance the hit reflects back along the path) where nothing blocks them;
/// emitter_rays: rays towards points sampled on emissive spheres, bringing `light` where the
/// first sphere they meet is `emitter_sphere`.
template <typename Q, typename F>
concept LightRayQueue = requires(Q queue, MaskFor<F> lanes, const RayFor<F>& rays,
                                 const Vec3For<F>& color, UIntFor<F> sphere) {
  queue.shadow_rays(lanes, rays, color);
  queue.emitter_rays(lanes, rays, sphere, color);
};

/// The scene as an estimator sees it, with the policies of Config C that do not depend on
/// how lobes are followed. Cheap to copy (a reference and a few values).
template <RenderConfig C>
class PathContext {
 public:
  using SamplerType = typename C::sampler;
  static constexpr bool kSamplesEmitters = C::light_sampling::samples_emitters;

 private:
  /// The light sampling policy's emitter choice, named only where the policy samples emitters
  /// (the default argument is resolved where it is used).
  template <typename L = typename C::light_sampling>
  using EmitterChoiceOf = typename L::emitter_choice;

 public:
  PathContext(const Scene& scene, int max_depth)
      : scene_(scene),
        max_depth_(max_depth),
        has_emitters_(!scene.emitters().empty()),
        samples_environment_(kSamplesEmitters && scene.environment().has_image() &&
                             !scene.environment().is_black()),
        last_bounce_finds_light_(rays_can_find_light(scene)) {
    // A light sample goes to the environment or to an emitter, half the time each where the
    // scene has both: a fixed share, the same at every point, so that the weight of the light a
    // bounce finds needs no more than the bounce's direction.
    environment_share_ = samples_environment_ ? (has_emitters_ ? 0.5f : 1.0f) : 0.0f;
    emitter_share_ = samples_environment_ ? 1.0f - environment_share_ : 1.0f;
  }

  const Scene& scene() const { return scene_; }
  int max_depth() const { return max_depth_; }
  /// Whether light samples go to the environment's image as well as to the emitters.
  bool samples_environment() const { return samples_environment_; }

  /// The light of the environment for the lanes of `lanes`, whose rays escape in `direction`,
  /// each chosen by a bounce with density `from_pdf` (zero for a camera ray or a delta lobe),
  /// with its MIS weight: one unless light sampling could have chosen the same direction.
  template <typename F>
  Vec3For<F> escaped(MaskFor<F> lanes, const Vec3For<F>& direction, F from_pdf) const {
    const Environment& environment = scene_.environment();
    if constexpr (kSamplesEmitters) {
      if (samples_environment_) {
        // Lane by lane, the map from each direction to the image computed once for its radiance
        // and its density.
        Vec3For<F> radiance = splat_vector<Vec3For<F>>(Color(0.0f));
        for (int i = 0; i < kLanesOf<F>; ++i) {
          if (!lane(lanes, i)) continue;
          const Vec3 d = lane(direction, i);
          const float bounce = lane(from_pdf, i);
          if (bounce > 0.0f) {
            const Environment::Found found = environment.find(d);
            set_lane(radiance, i,
                     found.radiance *
                         C::light_sampling::bounce_weight(bounce, environment_share_ * found.pdf));
          } else {
            set_lane(radiance, i, environment.radiance(d));
          }
        }
        return radiance;
      }
    }
    return environment.radiance<F>(lanes, direction);
  }

  /// The lanes whose hit at `depth` scatters light (gathers it and may bounce): at most
  /// max_depth + 1 scattering vertices. A hit beyond only collects emission.
  template <typename D>
  MaskFor<D> scatters_at(D depth) const {
    return depth <= max_depth_;
  }

  /// The lanes whose scattering vertex at `depth` may bounce: below max_depth always, at
  /// max_depth only where the bounce's hit can find light to collect.
  template <typename D>
  MaskFor<D> bounces_from(D depth) const {
    return depth < max_depth_ ||
           (depth == max_depth_ && mask_of<MaskFor<D>>(last_bounce_finds_light_));
  }

  /// The first sphere along `ray`, if any. Counts the ray.
  std::optional<SphereHit> closest_hit(const Ray& ray, TraceCounters& counters) const {
    ++counters.rays;
    return scene_.closest_hit(ray);
  }

  /// The hit `hit` of `ray`, set up for shading.
  SurfaceInteraction interaction(const Ray& ray, const SphereHit& hit) const {
    return SurfaceInteraction::at_hit(scene_, ray.origin, ray.direction, hit.t, hit.sphere, true);
  }

  /// The rays leaving the hits in `direction`.
  template <typename F>
  static RayFor<F> continue_rays(const BasicSurfaceInteraction<F>& it,
                                 const Vec3For<F>& direction) {
    return rays_leaving_spheres(it.point, direction, it.sphere, it.outward_normal,
                                splat<F>(kInfinity));
  }

  /// For each point light on the side each ray came from (or on either side, where a lobe with a
  /// density transmits), in the scene's order, the shadow rays of the lanes of `lanes` that it
  /// lights, with the light `bsdf` scatters of it back along the path (f |cos| times the light's
  /// radiance I colour / d^2) where they are not blocked, to `queue.shadow_rays`.
  template <typename F, typename B, typename Queue>
  void light_rays(MaskFor<F> lanes, const BasicSurfaceInteraction<F>& it, const B& bsdf,
                  Queue& queue, TraceCounters& counters) const {
    const BasicLightPoint<F> at{it.point, it.sphere, it.at.from_inside};
    const MaskFor<F> two_sided = bsdf.transmits_with_density();
    for (const PointLight& light : scene_.lights()) {
      const BasicLightSample<F> sample = PointLightSource(light).sample_li(at);
      const F cosine = dot(sample.direction, it.at.facing_normal);
      const MaskFor<F> lit = lanes && sample.valid && (cosine > 0.0f || two_sided);
      if (!any(lit)) continue;
      counters.rays += count(lit);
      queue.shadow_rays(
          lit,
          rays_leaving_spheres(it.point, sample.direction, it.sphere, it.outward_normal,
                               sample.distance),
          bsdf.template evaluate<Transport::radiance>(sample.direction) * sample.radiance);
    }
  }

  /// The emission at the hits of `rays` (lanes of `lanes`), each reached by a bounce whose
  /// direction had density `from_pdf` (zero for a camera ray or a delta lobe), with its MIS
  /// weight: one unless light sampling could have chosen the same direction.
  template <typename F>
  Vec3For<F> weighted_emission(MaskFor<F> lanes, const RayFor<F>& rays, F t,
                               const BasicSurfaceInteraction<F>& it, F from_pdf) const {
    if constexpr (!kSamplesEmitters) {
      return it.surface.emission;
    } else {
      const MaskFor<F> weighed = lanes && it.surface.emitter != kNotAnEmitter && from_pdf > 0.0f;
      if (!any(weighed)) return it.surface.emission;
      F weight = splat<F>(1.0f);
      for (int i = 0; i < kLanesOf<F>; ++i)
        if (lane(weighed, i))
          set_lane(weight, i,
                   emission_weight(lane(rays.origin, i), lane(rays.origin_sphere, i),
                                   lane(rays.heads_into_origin_sphere, i) != 0,
                                   lane(rays.direction, i), lane(t, i), lane(it.outward_normal, i),
                                   lane(it.surface.emitter, i), lane(from_pdf, i)));
      return it.surface.emission * weight;
    }
  }

  /// Light sampling at the hits of `lanes`: per lane, the environment's image (by its share)
  /// or one emitter, chosen by the light sampling policy's emitter choice (on both sides of the
  /// surface where a lobe with a density transmits), and a direction towards it, scattered by
  /// `bsdf` and weighted against the estimator's own bounce, whose density for a direction is
  /// `bounce_pdf(direction)`. One next_1d and one next_2d per lane whenever the scene has
  /// emitters or an environment image, none otherwise (so such a scene renders exactly as
  /// without light sampling). The rays that can bring light go to `queue.emitter_rays`, those
  /// towards the environment with kNoSphere: its light arrives where they meet nothing.
  template <typename F, typename B, typename BouncePdf, typename Draws, typename Queue>
  void emitter_rays(MaskFor<F> lanes, const BasicSurfaceInteraction<F>& it, const B& bsdf,
                    BouncePdf&& bounce_pdf, Draws& draws, Queue& queue,
                    TraceCounters& counters) const {
    using V3 = Vec3For<F>;
    using M = MaskFor<F>;
    if (!has_emitters_ && !samples_environment_) return;
    const F u_choice = next_1d(draws, lanes);
    const Vec2For<F> u = next_2d(draws, lanes);
    // A two-sided point sees its own sphere's light from inside, through the lobe that
    // transmits, whichever side it was reached from.
    const M two_sided = bsdf.transmits_with_density();
    const M from_inside = it.at.from_inside || two_sided;
    // The environment's share of u_choice, and the rest stretched back to [0, 1) for the
    // emitter choice (exactly, for a share of one half).
    M to_environment = mask_of<M>(false);
    F u_emitter = u_choice;
    if (samples_environment_) {
      const M below = u_choice < environment_share_;
      to_environment = lanes && below;
      if (has_emitters_)
        u_emitter = select(below, u_choice / environment_share_,
                           (u_choice - environment_share_) / emitter_share_);
    }
    const M to_emitters = lanes && !to_environment;
    BasicLightSample<F> sample{};
    F light_pdf = splat<F>(0.0f);
    M valid = mask_of<M>(false);
    if (any(to_emitters)) {
      const EmitterLanes<F> chosen = EmitterChoiceOf<>::choose(
          scene_.emitters(),
          EmitterChoicePoint<F>{it.point, it.at.facing_normal, it.sphere, from_inside, two_sided},
          u_emitter);
      const BasicSphereLight<F> light(chosen.center, chosen.radius, chosen.radiance, chosen.sphere);
      sample = light.sample_li({it.point, it.sphere, from_inside}, u, to_emitters);
      light_pdf = chosen.probability * emitter_share_ * sample.pdf;
      valid = to_emitters && chosen.probability > 0.0f && sample.valid && sample.pdf > 0.0f;
    }
    if (any(to_environment)) {
      const BasicLightSample<F> far = EnvironmentLight(scene_).sample_li(
          BasicLightPoint<F>{it.point, it.sphere, from_inside}, u, to_environment);
      sample.direction = select(to_environment, far.direction, sample.direction);
      sample.radiance = select(to_environment, far.radiance, sample.radiance);
      sample.sphere = select(to_environment, far.sphere, sample.sphere);
      light_pdf = select(to_environment, environment_share_ * far.pdf, light_pdf);
      valid = valid || (to_environment && far.valid);
    }
    const V3 reflected = bsdf.template evaluate<Transport::radiance>(sample.direction);
    const M arrives = valid && (reflected.x != 0.0f || reflected.y != 0.0f || reflected.z != 0.0f);
    if (!any(arrives)) return;
    const F weight = C::light_sampling::light_weight(light_pdf, bounce_pdf(sample.direction));
    counters.rays += count(arrives);
    queue.emitter_rays(arrives, continue_rays(it, sample.direction), sample.sphere,
                       reflected * sample.radiance * (weight / light_pdf));
  }

  /// Russian roulette for the lanes of `lanes` at `depth`: the lanes that go on, and in
  /// `weight` the factor 1/p that keeps the estimate unbiased (1 where the policy does not
  /// play). One next_1d per lane where it plays.
  template <typename F, typename Draws>
  MaskFor<F> roulette(MaskFor<F> lanes, IntFor<F> depth, F throughput, Draws& draws,
                      F& weight) const {
    weight = splat<F>(1.0f);
    if constexpr (C::path_termination::uses_roulette) {
      const F p = C::path_termination::continue_probability(depth, throughput);
      const MaskFor<F> played = lanes && p < 1.0f;
      if (any(played)) {
        lanes = lanes && !(played && next_1d(draws, played) >= p);
        weight = select(played, 1.0f / p, weight);
      }
    }
    return lanes;
  }

 private:
  /// The number of true lanes of a mask.
  template <typename M>
  static std::uint64_t count(M mask) {
    return std::uint64_t(std::popcount(bits_of_mask(mask)));
  }

  /// The MIS weight of the emission of emitter `index`, met at distance `t` (outward normal
  /// `normal` there) by a ray from `origin` in `direction`, chosen by a bounce with density
  /// `from_pdf` > 0 from sphere `origin_sphere`, into it if `heads_into_origin_sphere`.
  float emission_weight(const Vec3& origin, std::uint32_t origin_sphere,
                        bool heads_into_origin_sphere, const Vec3& direction, float t,
                        const Vec3& normal, std::uint32_t index, float from_pdf) const {
    const SphereLight emitter(scene_.emitters()[index]);
    // A bounce that has a density either reflected, and so left on the side the path arrived
    // from, or went through a two-sided surface, where the side does not matter: the light
    // sample at its origin saw the same point, normal (up to its sign, which a two-sided choice
    // ignores) and side, rebuilt here as the hit computed them, and so chose with the same
    // probability, to the bit.
    const SurfaceProperties& surface = scene_.surface(origin_sphere);
    const Vec3 outward = outward_normal_at(origin, surface.center);
    const bool two_sided = BsdfAt<C>::transmits_with_density_at(surface);
    const EmitterChoicePoint<float> at{origin, heads_into_origin_sphere ? -outward : outward,
                                       origin_sphere, heads_into_origin_sphere || two_sided,
                                       two_sided};
    // The ray started on its origin sphere; if that is the emitter it hit, it left it inwards
    // (a ray leaving a sphere outwards cannot meet it again), so the point saw it from inside.
    const float light_pdf = EmitterChoiceOf<>::probability(scene_.emitters(), at, index) *
                            emitter_share_ *
                            emitter.pdf_li({origin, origin_sphere, true}, direction, t, normal);
    return C::light_sampling::bounce_weight(from_pdf, light_pdf);
  }

  const Scene& scene_;
  int max_depth_;
  bool has_emitters_;
  bool samples_environment_;
  bool last_bounce_finds_light_;
  /// The probabilities that a light sample goes to the environment and to an emitter.
  float environment_share_ = 0.0f;
  float emitter_share_ = 1.0f;
};

/// A LightRayQueue that traces each ray at once, for one path (width 1): the reflected light
/// of the point lights whose shadow rays are not blocked, and the light of the emitter sample if
/// it arrives.
class TracedLight {
 public:
  explicit TracedLight(const Scene& scene) : scene_(scene) {}

  void shadow_rays(bool lit, const Ray& ray, const Color& light) {
    if (lit && !scene_.occluded(ray)) point_light_ += light;
  }
  void emitter_rays(bool sampled, const Ray& ray, std::uint32_t emitter_sphere,
                    const Color& light) {
    if (!sampled) return;
    const std::optional<SphereHit> hit = scene_.closest_hit(ray);
    // A shadow ray with the emitter's distance as its end would have to beat the rounding of
    // that distance: the light arrives where the first sphere along the ray is the emitter (or,
    // for the environment, kNoSphere: where the ray meets none).
    emitter_visible_ = (hit ? hit->sphere : kNoSphere) == emitter_sphere;
    emitter_light_ = light;
  }

  /// The point lights' light reflected back along the path.
  const Color& point_light() const { return point_light_; }
  bool emitter_visible() const { return emitter_visible_; }
  const Color& emitter_light() const { return emitter_light_; }

 private:
  const Scene& scene_;
  Color point_light_{0.0f};
  bool emitter_visible_ = false;
  Color emitter_light_{0.0f};
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
