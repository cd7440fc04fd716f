#pragma once
// Vector types used throughout glint. Rendering runs in single precision: it halves memory
// traffic and doubles SIMD width; the ray/sphere test is written to stay accurate in float
// even for the 1e5-radius wall spheres (see geometry/ray_sphere.hpp).

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
/// Linear RGB radiance or reflectance.
using Color = glm::vec3;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;

/// Minimum and maximum that compile to single instructions (std::fmin/fmax must handle NaN
/// specially and end up as library calls in hot loops). If either argument is NaN the
/// result is the second argument.
inline float min_of(float a, float b) {
  return a < b ? a : b;
}
inline float max_of(float a, float b) {
  return a > b ? a : b;
}

inline float max_component(const Vec3& v) {
  return max_of(v.x, max_of(v.y, v.z));
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
