#pragma once
// A rough surface as a distribution of mirror microfacets: the Trowbridge-Reitz (GGX) normal
// distribution with the Smith height-correlated masking-shadowing term (Heitz 2014,
// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs"), its visible normals
// sampled on a spherical cap (Dupuy and Benyoub 2023, "Sampling Visible GGX Normals with
// Spherical Caps"), and the reflectance of a conductor for the microfacets' Fresnel term.
//
// Directions are in the local frame of the macro-surface's normal on the side the light is on
// (z up); everything is written once over a Float type (math/wide.hpp), with glint's own sin and
// cos, so that a lane gives the same bits at every width.

#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The narrowest lobe modelled as microfacets: below this alpha the distribution's density
/// (1 / (pi alpha^2) at its peak) and the cancellations in its denominator leave single precision,
/// so such a surface reflects as the ideal mirror it nearly is (pbrt-v4 draws the same line).
inline constexpr float kSmoothestMicrofacetAlpha = 1e-3f;

/// A scene's roughness (in [0, 1]) as the distribution's alpha: its square, so that roughness
/// reads about linearly in the look of a highlight.
template <FloatType F>
inline F microfacet_alpha(F roughness) {
  return roughness * roughness;
}

/// Whether a lobe of this roughness is a microfacet lobe rather than the ideal one, lane by lane.
template <FloatType F>
inline MaskFor<F> is_microfacet_lobe(F roughness) {
  return microfacet_alpha(roughness) >= kSmoothestMicrofacetAlpha;
}

/// The isotropic Trowbridge-Reitz distribution of width `alpha` (> 0) over a Float's lanes.
template <FloatType F>
struct TrowbridgeReitz {
  using V3 = Vec3For<F>;
  F alpha;

  /// D(m): the density of microfacet normals m (unit, local) per unit solid angle and unit
  /// macro-surface area, so that the integral of D(m) m.z over the hemisphere is one. Written
  /// with m.x^2 + m.y^2 in place of 1 - m.z^2, which cancels for the narrow lobes.
  F normal_density(const V3& m) const {
    const F a2 = alpha * alpha;
    const F t = (m.x * m.x + m.y * m.y) + a2 * (m.z * m.z);
    return a2 / (kPi * (t * t));
  }

  /// Smith's Lambda(w) for a direction above the surface (w.z > 0).
  F lambda(const V3& w) const {
    const F z2 = w.z * w.z;
    return 0.5f * (sqrt(z2 + (alpha * alpha) * (w.x * w.x + w.y * w.y)) / abs(w.z) - 1.0f);
  }

  /// The fraction of the microfacets facing w that w sees (G1).
  F masking(const V3& w) const { return 1.0f / (1.0f + lambda(w)); }

  /// A microfacet normal drawn from the normals visible from wo (wo.z > 0), with density
  /// masking(wo) max(0, wo . m) normal_density(m) / wo.z per unit solid angle: wo is stretched
  /// to the distribution of alpha one, where the visible normals are uniform on a spherical cap
  /// around it, and the normal drawn there is unstretched.
  V3 sample_visible_normal(const V3& wo, const Vec2For<F>& u) const {
    const V3 stretched = normalize(V3{alpha * wo.x, alpha * wo.y, wo.z});
    const F z = (1.0f - u.y) * (1.0f + stretched.z) - stretched.z;
    const V3 cap = detail::around_z(u.x, sqrt(max(splat<F>(0.0f), 1.0f - z * z)), z);
    const V3 h = cap + stretched;
    return normalize(V3{alpha * h.x, alpha * h.y, max(splat<F>(0.0f), h.z)});
  }
};

/// A reflection by a TrowbridgeReitz mirror from wo to wi (both unit, local, z up), without
/// Fresnel: its half vector, f cos(wi) = D G2 / (4 wo.z) with the height-correlated
/// G2 = 1 / (1 + Lambda(wo) + Lambda(wi)), and the density with which
/// sample_visible_normal reflects wo to wi, G1(wo) D / (4 wo.z); `above` where both directions
/// are above the surface (elsewhere the values are unspecified: the lobe has none there).
template <FloatType F>
struct MicrofacetReflection {
  Vec3For<F> half;
  F f_cos;
  F pdf;
  MaskFor<F> above;
};

/// The reflection from wo to wi by `d`, given 1 + Lambda(wo) (`masking_o`, which a material
/// computes once per hit).
template <FloatType F>
inline MicrofacetReflection<F> microfacet_reflection(const TrowbridgeReitz<F>& d,
                                                     const Vec3For<F>& wo, F masking_o,
                                                     const Vec3For<F>& wi) {
  const Vec3For<F> half = normalize(wo + wi);
  const F density = d.normal_density(half);
  const F four_cos_o = 4.0f * wo.z;
  return {half, density / (four_cos_o * (masking_o + d.lambda(wi))),
          density / (four_cos_o * masking_o), wo.z > 0.0f && wi.z > 0.0f};
}

/// A refraction by a TrowbridgeReitz interface from wo (above, z > 0) to wi (below), without
/// Fresnel: the microfacet normal that refracts one into the other (the generalised half vector
/// of wo + eta wi, turned above the surface), f |cos(wi)| for radiance (a camera path's, which
/// goes through unscaled, render/bsdf.hpp's Transport), and the density with which
/// sample_visible_normal refracts wo to wi; `valid` where the facet has wo in front and wi
/// behind (elsewhere the values are unspecified). `eta` is the index on wi's side over wo's.
///
/// With the facets' density D(h) G1(wo) (wo.h) / wo.z and the change of variables from the
/// facet to the refracted direction, eta^2 |wi.h| / (wo.h + eta wi.h)^2, the density is their
/// product, and f |cos(wi)| is the density times G2 / G1 = (1 + Lambda(wo)) / (1 + Lambda(wo)
/// + Lambda(wi)) (Walter, Marschner, Li and Torrance 2007, "Microfacet Models for Refraction
/// through Rough Surfaces", with the radiance scaled as glint's refraction scales it).
template <FloatType F>
struct MicrofacetTransmission {
  Vec3For<F> half;
  F f_cos;
  F pdf;
  MaskFor<F> valid;
};

/// The refraction from wo to wi through `d` at relative index `eta`, given 1 + Lambda(wo).
template <FloatType F>
inline MicrofacetTransmission<F> microfacet_transmission(const TrowbridgeReitz<F>& d,
                                                         const Vec3For<F>& wo, F masking_o, F eta,
                                                         const Vec3For<F>& wi) {
  using V3 = Vec3For<F>;
  const V3 toward = normalize(wo + eta * wi);
  const V3 half = select(toward.z < 0.0f, -toward, toward);
  const F cos_o = dot(wo, half);
  const F cos_i = dot(wi, half);
  const F denominator = cos_o + eta * cos_i;
  const F jacobian = (eta * eta) * abs(cos_i) / (denominator * denominator);
  const F visible = d.normal_density(half) * cos_o / wo.z;
  const F pdf = visible * jacobian / masking_o;
  return {half, visible * jacobian / (masking_o + d.lambda(wi)), pdf,
          wo.z > 0.0f && wi.z < 0.0f && cos_o > 0.0f && cos_i < 0.0f};
}

namespace detail {
/// The unpolarised Fresnel reflectance of a conductor of complex relative index eta + i k for a
/// cosine `c` in [0, 1] on the incident side: the mean of the s and p reflectances in the closed
/// form of the complex Snell's law (as in Born and Wolf), one colour channel.
template <FloatType F>
inline F conductor_reflectance(F c, F eta, F k) {
  const F c2 = c * c;
  const F s2 = 1.0f - c2;
  const F t0 = eta * eta - k * k - s2;
  const F a2b2 = sqrt(max(splat<F>(0.0f), t0 * t0 + 4.0f * (eta * eta) * (k * k)));
  const F a = sqrt(max(splat<F>(0.0f), 0.5f * (a2b2 + t0)));
  const F t1 = a2b2 + c2;
  const F t2 = 2.0f * c * a;
  const F rs = (t1 - t2) / (t1 + t2);
  const F t3 = c2 * a2b2 + s2 * s2;
  const F t4 = t2 * s2;
  const F rp = rs * (t3 - t4) / (t3 + t4);
  return 0.5f * (rs + rp);
}
}  // namespace detail

/// The Fresnel reflectance of a conductor of complex relative index eta + i k, per colour
/// channel, at cosine `c` between the incident direction and the (micro)surface normal.
template <typename V3>
inline V3 conductor_reflectance(FloatOf<V3> c, const V3& eta, const V3& k) {
  return V3{detail::conductor_reflectance(c, eta.x, k.x),
            detail::conductor_reflectance(c, eta.y, k.y),
            detail::conductor_reflectance(c, eta.z, k.z)};
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
