#pragma once
// Antialiasing policies: where within (or around) a pixel a primary ray goes, as an offset in
// pixels from the pixel centre. Each is written once for every width (math/wide.hpp).
//
// The offsets' distribution is the pixel filter: a pixel's value is the mean radiance of the
// rays through its centre plus an offset of that density. So each policy also gives the
// density, for the light that reaches the film anywhere (a light path connected to the camera,
// splatted on every pixel whose filter covers the point it lands on), and the half-width of the
// square outside which the density is zero. A filter without an area (every ray through the
// centre) has no density: no splat can reach a pixel's centre exactly.

#include <cmath>

#include "glint/instruction_set.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/sampling.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Every primary ray through the pixel centre: aliased edges, as in the report's figure 4a.
struct NoAntialiasing {
  static constexpr bool enabled = false;
  template <typename V2>
  static V2 offset(const V2&, float) {
    using F = FloatOf<V2>;
    return V2{splat<F>(0.0f), splat<F>(0.0f)};
  }
  static float density(Vec2, float) { return 0.0f; }
  static float footprint(float) { return 0.0f; }
};

/// The report's antialiasing: a Gaussian perturbation with standard deviation sigma pixels.
struct GaussianAntialiasing {
  static constexpr bool enabled = true;
  template <typename V2>
  static V2 offset(const V2& u, float sigma) {
    const V2 normal = sample_standard_normal_pair(u);
    return V2{sigma * normal.x, sigma * normal.y};
  }
  /// The normal density of standard deviation sigma. Offsets are drawn with a radius of at most
  /// kLargestRadius sigma (sample_standard_normal_pair's from a float u), which leaves out 2^-24
  /// of the density's mass: the density is the truncated one's to that fraction.
  static float density(Vec2 offset, float sigma) {
    if (!(sigma > 0.0f)) return 0.0f;
    const float r2 = (offset.x * offset.x + offset.y * offset.y) / (sigma * sigma);
    if (!(r2 <= kLargestRadius * kLargestRadius)) return 0.0f;
    return exponential(-0.5f * r2) / (2.0f * kPi * sigma * sigma);
  }
  static float footprint(float sigma) { return sigma > 0.0f ? kLargestRadius * sigma : 0.0f; }
  /// sqrt(-2 ln 2^-24): the largest radius sample_standard_normal_pair gives, in sigmas.
  static constexpr float kLargestRadius = 5.7681515f;
};

/// Uniform over the pixel square (sigma unused).
struct BoxAntialiasing {
  static constexpr bool enabled = true;
  template <typename V2>
  static V2 offset(const V2& u, float) {
    return V2{u.x - 0.5f, u.y - 0.5f};
  }
  static float density(Vec2 offset, float) {
    return offset.x >= -0.5f && offset.x < 0.5f && offset.y >= -0.5f && offset.y < 0.5f ? 1.0f
                                                                                        : 0.0f;
  }
  static float footprint(float) { return 0.5f; }
};

/// Tent filter of radius one pixel (sigma unused): the sum of two uniform offsets, sampled by
/// inverting its CDF per axis.
struct TentAntialiasing {
  static constexpr bool enabled = true;
  template <FloatType F>
  static F tent(F u) {
    return select(u < 0.5f, sqrt(2.0f * u) - 1.0f,
                  1.0f - sqrt(max(splat<F>(0.0f), 2.0f - 2.0f * u)));
  }
  template <typename V2>
  static V2 offset(const V2& u, float) {
    return V2{tent(u.x), tent(u.y)};
  }
  static float density(Vec2 offset, float) {
    return std::fmax(0.0f, 1.0f - std::fabs(offset.x)) *
           std::fmax(0.0f, 1.0f - std::fabs(offset.y));
  }
  static float footprint(float) { return 1.0f; }
};

static_assert(Antialiasing<NoAntialiasing> && Antialiasing<GaussianAntialiasing> &&
              Antialiasing<BoxAntialiasing> && Antialiasing<TentAntialiasing>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
