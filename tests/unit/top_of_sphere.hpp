#pragma once
// A hit on the top of a unit sphere at the origin, in air, for the tests of a material at one
// hit (scattering_test.cpp, microfacet_test.cpp).

#include "glint/geometry/ray.hpp"
#include "glint/render/scattering.hpp"
#include "glint/scene/scene.hpp"

namespace glint::test {

/// The hit (normal +z) of a ray travelling along `incoming`, with everything a material needs.
struct TopOfSphere {
  glint::SurfaceProperties surface;
  glint::Ray ray;
  glint::SurfaceInteraction interaction;

  TopOfSphere(const glint::Material& material, const glint::Vec3& incoming)
      : surface{material,
                glint::Vec3(0.0f),
                1.0f,
                glint::ShadingKind::uniform,
                material.is_fully_transparent(),
                material.has_mirror_finish(),
                glint::kNotAnEmitter} {
    const glint::Vec3 normal(0.0f, 0.0f, 1.0f);
    ray.origin = normal - incoming;
    ray.direction = incoming;
    interaction.point = normal;
    interaction.outward_normal = normal;
    interaction.sphere = 0u;
    glint::detail::set_surface_lane(interaction.surface, 0, surface);
    interaction.at = glint::detail::interface_at(ray.direction, normal);
  }
};

/// The same hit with its Bsdf of type B.
template <typename B>
struct TopOfSphereWith : TopOfSphere {
  TopOfSphereWith(const glint::Material& material, const glint::Vec3& incoming)
      : TopOfSphere(material, incoming) {}
  B bsdf(const glint::Vec3& incoming) const { return B(interaction, incoming); }
};

}  // namespace glint::test
