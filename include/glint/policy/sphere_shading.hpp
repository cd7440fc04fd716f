#pragma once
// Sphere shading policies: a sphere's diffuse colour as a function of the point hit. The
// report did this with a virtual Sphere::color(P); here the set of kinds is closed per build
// and dispatched with a switch on a one-byte tag stored with the sphere.

#include <cmath>

#include "glint/policy/concepts.hpp"

namespace glint {

/// One colour per sphere; the cheapest policy, and scenes asking for more are rejected.
struct UniformShading {
  static bool supports(ShadingKind kind) { return kind == ShadingKind::uniform; }
  static Color color(ShadingKind, Color base, Vec3) { return base; }
};

/// The built-in set: uniform, the report's eight-coloured sphere, and a checkerboard.
/// `custom` is left to user-defined policies (see examples/custom_shading).
struct BuiltinShading {
  static bool supports(ShadingKind kind) { return kind != ShadingKind::custom; }

  /// One colour per octant around the centre (octant bit i set where component i > 0),
  /// multiplied by the sphere's colour.
  static Color octant_color(Color base, Vec3 direction) {
    static constexpr float palette[8][3] = {
        {0.85f, 0.15f, 0.15f}, {0.15f, 0.75f, 0.20f}, {0.15f, 0.30f, 0.85f}, {0.90f, 0.80f, 0.15f},
        {0.15f, 0.80f, 0.80f}, {0.80f, 0.20f, 0.80f}, {0.95f, 0.95f, 0.95f}, {0.95f, 0.50f, 0.10f}};
    const int octant =
        (direction.x > 0.0f ? 1 : 0) | (direction.y > 0.0f ? 2 : 0) | (direction.z > 0.0f ? 4 : 0);
    return base * Color(palette[octant][0], palette[octant][1], palette[octant][2]);
  }

  /// Eight squares around the equator and four from pole to pole, alternating between the
  /// colour and its complement.
  static Color checker_color(Color base, Vec3 direction) {
    const float longitude = std::atan2(direction.z, direction.x) + kPi;                // [0, 2pi]
    const float latitude = std::acos(std::fmax(-1.0f, std::fmin(1.0f, direction.y)));  // [0, pi]
    const int u = static_cast<int>(longitude * (4.0f * kInvPi));
    const int v = static_cast<int>(latitude * (4.0f * kInvPi));
    return ((u + v) & 1) ? Color(1.0f) - base : base;
  }

  static Color color(ShadingKind kind, Color base, Vec3 direction) {
    switch (kind) {
      case ShadingKind::uniform:
        return base;
      case ShadingKind::octants:
        return octant_color(base, direction);
      case ShadingKind::checker:
        return checker_color(base, direction);
      case ShadingKind::custom:
        return base;  // not supported: scenes using it are rejected
    }
    return base;
  }
};

static_assert(SphereShading<UniformShading> && SphereShading<BuiltinShading>);

}  // namespace glint
