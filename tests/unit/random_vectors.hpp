#pragma once
// Random numbers and directions for the geometry tests, from glint's own PCG32 so that a test's
// rays are the same on every platform.

#include <algorithm>
#include <cmath>

#include "glint/math/random.hpp"
#include "glint/math/vector.hpp"

namespace glint::test {

/// Uniform in [lo, hi).
inline float uniform(Pcg32& rng, float lo, float hi) {
  return lo + (hi - lo) * rng.next_float();
}

/// A direction uniform on the unit sphere (rejection from the cube).
inline Vec3 unit_vector(Pcg32& rng) {
  for (;;) {
    const Vec3 v(uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f));
    const float length2 = glm::dot(v, v);
    if (length2 > 1e-4f && length2 <= 1.0f) return v / std::sqrt(length2);
  }
}

/// A direction uniform on the unit sphere, from z uniform in [-1, 1) and the angle about z.
inline Vec3 random_unit_vector(Pcg32& rng) {
  const float z = uniform(rng, -1.0f, 1.0f);
  const float phi = uniform(rng, 0.0f, 2.0f * kPi);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return glm::normalize(Vec3(r * std::cos(phi), r * std::sin(phi), z));
}

}  // namespace glint::test
