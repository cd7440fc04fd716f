#pragma once
// The report's material as a Bsdf (render/bsdf.hpp): a diffuse lobe, a mirror and a transmission
// lobe mixed by the sphere's coefficients, the transmission taking its outside index from the
// inclusion tree. Named by the material model ReportMaterialModel (policy/material_model.hpp).

#include "glint/config.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/bsdf.hpp"
#include "glint/render/scattering.hpp"
#include "glint/scene/scene.hpp"
#include "glint/scene/surface_lanes.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The report's material at a Float's lanes of hits: a diffuse lobe (coloured by the sphere's
/// shading, directions drawn by C::diffuse_sampling), a mirror lobe and a transmission lobe
/// (refraction, with Fresnel reflection by C::fresnel for fully transparent spheres and total
/// internal reflection). Each lobe's weight is its coefficient times its colour. Built per hit.
template <typename C, typename F>
class ReportMaterial {
  static_assert(RenderConfig<C>);

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
          if (lane(patterned, i)) {
            const auto kind = ShadingKind(lane(s_.shading, i));
            const ShadingPoint point{
                lane(interaction.outward_normal, i),
                kind == ShadingKind::texture && interaction.scene
                    ? interaction.scene->sphere_texture(lane(interaction.sphere, i))
                    : nullptr};
            set_lane(color, i, C::sphere_shading::color(kind, lane(color, i), point));
          }
      albedo_ = select(diffuse, s_.diffuse * color, albedo_);
    }
  }

  /// The material at a vertex of a stored subpath (RecordableBsdf): its diffuse lobe, the only
  /// one with a value and a density at given directions, on the side the subpath arrived from.
  /// Lambertian, so the same in both transport modes and independent of wo.
  struct Record {
    Color albedo{0.0f};           ///< diffuse coefficient x colour: f is albedo / pi
    float diffuse_choice = 0.0f;  ///< the probability with which sample() chooses the lobe

    bool has_density() const { return diffuse_choice > 0.0f; }
    /// No lobe with a density transmits: light is joined on the arrival side only.
    bool transmits_with_density() const { return false; }
    Color f(const Vec3& facing, const Vec3& /*wo*/, const Vec3& wi) const {
      return glm::dot(wi, facing) > 0.0f ? albedo * kInvPi : Color(0.0f);
    }
    float pdf(const Vec3& facing, const Vec3& /*wo*/, const Vec3& wi) const {
      const float cosine = glm::dot(wi, facing);
      if (!(cosine > 0.0f) || !(diffuse_choice > 0.0f)) return 0.0f;
      return diffuse_choice * C::diffuse_sampling::pdf(cosine);
    }
  };
  template <Transport mode>
  Record record() const requires(kLanesOf<F> == 1) {
    return {albedo_, s_.diffuse / total_};
  }

  /// Whether the surface reflects at all (some lobe has a positive coefficient).
  M scatters() const { return total_ > 0.0f; }
  /// Whether the diffuse lobe is present: the one with a density.
  M has_density() const { return s_.diffuse > 0.0f; }
  /// Whether a lobe with a density transmits, so that light is sampled and joined on both sides
  /// of the surface: none of the report's does.
  M transmits_with_density() const { return mask_of<M>(false); }
  /// transmits_with_density() of any hit on a sphere of properties `surface`, for an estimator
  /// that rebuilds a vertex's light sampling from the sphere alone.
  static bool transmits_with_density_at(const SurfaceProperties&) { return false; }
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
    return sample_lobes<mode>(draws, lanes, mask_of<M>(true));
  }

  /// f·cos for `direction` leaving the surface: the diffuse lobe only, since a delta lobe has
  /// no value at a given direction. The same for both transport directions (a Lambertian lobe is
  /// symmetric, and only refraction is scaled for importance).
  template <Transport mode = Transport::radiance>
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

 protected:
  /// sample(), with the transmission lobe's direction drawn only in the lanes of `ideal` (the
  /// others, where a model that extends this one has its own interface, keep the lobe's choice
  /// and tint and draw nothing more for it).
  template <Transport mode, typename Draws>
  BasicScatterSample<F> sample_lobes(Draws& draws, M lanes, M ideal) const {
    const F u = next_1d(draws, lanes) * total_;
    const M diffuse = u < s_.diffuse;
    const M mirror = !diffuse && u < s_.diffuse + s_.mirror;
    const M chose_transmission = lanes && !(diffuse || mirror);
    const M transmits = chose_transmission && ideal;
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
    if (any(chose_transmission && !ideal)) {
      const M other = chose_transmission && !ideal;
      s.tint = select(other, s_.transparent_color, s.tint);
      s.pdf = select(other, s_.transparent / total_, s.pdf);
      s.lobe = select(other, lobe_lanes<F>(Lobe::transmission), s.lobe);
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

  // The lobes' pieces, for the models that extend this one (materials/microfacet_material.hpp).
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
