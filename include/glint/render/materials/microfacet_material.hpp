#pragma once
// The report's material with a mirror lobe that may be rough and a metal's, and a transparent
// lobe whose interface may be rough: a Bsdf (render/bsdf.hpp) named by MicrofacetMaterialModel
// (policy/material_model.hpp). A sphere with neither (Material::has_mirror_finish,
// Material::has_rough_interface) is the report's material to the bit.

#include "glint/config.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/bsdf.hpp"
#include "glint/render/materials/microfacet.hpp"
#include "glint/render/materials/report_material.hpp"
#include "glint/render/materials/rough_interface.hpp"
#include "glint/render/scattering.hpp"
#include "glint/scene/surface_lanes.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The report's lobes (diffuse, mirror, transmission, mixed by the sphere's coefficients), with
/// the mirror lobe finished by the sphere's roughness and metal: a Trowbridge-Reitz microfacet
/// lobe of alpha roughness^2 (a density over the directions of its side, joined and sampled
/// towards lights as the diffuse lobe is) where alpha reaches kSmoothestMicrofacetAlpha, the ideal
/// mirror below, each reflecting mirror_color times the metal's Fresnel reflectance (one without
/// a metal). The metal's index is relative to the medium on the side the light arrives from.
/// The transparent lobe's interface is likewise a RoughInterface of alpha transparent_roughness^2
/// where that reaches kSmoothestMicrofacetAlpha (and the indices on its sides differ), tinted by
/// transparent_color: a density on both sides of the surface, so light is sampled and joined
/// through it too.
///
/// A sampled direction chooses its lobe as the report's material does (probability coefficient /
/// total) and carries that lobe's weight; its density is that of every lobe with a density
/// together, as pdf() gives it, so that the estimators' MIS weights see one density per
/// direction whichever lobe drew it.
template <typename C, typename F>
class MicrofacetMaterial : private ReportMaterial<C, F> {
  using Ideal = ReportMaterial<C, F>;
  using Ideal::at_;
  using Ideal::incoming_;
  using Ideal::s_;
  using Ideal::total_;

 public:
  using V3 = Vec3For<F>;
  using M = MaskFor<F>;

  /// The material at `interaction` (its lanes of `lanes`), reached along `incoming`.
  MicrofacetMaterial(const BasicSurfaceInteraction<F>& interaction, const V3& incoming,
                     M lanes = mask_of<M>(true))
      : Ideal(interaction, incoming, lanes),
        finished_(lanes && s_.mirror_finish),
        glossy_(mask_of<M>(false)),
        metal_(mask_of<M>(false)),
        distribution_{splat<F>(1.0f)},
        masking_o_(splat<F>(1.0f)),
        frame_{},
        wo_(splat_vector<V3>(Color(0.0f))),
        eta_(splat_vector<V3>(Color(1.0f))),
        k_(splat_vector<V3>(Color(0.0f))),
        rough_interface_(lanes && is_rough_interface(s_.transparent, s_.transparent_roughness,
                                                     s_.ior, s_.ior_outside)),
        interface_{} {
    if (!any(finished_ || rough_interface_)) return;
    frame_ = BasicFrame<V3>::around(at_.facing_normal);
    const V3 away = -incoming_;
    wo_ = V3{dot(away, frame_.tangent), dot(away, frame_.bitangent), at_.cos_incident};
    if (any(rough_interface_)) {
      const F one = splat<F>(1.0f);
      interface_ = Interface::seen_from(
          wo_, select(rough_interface_, microfacet_alpha(s_.transparent_roughness), one),
          select(rough_interface_, select(at_.from_inside, s_.ior, s_.ior_outside), one),
          select(rough_interface_, select(at_.from_inside, s_.ior_outside, s_.ior), one),
          s_.fully_transparent);
    }
    if (!any(finished_)) return;
    glossy_ = finished_ && is_microfacet_lobe(s_.mirror_roughness);
    distribution_.alpha = select(glossy_, microfacet_alpha(s_.mirror_roughness), splat<F>(1.0f));
    // 1 + Lambda(wo), which every value, density and weight of the lobe at this hit divides by.
    masking_o_ = select(glossy_, 1.0f + distribution_.lambda(wo_), splat<F>(1.0f));
    metal_ =
        finished_ && (s_.metal_eta.x != 0.0f || s_.metal_eta.y != 0.0f || s_.metal_eta.z != 0.0f ||
                      s_.metal_k.x != 0.0f || s_.metal_k.y != 0.0f || s_.metal_k.z != 0.0f);
    if (any(metal_)) {
      const F outside = 1.0f / select(at_.from_inside, s_.ior, s_.ior_outside);
      eta_ = select(metal_, s_.metal_eta * outside, eta_);
      k_ = select(metal_, s_.metal_k * outside, k_);
    }
  }

  /// The material at a vertex of a stored subpath (RecordableBsdf): the report's diffuse lobe,
  /// the rough mirror and the rough interface, the lobes with a value and a density at given
  /// directions. Conductor reflection is the same in both transport modes; refraction through
  /// the rough interface is scaled for importance as the ideal interface's is.
  struct Record {
    typename Ideal::Record diffuse{};
    bool glossy = false;
    Color tint{0.0f};         ///< mirror coefficient x mirror_color
    float glossy_choice = 0;  ///< the probability with which sample() chooses the mirror lobe
    float alpha = 1.0f;
    bool metal = false;
    Color eta{1.0f};
    Color k{0.0f};
    bool rough_interface = false;
    bool importance = false;     ///< the subpath carries importance (a light subpath)
    bool by_fresnel = false;     ///< the interface's facets choose by Fresnel
    Color interface_tint{0.0f};  ///< transparent coefficient x transparent_color
    float interface_choice = 0;  ///< the probability with which sample() chooses the interface
    float interface_alpha = 1.0f;
    float eta_facing = 1.0f;  ///< the index on the side of `facing`
    float eta_behind = 1.0f;  ///< the index on the other side

    bool has_density() const { return diffuse.has_density() || glossy || rough_interface; }
    bool transmits_with_density() const { return rough_interface; }
    Color f(const Vec3& facing, const Vec3& wo, const Vec3& wi) const {
      const Vec3 side = side_of(facing, wo);
      Color value = diffuse.f(side, wo, wi);
      if (glossy || rough_interface) {
        const Local l = local(side, wo, wi);
        if (glossy) {
          const MicrofacetReflection<float> r = reflection(l);
          if (r.above) value += fresnel(l, r) * (r.f_cos / l.wi.z);
        }
        if (rough_interface) {
          const Interface at = interface_seen_from(facing, side, l);
          const typename Interface::Scatter scatter = at.scatter(l.wo, l.wi);
          if (scatter.valid) {
            const float adjoint = importance && scatter.transmits ? at.adjoint_scale() : 1.0f;
            value += interface_tint * (scatter.f_cos * adjoint / std::fabs(l.wi.z));
          }
        }
      }
      return value;
    }
    float pdf(const Vec3& facing, const Vec3& wo, const Vec3& wi) const {
      const Vec3 side = side_of(facing, wo);
      float density = diffuse.pdf(side, wo, wi);
      if (glossy || rough_interface) {
        const Local l = local(side, wo, wi);
        if (glossy) {
          const MicrofacetReflection<float> r = reflection(l);
          if (r.above) density += glossy_choice * r.pdf;
        }
        if (rough_interface) {
          const typename Interface::Scatter scatter =
              interface_seen_from(facing, side, l).scatter(l.wo, l.wi);
          if (scatter.valid) density += interface_choice * scatter.pdf;
        }
      }
      return density;
    }

   private:
    using Interface = RoughInterface<typename C::fresnel, float>;
    struct Local {
      Vec3 wo, wi;
    };
    /// The normal on wo's side: the vertex's own, but for a density asked through the rough
    /// interface the other way round (from the side the subpath left towards).
    Vec3 side_of(const Vec3& facing, const Vec3& wo) const {
      return rough_interface && glm::dot(wo, facing) < 0.0f ? -facing : facing;
    }
    static Local local(const Vec3& side, const Vec3& wo, const Vec3& wi) {
      const Frame frame = Frame::around(side);
      return {Vec3{glm::dot(wo, frame.tangent), glm::dot(wo, frame.bitangent), glm::dot(wo, side)},
              Vec3{glm::dot(wi, frame.tangent), glm::dot(wi, frame.bitangent), glm::dot(wi, side)}};
    }
    MicrofacetReflection<float> reflection(const Local& l) const {
      const TrowbridgeReitz<float> d{alpha};
      return microfacet_reflection(d, l.wo, 1.0f + d.lambda(l.wo), l.wi);
    }
    Interface interface_seen_from(const Vec3& facing, const Vec3& side, const Local& l) const {
      const bool flipped = side != facing;
      return Interface::seen_from(l.wo, interface_alpha, flipped ? eta_behind : eta_facing,
                                  flipped ? eta_facing : eta_behind, by_fresnel);
    }
    /// The mirror's tint times the metal's reflectance for the reflection `r`.
    Color fresnel(const Local& l, const MicrofacetReflection<float>& r) const {
      return metal ? tint * conductor_reflectance(glm::dot(l.wo, r.half), eta, k) : tint;
    }
  };
  template <Transport mode>
  Record record() const requires(kLanesOf<F> == 1) {
    Record r;
    r.diffuse = Ideal::template record<mode>();
    r.glossy = glossy_;
    if (glossy_) {
      r.tint = s_.mirror * s_.mirror_color;
      r.glossy_choice = s_.mirror / total_;
      r.alpha = distribution_.alpha;
      r.metal = metal_;
      r.eta = eta_;
      r.k = k_;
    }
    r.rough_interface = rough_interface_;
    if (rough_interface_) {
      r.importance = mode == Transport::importance;
      r.by_fresnel = interface_.by_fresnel;
      r.interface_tint = s_.transparent * s_.transparent_color;
      r.interface_choice = s_.transparent / total_;
      r.interface_alpha = interface_.distribution.alpha;
      r.eta_facing = interface_.eta_o;
      r.eta_behind = interface_.eta_t;
    }
    return r;
  }

  using Ideal::scatters;
  /// Whether a lobe with a density is present: the diffuse, the rough mirror or the rough
  /// interface.
  M has_density() const { return Ideal::has_density() || glossy_ || rough_interface_; }
  /// Whether the rough interface is present: a density on both sides of the surface.
  M transmits_with_density() const { return rough_interface_; }
  static bool transmits_with_density_at(const SurfaceProperties& surface) {
    const Material& m = surface.material;
    return is_rough_interface(m.transparent, m.transparent_roughness, m.ior, surface.ior_outside);
  }

  /// Chooses one lobe per lane with probability coefficient / total (one next_1d) and samples
  /// it as the report's material does (a diffuse direction: one next_2d; Fresnel at smooth glass:
  /// one next_1d); a rough mirror draws its microfacet normal with one next_2d, a rough interface
  /// its facet with one next_2d and then, where its facets choose by Fresnel, one next_1d.
  /// Requires scatters() in `lanes`.
  template <Transport mode = Transport::radiance, typename Draws>
  BasicScatterSample<F> sample(Draws& draws, M lanes = mask_of<M>(true)) const {
    BasicScatterSample<F> s = Ideal::template sample_lobes<mode>(draws, lanes, !rough_interface_);
    if (!any(lanes && (finished_ || rough_interface_))) return s;
    M rough = mask_of<M>(false);
    if (any(lanes && finished_)) {
      const M mirror = lanes && finished_ && s.lobe == lobe_lanes<F>(Lobe::mirror);
      const M smooth_metal = mirror && metal_ && !glossy_;
      if (any(smooth_metal))
        s.tint = select(smooth_metal, s.tint * conductor_reflectance(at_.cos_incident, eta_, k_),
                        s.tint);
      rough = mirror && glossy_;
      if (any(rough)) {
        const Vec2For<F> u = next_2d(draws, rough);
        const V3 half = distribution_.sample_visible_normal(wo_, u);
        const F cos_half = dot(wo_, half);
        const V3 wi = (2.0f * cos_half) * half - wo_;
        const MicrofacetReflection<F> r = microfacet_reflection(distribution_, wo_, masking_o_, wi);
        // (A ray that grazes the sphere, wo.z = 0, sees no microfacet: it carries nothing on.)
        const M above = rough && r.above;
        V3 tint = s_.mirror_color;
        if (any(metal_ && rough))
          tint = select(metal_, tint * conductor_reflectance(cos_half, eta_, k_), tint);
        // f cos / pdf = F G2(wo, wi) / G1(wo).
        const F weight = masking_o_ / (masking_o_ + distribution_.lambda(wi));
        s.direction = select(rough, frame_.to_world(wi), s.direction);
        // A normal drawn for wo may reflect it below the surface: no light goes that way, and
        // the lane carries nothing on (as a delta, so that no density is read for it).
        s.tint = select(rough, select(above, tint, splat_vector<V3>(Color(0.0f))), s.tint);
        s.factor = select(rough, select(above, total_ * weight, splat<F>(0.0f)), s.factor);
        s.delta = select(rough, !above, s.delta);
        // The density of every lobe that has one, as pdf() finds it.
        F density = Ideal::pdf(s.direction) + (s_.mirror / total_) * r.pdf;
        if (any(rough_interface_)) density = density + interface_density(s.direction);
        s.pdf = select(above, density, s.pdf);
      }
    }
    const M through = lanes && rough_interface_ && s.lobe == lobe_lanes<F>(Lobe::transmission);
    if (any(through)) {
      const Vec2For<F> u = next_2d(draws, through);
      F u_choice = splat<F>(0.5f);  // where the facet's choice is certain
      if constexpr (C::fresnel::enabled) {
        const M choosing = through && interface_.by_fresnel;
        if (any(choosing)) u_choice = select(choosing, next_1d(draws, choosing), u_choice);
      }
      const typename Interface::Sample t = interface_.sample(wo_, u, u_choice);
      const M valid = through && t.weight > 0.0f;
      F factor = total_ * t.weight;
      if constexpr (mode == Transport::importance)
        factor = select(t.transmits, factor * interface_.adjoint_scale(), factor);
      s.direction = select(through, frame_.to_world(t.wi), s.direction);
      // As at a rough mirror, a facet that sends the light to the wrong side ends the path.
      s.tint = select(through, select(valid, s_.transparent_color, splat_vector<V3>(Color(0.0f))),
                      s.tint);
      s.factor = select(through, select(valid, factor, splat<F>(0.0f)), s.factor);
      s.delta = select(through, !valid, s.delta);
    }
    // The other directions with a density get every lobe's density there.
    const M others = lanes && !s.delta && (glossy_ || rough_interface_) && !rough;
    if (any(others)) s.pdf = select(others, pdf(s.direction), s.pdf);
    return s;
  }

  /// f |cos| for light leaving in `direction`: the diffuse lobe, the rough mirror and the rough
  /// interface (the ideal lobes have no value at a given direction). The mirrors are the same in
  /// both transport modes; refraction through the rough interface is scaled for importance.
  template <Transport mode = Transport::radiance>
  V3 evaluate(const V3& direction) const {
    V3 value = Ideal::template evaluate<mode>(direction);
    if (any(glossy_)) {
      const MicrofacetReflection<F> r = reflection(direction);
      const M above = glossy_ && r.above;
      if (any(above)) {
        V3 tint = s_.mirror * s_.mirror_color;
        if (any(metal_ && above))
          tint = select(metal_, tint * conductor_reflectance(dot(wo_, r.half), eta_, k_), tint);
        value = select(above, value + tint * r.f_cos, value);
      }
    }
    if (any(rough_interface_)) {
      const typename Interface::Scatter scatter = interface_.scatter(wo_, local(direction));
      const M through = rough_interface_ && scatter.valid;
      if (any(through)) {
        F f_cos = scatter.f_cos;
        if constexpr (mode == Transport::importance)
          f_cos = select(scatter.transmits, f_cos * interface_.adjoint_scale(), f_cos);
        value = select(through, value + (s_.transparent * s_.transparent_color) * f_cos, value);
      }
    }
    return value;
  }

  /// Density of sample() producing `direction` through the lobes with a density (requires
  /// scatters()).
  F pdf(const V3& direction) const {
    F density = Ideal::pdf(direction);
    if (any(glossy_)) {
      const MicrofacetReflection<F> r = reflection(direction);
      const M above = glossy_ && r.above;
      if (any(above)) density = select(above, density + (s_.mirror / total_) * r.pdf, density);
    }
    if (any(rough_interface_)) density = density + interface_density(direction);
    return density;
  }

 private:
  using Interface = RoughInterface<typename C::fresnel, F>;

  /// World `direction` in frame_.
  V3 local(const V3& direction) const {
    return V3{dot(direction, frame_.tangent), dot(direction, frame_.bitangent),
              dot(direction, frame_.normal)};
  }

  /// The rough mirror's reflection from wo_ to world `direction`.
  MicrofacetReflection<F> reflection(const V3& direction) const {
    return microfacet_reflection(distribution_, wo_, masking_o_, local(direction));
  }

  /// The rough interface's share of pdf() (zero where there is none).
  F interface_density(const V3& direction) const {
    const typename Interface::Scatter scatter = interface_.scatter(wo_, local(direction));
    return select(rough_interface_ && scatter.valid, (s_.transparent / total_) * scatter.pdf,
                  splat<F>(0.0f));
  }

  M finished_;  // a mirror lobe with a finish: rough, or a metal's
  M glossy_;    // the mirror lobe is a microfacet lobe
  M metal_;
  TrowbridgeReitz<F> distribution_;
  F masking_o_;  // 1 + Lambda(wo) (1 where not glossy)
  BasicFrame<V3> frame_;
  V3 wo_;  // the reversed arrival direction in frame_ (set where finished_)
  V3 eta_;
  V3 k_;
  M rough_interface_;
  Interface interface_;  // set where rough_interface_
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
