#pragma once
// Antialiasing policies: where within (or around) a pixel a primary ray goes, as an offset in
// pixels from the pixel centre.

#include <cmath>

#include "glint/math/sampling.hpp"
#include "glint/policy/concepts.hpp"

namespace glint {

/// Every primary ray through the pixel centre: aliased edges, as in the report's figure 4a.
struct NoAntialiasing {
  static constexpr bool enabled = false;
  static Vec2 offset(Vec2, float) { return Vec2(0.0f); }
#if defined(GLINT_AVX2)
  static Vec2Lanes offset(Vec2Lanes, float) {
    return {broadcast(0.0f), broadcast(0.0f)};
  }
#endif
};

/// The report's antialiasing: a Gaussian perturbation with standard deviation sigma pixels.
struct GaussianAntialiasing {
  static constexpr bool enabled = true;
  static Vec2 offset(Vec2 u, float sigma) { return sigma * sample_standard_normal_pair(u); }
#if defined(GLINT_AVX2)
  static Vec2Lanes offset(Vec2Lanes u, float sigma) {
    const Vec2Lanes normal = sample_standard_normal_pair_lanes(u);
    return {sigma * normal.x, sigma * normal.y};
  }
#endif
};

/// Uniform over the pixel square (sigma unused).
struct BoxAntialiasing {
  static constexpr bool enabled = true;
  static Vec2 offset(Vec2 u, float) { return u - Vec2(0.5f); }
#if defined(GLINT_AVX2)
  static Vec2Lanes offset(Vec2Lanes u, float) {
    return {u.x - 0.5f, u.y - 0.5f};
  }
#endif
};

/// Tent filter of radius one pixel (sigma unused): the sum of two uniform offsets, sampled by
/// inverting its CDF per axis.
struct TentAntialiasing {
  static constexpr bool enabled = true;
  static float tent(float u) {
    return u < 0.5f ? std::sqrt(2.0f * u) - 1.0f : 1.0f - std::sqrt(2.0f - 2.0f * u);
  }
  static Vec2 offset(Vec2 u, float) { return {tent(u.x), tent(u.y)}; }
#if defined(GLINT_AVX2)
  static FloatLanes tent(FloatLanes u) {
    return select(u < 0.5f, sqrt_lanes(2.0f * u) - 1.0f,
                  1.0f - sqrt_lanes(max_lanes(broadcast(0.0f), 2.0f - 2.0f * u)));
  }
  static Vec2Lanes offset(Vec2Lanes u, float) {
    return {tent(u.x), tent(u.y)};
  }
#endif
};

static_assert(Antialiasing<NoAntialiasing> && Antialiasing<GaussianAntialiasing> &&
              Antialiasing<BoxAntialiasing> && Antialiasing<TentAntialiasing>);

}  // namespace glint
