#pragma once
// Sphere shading policies: a sphere's diffuse colour as a function of the point hit. The
// report did this with a virtual Sphere::color(P); here the set of kinds is closed per build
// and dispatched with a switch on a one-byte tag stored with the sphere.

#include "glint/instruction_set.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// One colour per sphere; the cheapest policy, and scenes asking for more are rejected.
struct UniformShading {
  static bool supports(ShadingKind kind) { return kind == ShadingKind::uniform; }
  static Color color(ShadingKind, Color base, const ShadingPoint&) { return base; }
};

/// The built-in set: uniform, the report's eight-coloured sphere, a checkerboard and an image.
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
  /// colour and its complement: sectors of 45 degrees of longitude (around the y axis) and of
  /// latitude. Only the parity of a square matters, and it flips across each plane that bounds
  /// the squares (z = 0, x = 0, z = x and z = -x for the longitude; y = sqrt(1/2), 0 and
  /// -sqrt(1/2) for the latitude), so comparisons decide it: no inverse trigonometry from the
  /// C library, whose rounding differs between libraries, decides a pixel.
  static Color checker_color(Color base, Vec3 direction) {
    const float x = direction.x, y = direction.y, z = direction.z;
    constexpr float kHalfSqrt2 = 0.70710678f;
    const bool longitude_odd = !((z < 0.0f) ^ (x < 0.0f) ^ (z < x) ^ (z < -x));
    const bool latitude_odd = (y <= kHalfSqrt2) ^ (y <= 0.0f) ^ (y <= -kHalfSqrt2);
    return longitude_odd != latitude_odd ? Color(1.0f) - base : base;
  }

  static Color color(ShadingKind kind, Color base, const ShadingPoint& at) {
    switch (kind) {
      case ShadingKind::uniform:
        return base;
      case ShadingKind::octants:
        return octant_color(base, at.direction);
      case ShadingKind::checker:
        return checker_color(base, at.direction);
      case ShadingKind::texture:
        return at.texture ? base * at.texture->color(at.direction) : base;
      case ShadingKind::custom:
        return base;  // not supported: scenes using it are rejected
    }
    return base;
  }
};

static_assert(SphereShading<UniformShading> && SphereShading<BuiltinShading>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
