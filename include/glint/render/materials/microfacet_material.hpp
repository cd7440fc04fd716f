#pragma once
// The report's material with a mirror lobe that may be rough and a metal's: a Bsdf
// (render/bsdf.hpp) named by MicrofacetMaterialModel (policy/material_model.hpp). A sphere
// without a mirror finish (Material::has_mirror_finish) is the report's material to the bit.

#include "glint/config.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/bsdf.hpp"
#include "glint/render/materials/microfacet.hpp"
#include "glint/render/materials/report_material.hpp"
#include "glint/render/scattering.hpp"
#include "glint/scene/surface_lanes.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The report's lobes (diffuse, mirror, transmission, mixed by the sphere's coefficients), with
/// the mirror lobe finished by the sphere's roughness and metal: a Trowbridge-Reitz microfacet
/// lobe of alpha roughness^2 (a density over the directions of its side, joined and sampled
/// towards lights as the diffuse lobe is) where alpha reaches kSmoothestMicrofacetAlpha, the ideal
/// mirror below, each reflecting mirror_color times the metal's Fresnel reflectance (one without
/// a metal). The metal's index is relative to the medium on the side the light arrives from.
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
        k_(splat_vector<V3>(Color(0.0f))) {
    if (!any(finished_)) return;
    glossy_ = finished_ && is_microfacet_lobe(s_.mirror_roughness);
    distribution_.alpha = select(glossy_, microfacet_alpha(s_.mirror_roughness), splat<F>(1.0f));
    frame_ = BasicFrame<V3>::around(at_.facing_normal);
    const V3 away = -incoming_;
    wo_ = V3{dot(away, frame_.tangent), dot(away, frame_.bitangent), at_.cos_incident};
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

  /// The material at a vertex of a stored subpath (RecordableBsdf): the report's diffuse lobe
  /// and the rough mirror, the lobes with a value and a density at given directions.
  /// Conductor reflection is the same in both transport modes.
  struct Record {
    typename Ideal::Record diffuse{};
    bool glossy = false;
    Color tint{0.0f};         ///< mirror coefficient x mirror_color
    float glossy_choice = 0;  ///< the probability with which sample() chooses the mirror lobe
    float alpha = 1.0f;
    bool metal = false;
    Color eta{1.0f};
    Color k{0.0f};

    bool has_density() const { return diffuse.has_density() || glossy; }
    Color f(const Vec3& facing, const Vec3& wo, const Vec3& wi) const {
      Color value = diffuse.f(facing, wo, wi);
      if (glossy) {
        const Local l = local(facing, wo, wi);
        if (l.reflection.above) value += fresnel(l) * (l.reflection.f_cos / l.wi.z);
      }
      return value;
    }
    float pdf(const Vec3& facing, const Vec3& wo, const Vec3& wi) const {
      float density = diffuse.pdf(facing, wo, wi);
      if (glossy) {
        const Local l = local(facing, wo, wi);
        if (l.reflection.above) density += glossy_choice * l.reflection.pdf;
      }
      return density;
    }

   private:
    struct Local {
      Vec3 wo, wi;
      MicrofacetReflection<float> reflection;
    };
    Local local(const Vec3& facing, const Vec3& wo, const Vec3& wi) const {
      const Frame frame = Frame::around(facing);
      const Vec3 o{glm::dot(wo, frame.tangent), glm::dot(wo, frame.bitangent),
                   glm::dot(wo, facing)};
      const Vec3 i{glm::dot(wi, frame.tangent), glm::dot(wi, frame.bitangent),
                   glm::dot(wi, facing)};
      const TrowbridgeReitz<float> d{alpha};
      return {o, i, microfacet_reflection(d, o, 1.0f + d.lambda(o), i)};
    }
    /// The mirror's tint times the metal's reflectance for the reflection `l`.
    Color fresnel(const Local& l) const {
      return metal ? tint * conductor_reflectance(glm::dot(l.wo, l.reflection.half), eta, k) : tint;
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
    return r;
  }

  using Ideal::scatters;
  /// Whether a lobe with a density is present: the diffuse or the rough mirror.
  M has_density() const { return Ideal::has_density() || glossy_; }

  /// Chooses one lobe per lane with probability coefficient / total (one next_1d) and samples
  /// it as the report's material does (a diffuse direction: one next_2d; Fresnel at glass: one
  /// next_1d); a rough mirror draws its microfacet normal with one next_2d. Requires scatters()
  /// in `lanes`.
  template <Transport mode = Transport::radiance, typename Draws>
  BasicScatterSample<F> sample(Draws& draws, M lanes = mask_of<M>(true)) const {
    BasicScatterSample<F> s = Ideal::template sample<mode>(draws, lanes);
    if (!any(lanes && finished_)) return s;
    const M mirror = lanes && finished_ && s.lobe == lobe_lanes<F>(Lobe::mirror);
    const M smooth_metal = mirror && metal_ && !glossy_;
    if (any(smooth_metal))
      s.tint =
          select(smooth_metal, s.tint * conductor_reflectance(at_.cos_incident, eta_, k_), s.tint);
    const M rough = mirror && glossy_;
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
      s.pdf = select(above, Ideal::pdf(s.direction) + (s_.mirror / total_) * r.pdf, s.pdf);
    }
    // A diffuse direction gets the rough mirror's density there too.
    const M diffuse = lanes && !s.delta && glossy_ && !rough;
    if (any(diffuse)) s.pdf = select(diffuse, pdf(s.direction), s.pdf);
    return s;
  }

  /// f |cos| for light leaving in `direction`: the diffuse lobe and the rough mirror (the ideal
  /// lobes have no value at a given direction). The same in both transport modes.
  template <Transport mode = Transport::radiance>
  V3 evaluate(const V3& direction) const {
    V3 value = Ideal::template evaluate<mode>(direction);
    if (!any(glossy_)) return value;
    const MicrofacetReflection<F> r = reflection(direction);
    const M above = glossy_ && r.above;
    if (!any(above)) return value;
    V3 tint = s_.mirror * s_.mirror_color;
    if (any(metal_ && above))
      tint = select(metal_, tint * conductor_reflectance(dot(wo_, r.half), eta_, k_), tint);
    return select(above, value + tint * r.f_cos, value);
  }

  /// Density of sample() producing `direction` through the lobes with a density (requires
  /// scatters()).
  F pdf(const V3& direction) const {
    F density = Ideal::pdf(direction);
    if (!any(glossy_)) return density;
    const MicrofacetReflection<F> r = reflection(direction);
    const M above = glossy_ && r.above;
    if (!any(above)) return density;
    return select(above, density + (s_.mirror / total_) * r.pdf, density);
  }

 private:
  /// The rough mirror's reflection from wo_ to world `direction`.
  MicrofacetReflection<F> reflection(const V3& direction) const {
    const V3 wi{dot(direction, frame_.tangent), dot(direction, frame_.bitangent),
                dot(direction, frame_.normal)};
    return microfacet_reflection(distribution_, wo_, masking_o_, wi);
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
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
