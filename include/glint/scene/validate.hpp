#pragma once
// Semantic checks on a SceneDescription, shared by the scene file reader and by programs that
// build descriptions themselves. Each failure is a SceneError naming the offending line.
//
// The checks are split per element (detail::check_image, check_camera, ...) so that the reader
// can run each one as soon as its statement is parsed: the first error reported is then the
// first one in the file, whatever kind it is.

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "glint/detail/text.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"
#include "glint/scene/material.hpp"
#include "glint/scene/scene_description.hpp"
#include "glint/scene/scene_error.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Limits on geometry, beyond which float arithmetic would no longer render a scene correctly.
/// A scene stores its numbers as floats (about 7 significant digits); within these limits the
/// ray/sphere kernels answer to that precision (geometry/ray_sphere.hpp) and no squared distance
/// they form comes near float's overflow at 3.4e38.
namespace limits {
/// The largest sphere radius: 1e10 covers the walls of the largest random scene (1.25e9) with a
/// margin; tests/render/huge_sphere_test.cpp checks floors up to it against the exact sphere
/// and the plane, and at the largest coordinates.
inline constexpr float max_sphere_radius = 1e10f;
/// The largest magnitude of a coordinate of a sphere's centre, the camera's position or a
/// light's position: ten times the largest radius, so that a floor of that radius can sit
/// anywhere near the origin, while |f|^2 <= 3 (2 * 1e11 + 1e10)^2 ~ 1.4e23 stays far from
/// overflow.
inline constexpr float max_coordinate = 1e11f;
}  // namespace limits

namespace detail {

inline bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
inline bool non_negative(const Vec3& v) {
  return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f;
}

/// An empty string if every coordinate of the point is within limits::max_coordinate, else the
/// complaint about `what` (e.g. "sphere center"). Only for finite points.
inline std::string coordinate_problem(const char* what, const Vec3& point) {
  const float largest = max_of(std::abs(point.x), max_of(std::abs(point.y), std::abs(point.z)));
  if (largest <= limits::max_coordinate) return {};
  return concat({what, " coordinates must be within +-", format_number(limits::max_coordinate),
                 " (the scene format's limit), got ", format_number(largest)});
}

inline void check_material(const SceneDescription& scene, const Material& m, int line) {
  auto fail = [&](const std::string& what) { throw SceneError(scene.source, line, what); };
  const float coefficients[] = {m.diffuse, m.mirror, m.transparent};
  const char* names[] = {"diffuse", "mirror", "transparent"};
  for (int i = 0; i < 3; ++i) {
    if (!(coefficients[i] >= 0.0f && coefficients[i] <= 1.0f))
      fail(concat(
          {names[i], " coefficient must be in [0, 1], got ", format_number(coefficients[i])}));
  }
  // A small tolerance lets "diffuse=0.3 mirror=0.3 transparent=0.4" through despite rounding.
  if (m.diffuse + m.mirror + m.transparent > 1.0f + 1e-5f)
    fail(concat({"diffuse + mirror + transparent must not exceed 1, got ",
                 format_number(m.diffuse + m.mirror + m.transparent)}));
  const Color* colors[] = {&m.diffuse_color, &m.mirror_color, &m.transparent_color};
  const char* color_names[] = {"color", "mirror_color", "transparent_color"};
  for (int i = 0; i < 3; ++i) {
    if (!finite(*colors[i]) || !non_negative(*colors[i]) || max_component(*colors[i]) > 1.0f)
      fail(concat({color_names[i], " components must be in [0, 1]"}));
  }
  if (!finite(m.emission) || !non_negative(m.emission))
    fail("emission must be finite and non-negative");
  if (!(m.ior >= 1e-3f && m.ior <= 100.0f)) fail("ior must be in [0.001, 100]");
  if (!(m.mirror_roughness >= 0.0f && m.mirror_roughness <= 1.0f))
    fail(concat({"mirror_roughness must be in [0, 1], got ", format_number(m.mirror_roughness)}));
  if (m.mirror_roughness > 0.0f && !(m.mirror > 0.0f))
    fail("mirror_roughness roughens the mirror lobe, which this material does not have (mirror=0)");
  if (!(m.transparent_roughness >= 0.0f && m.transparent_roughness <= 1.0f))
    fail(concat(
        {"transparent_roughness must be in [0, 1], got ", format_number(m.transparent_roughness)}));
  if (m.transparent_roughness > 0.0f && !(m.transparent > 0.0f))
    fail(
        "transparent_roughness roughens the transparent lobe, which this material does not have "
        "(transparent=0)");
  if (m.is_metal()) {
    const auto within = [](const Vec3& v, float low, float high) {
      for (int i = 0; i < 3; ++i)
        if (!(v[i] >= low && v[i] <= high)) return false;
      return true;
    };
    if (!within(m.metal_eta, 1e-3f, 100.0f)) fail("metal_eta components must be in [0.001, 100]");
    if (!within(m.metal_k, 0.0f, 100.0f)) fail("metal_k components must be in [0, 100]");
    if (!(m.mirror > 0.0f))
      fail(
          "a metal reflects through the mirror lobe, which this material does not have (mirror=0)");
  }
}

inline void check_image(const SceneDescription& scene) {
  const ImageDescription& image = scene.image;
  const std::string problem = image_settings_problem(image);
  if (!problem.empty()) throw SceneError(scene.source, image.line, problem);
}

inline void check_camera(const SceneDescription& scene) {
  const CameraDescription& camera = scene.camera;
  const auto fail = [&](const std::string& what) {
    throw SceneError(scene.source, camera.line, what);
  };
  if (!finite(camera.position) || !finite(camera.look_at) || !finite(camera.up))
    fail("camera vectors must be finite");
  // Geometry in double so that the test itself cannot overflow or lose the answer.
  const glm::dvec3 position(camera.position);
  const glm::dvec3 forward = glm::dvec3(camera.look_at) - position;
  const glm::dvec3 up(camera.up);
  const double distance = glm::length(forward);
  if (distance <= 1e-6 * (1.0 + glm::length(position)))
    fail("camera position and look_at coincide");
  if (glm::length(up) == 0.0) fail("camera up vector is zero");
  if (glm::length(glm::cross(forward / distance, up / glm::length(up))) < 1e-4)
    fail("camera up vector is parallel to the viewing direction");
  // The camera builds its basis in float; vectors valid in double can still overflow or
  // underflow there (position 1e30 from look_at, up=1e-30,0,0) and give a NaN basis.
  const Vec3 forward_f = glm::normalize(camera.look_at - camera.position);
  const Vec3 right_f = glm::normalize(glm::cross(forward_f, camera.up));
  if (!finite(forward_f) || !finite(right_f) || std::abs(glm::length(forward_f) - 1.0f) > 1e-3f ||
      std::abs(glm::length(right_f) - 1.0f) > 1e-3f)
    fail("camera vectors are too large or too small to build a viewing basis in float");
  if (const std::string problem = coordinate_problem("camera position", camera.position);
      !problem.empty())
    fail(problem);
  if (!(camera.fov_degrees > 0.0f && camera.fov_degrees < 180.0f))
    fail(concat({"camera fov must be strictly between 0 and 180 degrees, got ",
                 format_number(camera.fov_degrees)}));
  if (!(camera.near >= 0.0f) || !std::isfinite(camera.near))
    fail("camera near must be finite and non-negative");
  // The lens's rays leave from points up to `aperture` from the position: coordinates too.
  if (!(camera.aperture >= 0.0f && camera.aperture <= limits::max_coordinate))
    fail(concat({"camera aperture must be between 0 and ", format_number(limits::max_coordinate),
                 ", got ", format_number(camera.aperture)}));
  if (camera.projection == Projection::equirectangular && camera.aperture > 0.0f)
    fail("a thin lens (aperture) is a perspective camera's; an equirectangular one is a pinhole");
  // 0 stands for the distance to look_at (a file cannot write it: the reader refuses it).
  if (!(camera.focus_distance >= 0.0f && camera.focus_distance <= limits::max_coordinate))
    fail(
        concat({"camera focus must be positive and at most ", format_number(limits::max_coordinate),
                ", got ", format_number(camera.focus_distance)}));
}

inline void check_antialias(const SceneDescription& scene) {
  const std::string problem = antialias_sigma_problem(scene.antialias_sigma);
  if (!problem.empty()) throw SceneError(scene.source, scene.antialias_line, problem);
}

inline void check_background(const SceneDescription& scene) {
  const auto fail = [&](const std::string& what) {
    throw SceneError(scene.source, scene.background_line, what);
  };
  if (!finite(scene.background) || !non_negative(scene.background))
    fail("background color must be finite and non-negative");
  const TexturePlacement& placement = scene.background_placement;
  if (!scene.background_image) {
    if (placement.axis != TexturePlacement{}.axis || placement.turn_degrees != 0.0f ||
        scene.background_scale != 1.0f)
      fail("background axis, turn and scale place an image: give it with image=FILE");
    return;
  }
  if (scene.background != Color(0.0f))
    fail("a background is a color or an image, not both: give color= or image=");
  if (!finite(placement.axis) || placement.axis == Vec3(0.0f))
    fail("background axis must be a finite direction, not zero");
  if (!std::isfinite(placement.turn_degrees)) fail("background turn must be finite");
  const float scale = scene.background_scale;
  if (!(scale >= 0.0f) || !std::isfinite(scale))
    fail(concat({"background scale must be finite and non-negative, got ", format_number(scale)}));
  float brightest = 0.0f;
  for (const Color& texel : scene.background_image->texels())
    brightest = std::max({brightest, texel.r, texel.g, texel.b});
  if (!std::isfinite(brightest * scale))
    fail(concat({"background scale ", format_number(scale), " takes the image's brightest texel (",
                 format_number(brightest), ") beyond float's range"}));
}

inline void check_medium(const SceneDescription& scene) {
  if (!(scene.medium_ior >= 1e-3f && scene.medium_ior <= 100.0f))
    throw SceneError(
        scene.source, scene.medium_line,
        concat({"medium ior must be in [0.001, 100], got ", format_number(scene.medium_ior)}));
}

inline void check_light(const SceneDescription& scene, const PointLight& light) {
  const auto fail = [&](const std::string& what) {
    throw SceneError(scene.source, light.line, what);
  };
  if (!finite(light.position)) fail("light position must be finite");
  if (const std::string problem = coordinate_problem("light position", light.position);
      !problem.empty())
    fail(problem);
  if (!(light.intensity >= 0.0f) || !std::isfinite(light.intensity))
    fail("light intensity must be finite and non-negative");
  if (!finite(light.color) || !non_negative(light.color))
    fail("light color must be finite and non-negative");
}

/// What is wrong with a sphere's shading kind given whether it has an image ("" if nothing).
inline std::string texture_shading_problem(ShadingKind shading, bool has_texture) {
  if (shading == ShadingKind::texture && !has_texture)
    return "shading=texture needs an image: texture=FILE";
  if (has_texture && shading != ShadingKind::texture)
    return concat(
        {"a texture is shown by shading=texture, not shading=", std::string(to_string(shading))});
  return {};
}

inline void check_sphere(const SceneDescription& scene, const SphereDescription& sphere) {
  const auto fail = [&](const std::string& what) {
    throw SceneError(scene.source, sphere.line, what);
  };
  if (!finite(sphere.center)) fail("sphere center must be finite");
  if (const std::string problem = coordinate_problem("sphere center", sphere.center);
      !problem.empty())
    fail(problem);
  if (!(sphere.radius > 0.0f) || !std::isfinite(sphere.radius))
    fail(concat({"sphere radius must be positive and finite, got ", format_number(sphere.radius)}));
  if (sphere.radius > limits::max_sphere_radius)
    fail(concat({"sphere radius must be at most ", format_number(limits::max_sphere_radius),
                 " (the scene format's limit), got ", format_number(sphere.radius)}));
  check_material(scene, sphere.material, sphere.line);
  if (const std::string problem = texture_shading_problem(sphere.shading, bool(sphere.texture));
      !problem.empty())
    fail(problem);
  const TexturePlacement& placement = sphere.texture_placement;
  if (!finite(placement.axis) || placement.axis == Vec3(0.0f))
    fail("texture_axis must be a finite direction, not zero");
  if (!std::isfinite(placement.turn_degrees)) fail("texture_turn must be finite");
}

}  // namespace detail

/// Throws SceneError on the first problem found; returns normally for a valid scene. The
/// nesting rule for transparent spheres is checked by build_inclusion_tree, which needs the
/// geometry anyway.
inline void validate(const SceneDescription& scene) {
  detail::check_image(scene);
  detail::check_camera(scene);
  detail::check_antialias(scene);
  detail::check_background(scene);
  detail::check_medium(scene);
  for (const PointLight& light : scene.lights)
    detail::check_light(scene, light);
  for (const SphereDescription& sphere : scene.spheres)
    detail::check_sphere(scene, sphere);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
