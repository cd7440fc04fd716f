#pragma once
// Antialiasing policies: where within (or around) a pixel a primary ray goes, as an offset in
// pixels from the pixel centre. Each is written once for every width (math/wide.hpp).

#include "glint/instruction_set.hpp"
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
};

/// The report's antialiasing: a Gaussian perturbation with standard deviation sigma pixels.
struct GaussianAntialiasing {
  static constexpr bool enabled = true;
  template <typename V2>
  static V2 offset(const V2& u, float sigma) {
    const V2 normal = sample_standard_normal_pair(u);
    return V2{sigma * normal.x, sigma * normal.y};
  }
};

/// Uniform over the pixel square (sigma unused).
struct BoxAntialiasing {
  static constexpr bool enabled = true;
  template <typename V2>
  static V2 offset(const V2& u, float) {
    return V2{u.x - 0.5f, u.y - 0.5f};
  }
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
};

static_assert(Antialiasing<NoAntialiasing> && Antialiasing<GaussianAntialiasing> &&
              Antialiasing<BoxAntialiasing> && Antialiasing<TentAntialiasing>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
