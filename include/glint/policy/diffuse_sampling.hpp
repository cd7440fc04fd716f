#pragma once
// Diffuse bounce direction policies. Both give unbiased estimates of the same integral; they
// differ only in variance. Each is written once for every width (math/wide.hpp).

#include "glint/instruction_set.hpp"
#include "glint/math/sampling.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The report's choice: uniform over the hemisphere, weight cos(theta) / (1/2pi).
struct UniformHemisphere {
  template <typename V2>
  static BasicDirectionSample<FloatOf<V2>> sample(const V2& u) {
    const Vec3For<FloatOf<V2>> d = sample_uniform_hemisphere(u);
    return {d, d.z / kUniformHemispherePdf};
  }
  /// The density of a direction at cos(theta) from the normal: none below the surface.
  template <FloatType F>
  static F pdf(F cos_theta) {
    return select(cos_theta > 0.0f, splat<F>(kUniformHemispherePdf), splat<F>(0.0f));
  }
};

/// Cosine-weighted: the weight cos/pdf is exactly pi, so a bounce adds no variance of its own.
struct CosineHemisphere {
  template <typename V2>
  static BasicDirectionSample<FloatOf<V2>> sample(const V2& u) {
    return {sample_cosine_hemisphere(u), splat<FloatOf<V2>>(kPi)};
  }
  template <FloatType F>
  static F pdf(F cos_theta) {
    return select(cos_theta > 0.0f, cos_theta * kInvPi, splat<F>(0.0f));
  }
};

static_assert(DiffuseSampling<UniformHemisphere> && DiffuseSampling<CosineHemisphere>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
