#pragma once
// What a path tracer cannot see in a scene. A path from the camera finds a light either by
// hitting it or by a shadow ray towards it from a diffuse hit. A point light is never hit, and a
// shadow ray that meets a mirror or glass sphere is blocked: it cannot bend. So light that leaves
// a point light and reaches a diffuse surface by way of a mirror or through glass (a caustic:
// the bright spot under a glass ball) is missing from every path tracer's image, however many
// samples it takes. Light paths (vertex merging, bidirectional joins) find it. glint-render
// renders a scene with such a blind spot by vertex connection and merging, and every other scene
// with the path tracer, which is unbiased there and the fastest to a given error.

#include <cstdint>
#include <optional>

#include "glint/instruction_set.hpp"
#include "glint/render/materials/microfacet.hpp"
#include "glint/render/materials/rough_interface.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A point light and a specular sphere it can shine on: the light it sends by way of the sphere
/// is what a path tracer misses. Lines are the scene file's.
struct PathTracingBlindSpot {
  int light_line;
  int sphere_line;
};

/// The first point light that emits and the first sphere that reflects or transmits
/// specularly (a transparent lobe or a mirror that is not rough enough to be a microfacet lobe;
/// light is sampled towards and through a rough one), where the scene has both; none
/// otherwise. Conservative: it does not ask whether the light reaches the sphere or whether the
/// caustic lands in view, so a scene it names may render the same by both estimators, but a
/// scene it clears is one the path tracer renders without bias.
inline std::optional<PathTracingBlindSpot> path_tracing_blind_spot(const Scene& scene) {
  const PointLight* light = nullptr;
  for (const PointLight& candidate : scene.lights())
    if (candidate.intensity > 0.0f &&
        (candidate.color.x > 0.0f || candidate.color.y > 0.0f || candidate.color.z > 0.0f)) {
      light = &candidate;
      break;
    }
  if (!light) return std::nullopt;
  for (std::uint32_t sphere = 0; sphere < scene.sphere_count(); ++sphere) {
    const Material& material = scene.surface(sphere).material;
    const bool ideal_mirror =
        material.mirror > 0.0f && !is_microfacet_lobe(material.mirror_roughness);
    const bool ideal_interface =
        material.transparent > 0.0f &&
        !is_rough_interface(material.transparent, material.transparent_roughness, material.ior,
                            scene.surface(sphere).ior_outside);
    if (ideal_mirror || ideal_interface)
      return PathTracingBlindSpot{light->line, scene.sphere_line(sphere)};
  }
  return std::nullopt;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
