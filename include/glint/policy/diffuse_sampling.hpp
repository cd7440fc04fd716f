#pragma once
// Diffuse bounce direction policies. Both give unbiased estimates of the same integral; they
// differ only in variance.

#include "glint/math/sampling.hpp"
#include "glint/policy/concepts.hpp"

namespace glint {

/// The report's choice: uniform over the hemisphere, weight cos(theta) / (1/2pi).
struct UniformHemisphere {
  static DirectionSample sample(Vec2 u) {
    const Vec3 d = sample_uniform_hemisphere(u);
    return {d, d.z / kUniformHemispherePdf};
  }
  static float pdf(float /*cos_theta*/) { return kUniformHemispherePdf; }
};

/// Cosine-weighted: the weight cos/pdf is exactly pi, so a bounce adds no variance of its own.
struct CosineHemisphere {
  static DirectionSample sample(Vec2 u) { return {sample_cosine_hemisphere(u), kPi}; }
  static float pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }
};

static_assert(DiffuseSampling<UniformHemisphere> && DiffuseSampling<CosineHemisphere>);

}  // namespace glint
