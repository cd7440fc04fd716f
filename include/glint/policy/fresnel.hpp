#pragma once
// Fresnel policies for fully transparent spheres: the probability that light is reflected
// rather than refracted at the interface. Total internal reflection is geometry, not Fresnel:
// the renderer reflects when Snell's law has no solution whatever the policy. Each is written
// once for every width (math/wide.hpp).

#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The report before Fresnel (its figure 5a): fully transparent spheres always refract.
struct NoFresnel {
  static constexpr bool enabled = false;
  template <FloatType F>
  static F reflectance(F, F, F) {
    return splat<F>(0.0f);
  }
};

/// Unpolarised reflectance from the full Fresnel equations for a dielectric.
struct ExactFresnel {
  static constexpr bool enabled = true;
  template <FloatType F>
  static F reflectance(F cos_incident, F eta_incident, F eta_transmitted) {
    cos_incident = min(max(cos_incident, splat<F>(0.0f)), splat<F>(1.0f));
    const F sin2_incident = max(splat<F>(0.0f), 1.0f - cos_incident * cos_incident);
    const F eta = eta_incident / eta_transmitted;
    const F sin2_transmitted = eta * eta * sin2_incident;
    const MaskFor<F> total_internal = sin2_transmitted >= 1.0f;
    const F cos_transmitted = sqrt(max(splat<F>(0.0f), 1.0f - sin2_transmitted));
    const F perpendicular = (eta_incident * cos_incident - eta_transmitted * cos_transmitted) /
                            (eta_incident * cos_incident + eta_transmitted * cos_transmitted);
    const F parallel = (eta_transmitted * cos_incident - eta_incident * cos_transmitted) /
                       (eta_transmitted * cos_incident + eta_incident * cos_transmitted);
    return select(total_internal, splat<F>(1.0f),
                  0.5f * (perpendicular * perpendicular + parallel * parallel));
  }
};

/// Schlick's approximation. The cosine must be taken on the lower-index side, otherwise the
/// approximation misses total internal reflection and is badly wrong inside glass.
struct SchlickFresnel {
  static constexpr bool enabled = true;
  template <FloatType F>
  static F reflectance(F cos_incident, F eta_incident, F eta_transmitted) {
    cos_incident = min(max(cos_incident, splat<F>(0.0f)), splat<F>(1.0f));
    F r0 = (eta_incident - eta_transmitted) / (eta_incident + eta_transmitted);
    r0 *= r0;
    const MaskFor<F> denser_side = eta_incident > eta_transmitted;
    const F eta = eta_incident / eta_transmitted;
    const F sin2_transmitted = eta * eta * (1.0f - cos_incident * cos_incident);
    const MaskFor<F> total_internal = denser_side && sin2_transmitted >= 1.0f;
    const F cosine =
        select(denser_side, sqrt(max(splat<F>(0.0f), 1.0f - sin2_transmitted)), cos_incident);
    const F m = 1.0f - cosine;
    const F m2 = m * m;
    return select(total_internal, splat<F>(1.0f), r0 + (1.0f - r0) * m2 * m2 * m);
  }
};

static_assert(Fresnel<NoFresnel> && Fresnel<ExactFresnel> && Fresnel<SchlickFresnel>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
