#pragma once
// A rough interface between two dielectrics (frosted glass): Trowbridge-Reitz microfacets
// (render/materials/microfacet.hpp), each of which reflects or refracts as the ideal interface
// does, with the same choice between the two: Fresnel's where the report applies it (fully
// transparent spheres, under a Fresnel policy), refraction otherwise unless the facet totally
// reflects. Local directions are in the frame of the macro-surface's normal on the side the light
// arrives from (wo.z > 0); written once over a Float type, so a lane gives the same bits at every
// width.

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/render/materials/microfacet.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Whether a transparent lobe (coefficient `transparent`, roughness `roughness`) between
/// indices `ior` and `ior_outside` is a rough interface, lane by lane: a microfacet lobe with
/// light bent through it. An interface between equal indices bends nothing, whatever its
/// facets: light goes straight through, as the ideal interface lets it.
template <FloatType F>
inline MaskFor<F> is_rough_interface(F transparent, F roughness, F ior, F ior_outside) {
  return transparent > 0.0f && is_microfacet_lobe(roughness) && ior != ior_outside;
}

/// A rough interface seen from the direction `wo` light leaves towards, under Fresnel policy
/// `Fresnel`, over a Float's lanes.
template <Fresnel FresnelPolicy, FloatType F>
struct RoughInterface {
  using V3 = Vec3For<F>;
  using M = MaskFor<F>;

  TrowbridgeReitz<F> distribution;
  F masking_o;   ///< 1 + Lambda(wo)
  F eta_o;       ///< the index on wo's side
  F eta_t;       ///< the index on the other side
  M by_fresnel;  ///< lanes whose facets choose by Fresnel (else: refraction unless total)

  /// The interface of width `alpha` for local `wo` (wo.z > 0).
  static RoughInterface seen_from(const V3& wo, F alpha, F eta_o, F eta_t, M by_fresnel) {
    const TrowbridgeReitz<F> d{alpha};
    return {d, 1.0f + d.lambda(wo), eta_o, eta_t, by_fresnel};
  }

  /// The probability that a facet at cosine `c` with wo reflects the light rather than
  /// refracting it.
  F reflectance(F c) const {
    const F eta = eta_o / eta_t;
    const M total_internal = (eta * eta) * (1.0f - c * c) >= 1.0f;
    F reflected = select(total_internal, splat<F>(1.0f), splat<F>(0.0f));
    if constexpr (FresnelPolicy::enabled)
      reflected = select(by_fresnel, FresnelPolicy::reflectance(c, eta_o, eta_t), reflected);
    return reflected;
  }

  /// The factor by which a light path's importance (Transport::importance) refracted from wo's
  /// side differs from radiance: (eta_o / eta_t)^2, as at the ideal interface.
  F adjoint_scale() const {
    const F ratio = eta_o / eta_t;
    return ratio * ratio;
  }

  /// f |cos(wi)| for radiance and the density of sample() for local `wi`; `valid` where wi is
  /// reached by some facet (the values are zero elsewhere), `transmits` where wi is below.
  struct Scatter {
    F f_cos;
    F pdf;
    M valid;
    M transmits;
  };
  Scatter scatter(const V3& wo, const V3& wi) const {
    const M transmits = wi.z < 0.0f;
    // Each branch only where some lane takes it: a lane's values are its own branch's.
    if (!any(transmits)) return reflected(wo, wi);
    if (all(transmits)) return transmitted(wo, wi);
    const Scatter r = reflected(wo, wi);
    const Scatter t = transmitted(wo, wi);
    return {select(transmits, t.f_cos, r.f_cos), select(transmits, t.pdf, r.pdf),
            select(transmits, t.valid, r.valid), transmits};
  }

  /// scatter() for directions above the surface: reflection by a facet.
  Scatter reflected(const V3& wo, const V3& wi) const {
    const MicrofacetReflection<F> r = microfacet_reflection(distribution, wo, masking_o, wi);
    const F share = reflectance(dot(wo, r.half));
    const F zero = splat<F>(0.0f);
    return {select(r.above, share * r.f_cos, zero), select(r.above, share * r.pdf, zero),
            r.above && share > 0.0f, mask_of<M>(false)};
  }

  /// scatter() for directions below the surface: refraction through a facet.
  Scatter transmitted(const V3& wo, const V3& wi) const {
    const MicrofacetTransmission<F> t =
        microfacet_transmission(distribution, wo, masking_o, eta_t / eta_o, wi);
    const F share = 1.0f - reflectance(dot(wo, t.half));
    const F zero = splat<F>(0.0f);
    return {select(t.valid, share * t.f_cos, zero), select(t.valid, share * t.pdf, zero),
            t.valid && share > 0.0f, mask_of<M>(true)};
  }

  /// A direction for local `wo`: a facet drawn among those wo sees (from `u`), then its
  /// reflection or refraction chosen with the facet's reflectance (from `u_choice` where
  /// `by_fresnel`; the choice is certain elsewhere). `weight` is f |cos(wi)| / pdf for radiance:
  /// G2 / G1, the same for both branches; zero where the facet sends the light to the wrong side
  /// of the macro-surface, which carries nothing on.
  struct Sample {
    V3 wi;
    F weight;
    M transmits;
  };
  Sample sample(const V3& wo, const Vec2For<F>& u, F u_choice) const {
    const V3 m = distribution.sample_visible_normal(wo, u);
    const F c = dot(wo, m);
    const M reflects = u_choice < reflectance(c);
    const F eta = eta_o / eta_t;
    const F cos_t = sqrt(max(splat<F>(0.0f), 1.0f - (eta * eta) * (1.0f - c * c)));
    const V3 wi = select(reflects, (2.0f * c) * m - wo, (eta * c - cos_t) * m - eta * wo);
    const M valid = select(reflects, wi.z > 0.0f, wi.z < 0.0f);
    const F weight = masking_o / (masking_o + distribution.lambda(wi));
    return {wi, select(valid, weight, splat<F>(0.0f)), !reflects};
  }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
