#pragma once
// Values and comparisons of floats that many tests share.

#include <bit>
#include <cstdint>
#include <limits>
#include <numbers>

namespace glint_test {

inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kInf = std::numeric_limits<float>::infinity();
inline constexpr double kDegree = std::numbers::pi / 180.0;

/// Whether two floats have the same bits (== would call -0 and 0 equal, and NaN unequal).
inline bool same_bits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

}  // namespace glint_test
