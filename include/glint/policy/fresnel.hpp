#pragma once
// Fresnel policies for fully transparent spheres: the probability that light is reflected
// rather than refracted at the interface. Total internal reflection is geometry, not Fresnel:
// the renderer reflects when Snell's law has no solution whatever the policy.

#include <algorithm>
#include <cmath>

#include "glint/policy/concepts.hpp"

namespace glint {

/// The report before Fresnel (its figure 5a): fully transparent spheres always refract.
struct NoFresnel {
  static constexpr bool enabled = false;
  static float reflectance(float, float, float) { return 0.0f; }
};

/// Unpolarised reflectance from the full Fresnel equations for a dielectric.
struct ExactFresnel {
  static constexpr bool enabled = true;
  static float reflectance(float cos_incident, float eta_incident, float eta_transmitted) {
    cos_incident = std::clamp(cos_incident, 0.0f, 1.0f);
    const float sin2_incident = std::max(0.0f, 1.0f - cos_incident * cos_incident);
    const float eta = eta_incident / eta_transmitted;
    const float sin2_transmitted = eta * eta * sin2_incident;
    if (sin2_transmitted >= 1.0f) return 1.0f;
    const float cos_transmitted = std::sqrt(1.0f - sin2_transmitted);
    const float perpendicular = (eta_incident * cos_incident - eta_transmitted * cos_transmitted) /
                                (eta_incident * cos_incident + eta_transmitted * cos_transmitted);
    const float parallel = (eta_transmitted * cos_incident - eta_incident * cos_transmitted) /
                           (eta_transmitted * cos_incident + eta_incident * cos_transmitted);
    return 0.5f * (perpendicular * perpendicular + parallel * parallel);
  }
};

/// Schlick's approximation. The cosine must be taken on the lower-index side, otherwise the
/// approximation misses total internal reflection and is badly wrong inside glass.
struct SchlickFresnel {
  static constexpr bool enabled = true;
  static float reflectance(float cos_incident, float eta_incident, float eta_transmitted) {
    cos_incident = std::clamp(cos_incident, 0.0f, 1.0f);
    float r0 = (eta_incident - eta_transmitted) / (eta_incident + eta_transmitted);
    r0 *= r0;
    float cosine = cos_incident;
    if (eta_incident > eta_transmitted) {
      const float eta = eta_incident / eta_transmitted;
      const float sin2_transmitted = eta * eta * (1.0f - cos_incident * cos_incident);
      if (sin2_transmitted >= 1.0f) return 1.0f;
      cosine = std::sqrt(1.0f - sin2_transmitted);
    }
    const float m = 1.0f - cosine;
    const float m2 = m * m;
    return r0 + (1.0f - r0) * m2 * m2 * m;
  }
};

static_assert(Fresnel<NoFresnel> && Fresnel<ExactFresnel> && Fresnel<SchlickFresnel>);

}  // namespace glint
