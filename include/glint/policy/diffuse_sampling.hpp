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
#if defined(GLINT_AVX2)
  static DirectionSampleLanes sample(Vec2Lanes u) {
    const Vec3Lanes d = sample_uniform_hemisphere_lanes(u);
    return {d, d.z / kUniformHemispherePdf};
  }
  static FloatLanes pdf(FloatLanes /*cos_theta*/) {
    return broadcast(kUniformHemispherePdf);
  }
#endif
};

/// Cosine-weighted: the weight cos/pdf is exactly pi, so a bounce adds no variance of its own.
struct CosineHemisphere {
  static DirectionSample sample(Vec2 u) { return {sample_cosine_hemisphere(u), kPi}; }
  static float pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }
#if defined(GLINT_AVX2)
  static DirectionSampleLanes sample(Vec2Lanes u) {
    return {sample_cosine_hemisphere_lanes(u), broadcast(kPi)};
  }
  static FloatLanes pdf(FloatLanes cos_theta) {
    return select(cos_theta > 0.0f, cos_theta * kInvPi, broadcast(0.0f));
  }
#endif
};

static_assert(DiffuseSampling<UniformHemisphere> && DiffuseSampling<CosineHemisphere>);

}  // namespace glint
