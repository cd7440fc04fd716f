#pragma once
// The render-ready scene: immutable after build, shared read-only by all render threads.
// Geometry lives in a SphereSet (structure of arrays for SIMD); what shading needs per sphere
// lives in one contiguous array of SurfaceProperties, touched only for the sphere that was hit.

#include <cstdint>
#include <string>
#include <vector>

#include "glint/geometry/ray.hpp"
#include "glint/geometry/sphere_set.hpp"
#include "glint/scene/inclusion_tree.hpp"
#include "glint/scene/scene_description.hpp"
#include "glint/scene/validate.hpp"

namespace glint {

struct SurfaceProperties {
  Color diffuse_color;
  float diffuse;
  Color mirror_color;
  float mirror;
  Color transparent_color;
  float transparent;
  Color emission;
  float ior_inside;
  float ior_outside;  ///< from the inclusion tree
  float radius;
  ShadingKind shading;
  bool fully_transparent;
  bool emissive;
};

struct SurfaceHit {
  Vec3 point;
  Vec3 outward_normal;
  Vec3 local_direction;  ///< unit vector from the sphere's centre to the point (for shading)
  std::uint32_t sphere;
};

class Scene {
 public:
  /// Validates the description (SceneError on any problem, with its line) and builds the
  /// acceleration data and the inclusion tree.
  static Scene build(const SceneDescription& description) {
    validate(description);
    Scene scene;
    scene.description_ = description;
    const InclusionTree tree = build_inclusion_tree(description);
    scene.surfaces_.reserve(description.spheres.size());
    for (std::size_t i = 0; i < description.spheres.size(); ++i) {
      const SphereDescription& sphere = description.spheres[i];
      const Material& m = sphere.material;
      scene.spheres_.add(sphere.center, sphere.radius);
      scene.surfaces_.push_back(SurfaceProperties{
          m.diffuse_color, m.diffuse, m.mirror_color, m.mirror, m.transparent_color,
          m.transparent, m.emission, m.ior, tree.outside_ior[i], sphere.radius, sphere.shading,
          m.is_fully_transparent(), m.is_emissive()});
    }
    return scene;
  }

  bool intersect(const Ray& ray, SphereHit& hit) const { return spheres_.closest_hit(ray, hit); }
  bool occluded(const Ray& ray) const { return spheres_.any_hit(ray); }

  SurfaceHit surface_hit(const Ray& ray, const SphereHit& hit) const {
    const Vec3 point = ray.at(hit.t);
    const Vec3 center = spheres_.center(hit.sphere);
    const Vec3 normal = glm::normalize(point - center);
    return {point, normal, normal, hit.sphere};
  }

  const SurfaceProperties& surface(std::uint32_t sphere) const { return surfaces_[sphere]; }
  std::size_t sphere_count() const { return surfaces_.size(); }
  const std::vector<PointLight>& lights() const { return description_.lights; }
  const SceneDescription& description() const { return description_; }
  const SphereSet& spheres() const { return spheres_; }

 private:
  Scene() = default;

  SceneDescription description_;
  SphereSet spheres_;
  std::vector<SurfaceProperties> surfaces_;
};

}  // namespace glint
