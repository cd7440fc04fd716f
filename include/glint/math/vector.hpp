#pragma once
// Vector types used throughout glint. Rendering runs in single precision: it halves memory
// traffic and doubles SIMD width; the ray/sphere test is written to stay accurate in float
// even for the 1e5-radius wall spheres (see geometry/ray_sphere.hpp).

#include <algorithm>
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

/// The largest component; where one is NaN, as math/wide.hpp's max decides (std::max's rule,
/// one instruction, where std::fmax would be a library call).
inline float max_component(const Vec3& v) {
  return std::max(std::max(v.z, v.y), v.x);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
