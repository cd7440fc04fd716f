#pragma once
// How light scatters at a hit: the side of the surface a ray arrives on, the mirror and Snell
// directions, and the report's material as a component that samples, evaluates and gives the
// density of its lobes. The estimators (render/estimators/) decide which lobes to follow; this
// component only answers for one lobe, or for one lobe chosen by coefficient.
//
// Everything here is written once over a Float type (math/wide.hpp): float for one path, a
// SIMD vector for a Float's lanes of paths, which the wavefront renderer shades together.
// Sample values are drawn through next_1d(draws, mask) and next_2d(draws, mask): from a
// sampler at width 1, from a block of samplers wider, only for the lanes of the mask.

#include <concepts>
#include <cstdint>
#include <type_traits>

#include "glint/config.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/wide.hpp"
#include "glint/scene/scene.hpp"
#include "glint/scene/surface_lanes.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A sample value for the lanes of `mask` (the others get unspecified values): `draws` is a
/// Sampler at width 1, or a block of W paths' samplers with next_1d(mask) and next_2d(mask).
template <Sampler S>
float next_1d(S& sampler, bool mask) {
  return mask ? sampler.next_1d() : 0.0f;
}
template <Sampler S>
Vec2 next_2d(S& sampler, bool mask) {
  return mask ? sampler.next_2d() : Vec2(0.0f);
}
template <typename Block, WideNumber M>
auto next_1d(Block& block, M mask) {
  return block.next_1d(mask);
}
template <typename Block, WideNumber M>
auto next_2d(Block& block, M mask) {
  return block.next_2d(mask);
}

namespace detail {

/// The side of a surface a ray arrives on, lane by lane.
template <typename V3>
struct BasicInterface {
  V3 facing_normal;          ///< unit normal on the side the ray came from
  FloatOf<V3> cos_incident;  ///< cosine between the reversed ray and facing_normal, in [0, 1]
  MaskFor<FloatOf<V3>> from_inside;
};
using Interface = BasicInterface<Vec3>;

template <typename V3>
BasicInterface<V3> interface_at(const V3& direction, const V3& outward_normal) {
  const auto cos_out = dot(direction, outward_normal);
  const auto from_inside = cos_out > 0.0f;
  return {select(from_inside, -outward_normal, outward_normal), abs(cos_out), from_inside};
}

template <typename V3>
V3 reflect(const V3& direction, const BasicInterface<V3>& at) {
  return direction + (2.0f * at.cos_incident) * at.facing_normal;
}

/// The refracted direction by Snell's law (eta = incident index / transmitted index) and the
/// lanes of total internal reflection, whose direction is unspecified.
template <typename V3>
struct Refraction {
  V3 direction;
  MaskFor<FloatOf<V3>> total_internal;
};
template <typename V3>
Refraction<V3> refract(const V3& direction, const BasicInterface<V3>& at, FloatOf<V3> eta) {
  using F = FloatOf<V3>;
  const F sin2_transmitted = eta * eta * (1.0f - at.cos_incident * at.cos_incident);
  const F cos_transmitted = sqrt(max(splat<F>(0.0f), 1.0f - sin2_transmitted));
  return {normalize(eta * direction + (eta * at.cos_incident - cos_transmitted) * at.facing_normal),
          sin2_transmitted >= 1.0f};
}

}  // namespace detail

/// Where a Float's lanes of rays met the scene, with everything shading needs there: the
/// geometry, the spheres' properties and the side each ray came from.
template <typename F>
struct BasicSurfaceInteraction {
  using V3 = Vec3For<F>;
  V3 point;
  V3 outward_normal;  ///< also the direction from the centre, which sphere shading reads
  UIntFor<F> sphere;
  SurfaceLanes<F> surface;
  detail::BasicInterface<V3> at;

  /// The hits at distances `t` along `rays` of spheres `sphere`, in the lanes of `lanes`.
  static BasicSurfaceInteraction at_hit(const Scene& scene, const V3& origin, const V3& direction,
                                        F t, UIntFor<F> sphere, MaskFor<F> lanes) {
    BasicSurfaceInteraction it;
    it.sphere = sphere;
    it.surface = gather_surfaces<F>(scene, sphere, lanes);
    it.point = origin + t * direction;
    it.outward_normal = normalize(it.point - it.surface.center);
    it.at = detail::interface_at(direction, it.outward_normal);
    return it;
  }
};
using SurfaceInteraction = BasicSurfaceInteraction<float>;

/// The three lobes of the report's material.
enum class Lobe : std::uint8_t { diffuse, mirror, transmission };

/// What a path carries: radiance (a camera path, followed from the eye) or importance (a light
/// path, followed from a light). The two see the same material but for refraction: a camera
/// path's radiance goes through an interface unscaled, so a light path, its adjoint, is scaled by
/// (incident index / transmitted index)^2 there, the ratio of the solid angles the interface
/// maps onto each other. (A path that enters and leaves a sphere is scaled by 1 either way.)
enum class Transport : std::uint8_t { radiance, importance };

/// A Lobe per lane: the Lobe itself at width 1, its value in an Int lane wider.
template <typename F>
using LobeFor = std::conditional_t<kLanesOf<F> == 1, Lobe, IntFor<F>>;
template <typename F>
LobeFor<F> lobe_lanes(Lobe lobe) {
  if constexpr (kLanesOf<F> == 1)
    return lobe;
  else
    return splat<IntFor<F>>(std::int32_t(lobe));
}

/// One sampled lobe direction per lane: what pbrt-v4's BSDFSample and Mitsuba 3's BSDFSample3f
/// hold. The weight f·cos/pdf is kept as two factors, weight = tint * factor, so that the
/// estimators fold their own scalars (roulette) into `factor` before the colour.
template <typename F>
struct BasicScatterSample {
  Vec3For<F> direction;  ///< unit direction the light continues in (away from the surface)
  Vec3For<F> tint;       ///< the colour part of the weight
  F factor;              ///< the scalar part of the weight
  /// Density of `direction`: per solid angle for the diffuse lobe; for a delta lobe (mirror,
  /// refraction) the discrete probability of having chosen it.
  F pdf;
  MaskFor<F> delta;  ///< a mirror or refraction direction: no other direction has a density
  LobeFor<F> lobe;

  Vec3For<F> weight() const { return tint * factor; }
};
using ScatterSample = BasicScatterSample<float>;

/// The report's material at a Float's lanes of hits: a diffuse lobe (coloured by the sphere's
/// shading, directions drawn by C::diffuse_sampling), a mirror lobe and a transmission lobe
/// (refraction, with Fresnel reflection by C::fresnel for fully transparent spheres and total
/// internal reflection). Each lobe's weight is its coefficient times its colour. Built per hit.
template <RenderConfig C, typename F = float>
class ReportMaterial {
 public:
  using V3 = Vec3For<F>;
  using M = MaskFor<F>;

  /// The material at `interaction` (its lanes of `lanes`), reached along `incoming`.
  ReportMaterial(const BasicSurfaceInteraction<F>& interaction, const V3& incoming,
                 M lanes = mask_of<M>(true))
      : s_(interaction.surface),
        at_(interaction.at),
        incoming_(incoming),
        albedo_(splat_vector<V3>(Color(0.0f))),
        total_(s_.diffuse + s_.mirror + s_.transparent) {
    const M diffuse = lanes && s_.diffuse > 0.0f;
    if (any(diffuse)) {
      // The sphere's colour at the point, from the shading policy lane by lane where it
      // depends on the point (a policy is written for one point).
      V3 color = s_.diffuse_color;
      const M patterned = diffuse && s_.shading != std::int32_t(ShadingKind::uniform);
      if (any(patterned))
        for (int i = 0; i < kLanesOf<F>; ++i)
          if (lane(patterned, i))
            set_lane(color, i,
                     C::sphere_shading::color(ShadingKind(lane(s_.shading, i)), lane(color, i),
                                              lane(interaction.outward_normal, i)));
      albedo_ = select(diffuse, s_.diffuse * color, albedo_);
    }
  }

  /// Whether the surface reflects at all (some lobe has a positive coefficient).
  M scatters() const { return total_ > 0.0f; }
  M has_lobe(Lobe lobe) const { return coefficient(lobe) > 0.0f; }
  /// The diffuse coefficient times the sphere's colour at the hit (zero without a diffuse lobe).
  const V3& albedo() const { return albedo_; }

  /// Samples lobe `lobe` alone in the lanes of `lanes`; its weight carries the lobe's
  /// coefficient (for the estimator that follows every lobe). Diffuse draws one next_2d;
  /// transmission one next_1d where Fresnel applies; the mirror draws nothing.
  template <Transport mode = Transport::radiance, typename Draws>
  BasicScatterSample<F> sample_lobe(Lobe lobe, Draws& draws, M lanes = mask_of<M>(true)) const {
    switch (lobe) {
      case Lobe::diffuse: {
        BasicScatterSample<F> s = sample_diffuse(next_2d(draws, lanes));
        s.factor = s.factor * kInvPi;
        return s;
      }
      case Lobe::mirror:
        return {mirror_direction(), s_.mirror_color,  s_.mirror,
                splat<F>(1.0f),     mask_of<M>(true), lobe_lanes<F>(Lobe::mirror)};
      case Lobe::transmission:
      default: {
        BasicScatterSample<F> s = sample_transmission<mode>(draws, lanes);
        s.tint = s_.transparent_color;
        s.factor = mode == Transport::radiance ? s_.transparent : s_.transparent * s.factor;
        return s;
      }
    }
  }

  /// Chooses one lobe per lane with probability coefficient / total (one next_1d), then
  /// samples it; the weight is divided by that probability and the pdf multiplied by it, so
  /// the expectation is that of following every lobe. Requires scatters() in `lanes`.
  template <Transport mode = Transport::radiance, typename Draws>
  BasicScatterSample<F> sample(Draws& draws, M lanes = mask_of<M>(true)) const {
    const F u = next_1d(draws, lanes) * total_;
    const M diffuse = u < s_.diffuse;
    const M mirror = !diffuse && u < s_.diffuse + s_.mirror;
    const M transmits = lanes && !(diffuse || mirror);
    // One draw per lane after the choice: the diffuse direction's or Fresnel's.
    const Vec2For<F> u_diffuse = next_2d(draws, lanes && diffuse);
    BasicScatterSample<F> s{mirror_direction(), s_.mirror_color,  total_,
                            s_.mirror / total_, mask_of<M>(true), lobe_lanes<F>(Lobe::mirror)};
    if (any(transmits)) {
      const BasicScatterSample<F> t = sample_transmission<mode>(draws, transmits);
      s.direction = select(transmits, t.direction, s.direction);
      s.tint = select(transmits, s_.transparent_color, s.tint);
      if constexpr (mode == Transport::importance)
        s.factor = select(transmits, s.factor * t.factor, s.factor);
      s.pdf = select(transmits, t.pdf * (s_.transparent / total_), s.pdf);
      s.lobe = select(transmits, t.lobe, s.lobe);
    }
    if (any(lanes && diffuse)) {
      const BasicScatterSample<F> d = sample_diffuse(u_diffuse);
      s.direction = select(diffuse, d.direction, s.direction);
      s.tint = select(diffuse, d.tint, s.tint);
      s.factor = select(diffuse, d.factor * kInvPi * total_ / s_.diffuse, s.factor);
      s.pdf = select(diffuse, d.pdf * (s_.diffuse / total_), s.pdf);
      s.delta = !diffuse;
      s.lobe = select(diffuse, d.lobe, s.lobe);
    }
    return s;
  }

  /// f·cos for `direction` leaving the surface: the diffuse lobe only, since a delta lobe has
  /// no value at a given direction.
  V3 evaluate(const V3& direction) const {
    const F cosine = dot(direction, at_.facing_normal);
    return select(cosine > 0.0f, albedo_ * (kInvPi * cosine), splat_vector<V3>(Color(0.0f)));
  }

  /// Density of sample_lobe(lobe) producing `direction` (zero for delta lobes).
  F lobe_pdf(Lobe lobe, const V3& direction) const {
    if (lobe != Lobe::diffuse) return splat<F>(0.0f);
    return C::diffuse_sampling::pdf(dot(direction, at_.facing_normal));
  }

  /// Density of sample() producing `direction` (zero unless diffuse; requires scatters()).
  F pdf(const V3& direction) const {
    return s_.diffuse / total_ * lobe_pdf(Lobe::diffuse, direction);
  }

  /// The probability that sample() chooses `lobe` (requires scatters()).
  F lobe_probability(Lobe lobe) const { return coefficient(lobe) / total_; }

 private:
  F coefficient(Lobe lobe) const {
    switch (lobe) {
      case Lobe::diffuse:
        return s_.diffuse;
      case Lobe::mirror:
        return s_.mirror;
      case Lobe::transmission:
      default:
        return s_.transparent;
    }
  }

  /// A diffuse direction with tint = albedo and factor = cos/pdf (without the 1/pi of the
  /// Lambertian f, which the callers multiply in at their place in the product).
  BasicScatterSample<F> sample_diffuse(const Vec2For<F>& u) const {
    const BasicDirectionSample<F> sample = C::diffuse_sampling::sample(u);
    const V3 direction = BasicFrame<V3>::around(at_.facing_normal).to_world(sample.local_direction);
    return {direction,         albedo_,
            sample.weight,     C::diffuse_sampling::pdf(sample.local_direction.z),
            mask_of<M>(false), lobe_lanes<F>(Lobe::diffuse)};
  }

  V3 mirror_direction() const { return detail::reflect(incoming_, at_); }

  /// The direction light continues in through a transparent surface: refracted, or reflected
  /// on total internal reflection or (fully transparent spheres with Fresnel) with probability
  /// F, for the lanes of `lanes`. The pdf is the probability of the branch taken; the tint is
  /// left for the caller, and the factor is the adjoint's scaling for importance (1 for
  /// radiance, and where the light reflects).
  template <Transport mode, typename Draws>
  BasicScatterSample<F> sample_transmission(Draws& draws, M lanes) const {
    const F eta_incident = select(at_.from_inside, s_.ior, s_.ior_outside);
    const F eta_transmitted = select(at_.from_inside, s_.ior_outside, s_.ior);
    const detail::Refraction<V3> refracted =
        detail::refract(incoming_, at_, eta_incident / eta_transmitted);
    // Refraction or total internal reflection without a Fresnel choice: probability 1.
    M reflects = refracted.total_internal;
    F pdf = splat<F>(1.0f);
    if constexpr (C::fresnel::enabled) {
      const M by_fresnel = lanes && !refracted.total_internal && s_.fully_transparent;
      if (any(by_fresnel)) {
        const F reflectance =
            C::fresnel::reflectance(at_.cos_incident, eta_incident, eta_transmitted);
        const M fresnel_reflects = by_fresnel && next_1d(draws, by_fresnel) < reflectance;
        reflects = reflects || fresnel_reflects;
        pdf = select(by_fresnel, select(fresnel_reflects, reflectance, 1.0f - reflectance), pdf);
      }
    }
    F factor = splat<F>(1.0f);
    if constexpr (mode == Transport::importance) {
      const F ratio = eta_incident / eta_transmitted;
      factor = select(reflects, factor, ratio * ratio);
    }
    return {select(reflects, mirror_direction(), refracted.direction),
            splat_vector<V3>(Color(0.0f)),
            factor,
            pdf,
            mask_of<M>(true),
            lobe_lanes<F>(Lobe::transmission)};
  }

  const SurfaceLanes<F>& s_;  // the interaction's, which outlives the material
  detail::BasicInterface<V3> at_;
  V3 incoming_;
  V3 albedo_;
  F total_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
