#pragma once
// A scene as plain, editable data: what the parser produces, what the random generator
// produces, and what a program may fill in by hand. Nothing here is optimised for rendering;
// Scene (scene/scene.hpp) is built from it once. Every element keeps the line it came from so
// that errors found later (e.g. overlapping glass) can still point into the file.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/scene/image_settings.hpp"
#include "glint/scene/material.hpp"
#include "glint/scene/sphere_texture.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

struct ImageDescription : ImageSettings {
  int line = 0;
};

/// How a camera maps its film to directions.
enum class Projection : std::uint8_t {
  perspective,      ///< a pinhole or a thin lens: a plane of film, `fov` high
  equirectangular,  ///< every direction: the film's columns are longitudes, its rows latitudes
};
inline constexpr int kProjectionCount = 2;

constexpr std::string_view to_string(Projection projection) {
  return projection == Projection::perspective ? "perspective" : "equirectangular";
}

struct CameraDescription {
  Vec3 position{0.0f, 0.0f, 55.0f};
  Vec3 look_at{0.0f, 0.0f, 0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fov_degrees = 60.0f;  ///< vertical field of view
  float near = 0.0f;          ///< nothing closer than this along the viewing direction is seen
  float aperture = 0.0f;      ///< the lens's radius; 0: a pinhole
  /// The distance along the viewing direction of the plane in focus; 0: that of look_at.
  float focus_distance = 0.0f;
  /// Equirectangular: a 360-degree panorama around the position, the film's middle towards
  /// look_at, its top row towards up (fov, aperture and focus do not apply).
  Projection projection = Projection::perspective;
  int line = 0;
};

struct PointLight {
  Vec3 position{0.0f};
  float intensity = 1.0f;  ///< radiant intensity in W/sr, multiplied by color
  Color color{1.0f};
  int line = 0;
};

struct SphereDescription {
  Vec3 center{0.0f};
  float radius = 1.0f;
  Material material{};
  ShadingKind shading = ShadingKind::uniform;
  /// The image of ShadingKind::texture (null for the other kinds), shared by the spheres that
  /// show the same file, and how it lies on the sphere.
  std::shared_ptr<const Texture> texture;
  TexturePlacement texture_placement{};
  int line = 0;
};

struct SceneDescription {
  std::string source = "<scene>";  ///< file name (or a label) used in error messages
  ImageDescription image{};
  CameraDescription camera{};
  float antialias_sigma = defaults::antialias_sigma;  ///< Gaussian pixel filter width, pixels
  Color background{0.0f};                             ///< radiance of rays that escape the scene
  /// An image around the scene in place of the background colour (scene/environment.hpp), its
  /// placement and the factor its texels are scaled by; null for a background of one colour.
  std::shared_ptr<const Texture> background_image;
  TexturePlacement background_placement{};
  float background_scale = 1.0f;
  float medium_ior = 1.0f;  ///< refractive index outside every transparent sphere
  std::vector<PointLight> lights;
  std::vector<SphereDescription> spheres;
  // Lines of the statements that set the three scalars above (0: not from a file).
  int antialias_line = 0;
  int background_line = 0;
  int medium_line = 0;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
