#pragma once
// A unit direction in four bytes: the octahedral map (Meyer et al. 2010, "On floating-point
// normal vectors"; Cigolle et al. 2014) folds the sphere onto the square [-1, 1]^2, whose two
// coordinates are kept in 16 bits each, rounded to the nearest step. A direction comes back
// within about 6.5e-5 radians of itself (the test holds it to 8e-5), the same bits on every
// machine: for directions that are read many times and must take little memory (the arrival of
// the light at a merge candidate).

#include <cmath>
#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class OctahedralDirection {
 public:
  OctahedralDirection() = default;

  /// The nearest of the map's directions to unit `direction`.
  explicit OctahedralDirection(const Vec3& direction) {
    const float norm = std::fabs(direction.x) + std::fabs(direction.y) + std::fabs(direction.z);
    float x = direction.x / norm, y = direction.y / norm;
    if (direction.z < 0.0f) {
      // The lower half folded over the diagonals onto the corners.
      const float folded_x = (1.0f - std::fabs(y)) * sign(x);
      y = (1.0f - std::fabs(x)) * sign(y);
      x = folded_x;
    }
    x_ = quantize(x);
    y_ = quantize(y);
  }

  /// The direction, of unit length.
  Vec3 direction() const {
    float x = dequantize(x_), y = dequantize(y_);
    const float z = 1.0f - std::fabs(x) - std::fabs(y);
    if (z < 0.0f) {
      const float unfolded_x = (1.0f - std::fabs(y)) * sign(x);
      y = (1.0f - std::fabs(x)) * sign(y);
      x = unfolded_x;
    }
    const float length = std::sqrt(x * x + y * y + z * z);
    return Vec3(x / length, y / length, z / length);
  }

  bool operator==(const OctahedralDirection&) const = default;

 private:
  static constexpr float kSteps = 65535.0f;
  static float sign(float v) { return v < 0.0f ? -1.0f : 1.0f; }
  static std::uint16_t quantize(float v) {
    const float clamped = v < -1.0f ? -1.0f : (v > 1.0f ? 1.0f : v);
    return std::uint16_t(std::lround((clamped + 1.0f) * 0.5f * kSteps));
  }
  static float dequantize(std::uint16_t q) { return float(q) / kSteps * 2.0f - 1.0f; }

  std::uint16_t x_ = 0, y_ = 0;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
