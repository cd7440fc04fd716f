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
#if defined(GLINT_AVX2)
  static FloatLanes reflectance(FloatLanes, FloatLanes, FloatLanes) {
    return broadcast(0.0f);
  }
#endif
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
#if defined(GLINT_AVX2)
  static FloatLanes reflectance(FloatLanes cos_incident, FloatLanes eta_incident,
                                FloatLanes eta_transmitted) {
    cos_incident = min_lanes(max_lanes(cos_incident, broadcast(0.0f)), broadcast(1.0f));
    const FloatLanes sin2_incident = max_lanes(broadcast(0.0f), 1.0f - cos_incident * cos_incident);
    const FloatLanes eta = eta_incident / eta_transmitted;
    const FloatLanes sin2_transmitted = eta * eta * sin2_incident;
    const IntLanes total_internal = sin2_transmitted >= 1.0f;
    const FloatLanes cos_transmitted =
        sqrt_lanes(max_lanes(broadcast(0.0f), 1.0f - sin2_transmitted));
    const FloatLanes perpendicular =
        (eta_incident * cos_incident - eta_transmitted * cos_transmitted) /
        (eta_incident * cos_incident + eta_transmitted * cos_transmitted);
    const FloatLanes parallel = (eta_transmitted * cos_incident - eta_incident * cos_transmitted) /
                                (eta_transmitted * cos_incident + eta_incident * cos_transmitted);
    return select(total_internal, broadcast(1.0f),
                  0.5f * (perpendicular * perpendicular + parallel * parallel));
  }
#endif
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
#if defined(GLINT_AVX2)
  static FloatLanes reflectance(FloatLanes cos_incident, FloatLanes eta_incident,
                                FloatLanes eta_transmitted) {
    cos_incident = min_lanes(max_lanes(cos_incident, broadcast(0.0f)), broadcast(1.0f));
    FloatLanes r0 = (eta_incident - eta_transmitted) / (eta_incident + eta_transmitted);
    r0 *= r0;
    const IntLanes denser_side = eta_incident > eta_transmitted;
    const FloatLanes eta = eta_incident / eta_transmitted;
    const FloatLanes sin2_transmitted = eta * eta * (1.0f - cos_incident * cos_incident);
    const IntLanes total_internal = denser_side & (sin2_transmitted >= 1.0f);
    const FloatLanes cosine = select(
        denser_side, sqrt_lanes(max_lanes(broadcast(0.0f), 1.0f - sin2_transmitted)), cos_incident);
    const FloatLanes m = 1.0f - cosine;
    const FloatLanes m2 = m * m;
    return select(total_internal, broadcast(1.0f), r0 + (1.0f - r0) * m2 * m2 * m);
  }
#endif
};

static_assert(Fresnel<NoFresnel> && Fresnel<ExactFresnel> && Fresnel<SchlickFresnel>);

}  // namespace glint
