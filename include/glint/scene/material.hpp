#pragma once
// The report's material: three lobes weighted by coefficients, each with its own colour, plus
// emission. The coefficients say what fraction of the light each lobe takes; they are in [0, 1]
// and sum to at most 1, so a material never creates energy.

#include <cstdint>
#include <string_view>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// How a sphere's diffuse colour varies over its surface. The set is closed so the renderer can
/// dispatch on a small tag; a shading policy declares which of these kinds a build supports.
enum class ShadingKind : std::uint8_t {
  uniform,  ///< one colour over the whole sphere
  octants,  ///< the report's eight-coloured sphere: one colour per octant around the centre
  checker,  ///< a latitude/longitude checkerboard of the colour and its complement
  custom,   ///< whatever the renderer variant's own shading policy defines (none built in)
};
inline constexpr int kShadingKindCount = 4;

constexpr std::string_view to_string(ShadingKind kind) {
  switch (kind) {
    case ShadingKind::uniform:
      return "uniform";
    case ShadingKind::octants:
      return "octants";
    case ShadingKind::checker:
      return "checker";
    case ShadingKind::custom:
      return "custom";
  }
  return "?";
}

struct Material {
  float diffuse = 1.0f;  ///< fraction scattered diffusely (Lambertian)
  Color diffuse_color{1.0f};
  float mirror = 0.0f;  ///< fraction reflected specularly
  Color mirror_color{1.0f};
  float transparent = 0.0f;  ///< fraction refracted (or, with Fresnel, reflected or refracted)
  Color transparent_color{1.0f};
  float ior = 1.5f;      ///< refractive index inside the sphere; used when transparent > 0
  Color emission{0.0f};  ///< emitted radiance, both sides of the surface

  bool is_transparent() const { return transparent > 0.0f; }
  /// The report applies Fresnel only to spheres with no user-defined diffusion or mirror.
  bool is_fully_transparent() const { return transparent == 1.0f; }
  bool is_emissive() const { return emission != Color(0.0f); }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
