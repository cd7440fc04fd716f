#pragma once
// The render-ready scene: immutable after build, shared read-only by all render threads.
// Geometry lives in two structures: a SphereSet (structure of arrays, scanned with SIMD) for
// small scenes and for huge spheres such as walls, whose boxes would swallow everything in a
// hierarchy, and a SphereBvh for the many ordinary spheres of large scenes. What shading needs
// per sphere lives in one contiguous array of SurfaceProperties, touched only for a hit sphere.

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "glint/geometry/ray.hpp"
#include "glint/geometry/sphere_bvh.hpp"
#include "glint/geometry/sphere_set.hpp"
#include "glint/scene/inclusion_tree.hpp"
#include "glint/scene/scene_description.hpp"
#include "glint/scene/validate.hpp"

namespace glint {

struct SurfaceProperties {
  Vec3 center;
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
    const float huge_radius = huge_radius_threshold(description);
    std::vector<SphereBvh::Input> hierarchy_spheres;
    scene.surfaces_.reserve(description.spheres.size());
    for (std::size_t i = 0; i < description.spheres.size(); ++i) {
      const SphereDescription& sphere = description.spheres[i];
      const Material& m = sphere.material;
      const auto id = static_cast<std::uint32_t>(i);
      if (sphere.radius >= huge_radius)
        scene.linear_.add(sphere.center, sphere.radius, id);
      else
        hierarchy_spheres.push_back({sphere.center, sphere.radius, id});
      scene.surfaces_.push_back(SurfaceProperties{
          sphere.center, m.diffuse_color, m.diffuse, m.mirror_color, m.mirror, m.transparent_color,
          m.transparent, m.emission, m.ior, tree.outside_ior[i], sphere.radius, sphere.shading,
          m.is_fully_transparent(), m.is_emissive()});
    }
    scene.hierarchy_ = SphereBvh(std::move(hierarchy_spheres));
    return scene;
  }

  /// Nearest sphere along the ray in (t_min, t_max); false if none.
  bool intersect(const Ray& ray, SphereHit& hit) const {
    hit = SphereHit{};
    hit.t = ray.t_max;
    bool found = origin_sphere_hit(ray, hit);
    if (linear_.size() > 0) found = linear_.closest_hit(ray, hit) || found;
    if (!hierarchy_.empty()) found = hierarchy_.closest_hit(ray, hit) || found;
    return found;
  }

  /// Whether any sphere blocks the ray in (t_min, t_max).
  bool occluded(const Ray& ray) const {
    SphereHit hit;
    hit.t = ray.t_max;
    return origin_sphere_hit(ray, hit) || (linear_.size() > 0 && linear_.any_hit(ray)) ||
           (!hierarchy_.empty() && hierarchy_.any_hit(ray));
  }

  SurfaceHit surface_hit(const Ray& ray, const SphereHit& hit) const {
    const Vec3 point = ray.at(hit.t);
    const Vec3& center = surfaces_[hit.sphere].center;
    const Vec3 normal = glm::normalize(point - center);
    return {point, normal, normal, hit.sphere};
  }

  const SurfaceProperties& surface(std::uint32_t sphere) const { return surfaces_[sphere]; }
  std::size_t sphere_count() const { return surfaces_.size(); }
  const std::vector<PointLight>& lights() const { return description_.lights; }
  const SceneDescription& description() const { return description_; }
  /// Spheres scanned linearly (all of a small scene; the huge ones of a large scene).
  const SphereSet& linear_spheres() const { return linear_; }
  const SphereBvh& hierarchy() const { return hierarchy_; }

  /// Scenes up to this many spheres are scanned linearly: with SIMD, that beats a hierarchy.
  static constexpr std::size_t kLinearSceneSize = 64;

 private:
  Scene() = default;

  /// Spheres at least this large stay out of the hierarchy: the walls of a room (radius 1e5
  /// around a scene of size 100) would make every box in it enormous.
  static float huge_radius_threshold(const SceneDescription& description) {
    if (description.spheres.size() <= kLinearSceneSize) return 0.0f;
    std::vector<float> radii;
    radii.reserve(description.spheres.size());
    for (const SphereDescription& s : description.spheres)
      radii.push_back(s.radius);
    auto middle = radii.begin() + std::ptrdiff_t(radii.size() / 2);
    std::nth_element(radii.begin(), middle, radii.end());
    return 100.0f * *middle;
  }

  // A ray leaving its origin sphere outwards cannot meet it again; heading inwards it meets
  // the far side only.
  bool origin_sphere_hit(const Ray& ray, SphereHit& hit) const {
    if (ray.origin_sphere == kNoSphere || !ray.heads_into_origin_sphere) return false;
    const float t =
        far_side_distance(ray.origin, ray.direction, surfaces_[ray.origin_sphere].center);
    if (!(t > ray.t_min && t < hit.t)) return false;
    hit.t = t;
    hit.sphere = ray.origin_sphere;
    return true;
  }

  SceneDescription description_;
  SphereSet linear_;
  SphereBvh hierarchy_;
  std::vector<SurfaceProperties> surfaces_;
};

}  // namespace glint
