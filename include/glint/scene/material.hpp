#pragma once
// The report's material: three lobes weighted by coefficients, each with its own colour, plus
// emission. The coefficients say what fraction of the light each lobe takes; they are in [0, 1]
// and sum to at most 1, so a material never creates energy. Beyond the report, the mirror lobe
// may be rough (a microfacet surface) and reflect as a metal does (a conductor's Fresnel
// reflectance), and the transparent lobe's interface may be rough (frosted glass); a material
// model that has these (policy/material_model.hpp) renders them.

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
  texture,  ///< an image wrapped around the sphere, times the colour (scene/sphere_texture.hpp)
  custom,   ///< whatever the renderer variant's own shading policy defines (none built in)
};
inline constexpr int kShadingKindCount = 5;

constexpr std::string_view to_string(ShadingKind kind) {
  switch (kind) {
    case ShadingKind::uniform:
      return "uniform";
    case ShadingKind::octants:
      return "octants";
    case ShadingKind::checker:
      return "checker";
    case ShadingKind::texture:
      return "texture";
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
  /// Roughness of the mirror lobe in [0, 1]: the microfacet distribution's alpha is its square
  /// (render/materials/microfacet.hpp); 0 is the ideal mirror.
  float mirror_roughness = 0.0f;
  /// The complex refractive index n + ik of a metal at the red, green and blue primaries, whose
  /// Fresnel reflectance scales the mirror lobe; all zero (the default) for a reflectance of one.
  Color metal_eta{0.0f};
  Color metal_k{0.0f};
  /// Roughness of the transparent lobe's interface in [0, 1], as mirror_roughness is of the
  /// mirror: a microfacet interface that reflects and refracts through each facet; 0 is the
  /// ideal interface.
  float transparent_roughness = 0.0f;

  bool is_transparent() const { return transparent > 0.0f; }
  /// The report applies Fresnel only to spheres with no user-defined diffusion or mirror.
  bool is_fully_transparent() const { return transparent == 1.0f; }
  bool is_emissive() const { return emission != Color(0.0f); }
  /// The mirror lobe reflects with a metal's Fresnel reflectance.
  bool is_metal() const { return metal_eta != Color(0.0f) || metal_k != Color(0.0f); }
  /// The mirror lobe is more than the report's ideal mirror: rough, or a metal's.
  bool has_mirror_finish() const {
    return mirror > 0.0f && (mirror_roughness > 0.0f || is_metal());
  }
  /// The transparent lobe's interface is rough.
  bool has_rough_interface() const { return transparent > 0.0f && transparent_roughness > 0.0f; }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
