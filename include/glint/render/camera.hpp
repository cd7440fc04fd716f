#pragma once

#include <cmath>
#include <optional>

#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/wide.hpp"
#include "glint/scene/scene_description.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Where the camera sees a point, for light that reaches the camera from it (a light path's
/// vertex connected to the camera).
struct CameraConnection {
  Vec2 film;       ///< film coordinates of the point's image, in pixels (maybe off the film)
  Vec3 direction;  ///< unit direction from the point to the camera
  float distance;  ///< from the point to the camera
  /// From the point to the near plane along `direction`: the part of the way that a sphere
  /// can block (the camera's rays start at the near plane).
  float unclipped_distance;
  /// The camera's importance for light leaving the point towards it, per unit area and unit
  /// cosine at the point: 1 / (p^2 cos^3(theta) distance^2), p the size of a pixel on the
  /// plane at distance 1 and theta the angle between the ray and the viewing direction. A pixel's
  /// value being the mean radiance over its filter's offsets (in pixels), light leaving the
  /// point with radiance L adds L |cos| importance density(film - centre) to it per unit area.
  float importance;
};

/// A pinhole camera. Film coordinates are in pixels: (0,0) is the top-left corner of the
/// image, (width, height) the bottom-right one, so pixel (x, y) has its centre at
/// (x + 0.5, y + 0.5).
class Camera {
 public:
  Camera(const CameraDescription& description, int width, int height)
      : position_(description.position), near_(description.near) {
    forward_ = glm::normalize(description.look_at - description.position);
    right_ = glm::normalize(glm::cross(forward_, description.up));
    up_ = glm::cross(right_, forward_);
    // glint's own sine and cosine, not the C library's tangent: every ray depends on it.
    float sin_half, cos_half;
    sincos(0.5f * description.fov_degrees * kPi / 180.0f, sin_half, cos_half);
    const float tan_half = sin_half / cos_half;
    pixel_scale_ = 2.0f * tan_half / static_cast<float>(height);
    half_width_ = 0.5f * static_cast<float>(width);
    half_height_ = 0.5f * static_cast<float>(height);
  }

  Ray ray_through(Vec2 film) const {
    Ray ray;
    ray.origin = position_;
    rays_through(film, ray.direction, ray.t_min);
    return ray;
  }

  /// ray_through for a Float's lanes of film points at once (V2 is Vec2 or a Vector2 of
  /// lanes), the same bits in every lane: the directions and t_min (the origin is position()).
  template <typename V2>
  void rays_through(const V2& film, Vec3For<FloatOf<V2>>& direction, FloatOf<V2>& t_min) const {
    using V3 = Vec3For<FloatOf<V2>>;
    const FloatOf<V2> sx = (film.x - half_width_) * pixel_scale_;
    const FloatOf<V2> sy = (half_height_ - film.y) * pixel_scale_;
    const V3 forward = splat_vector<V3>(forward_);
    direction = normalize(forward + sx * splat_vector<V3>(right_) + sy * splat_vector<V3>(up_));
    // The clipping plane is perpendicular to the viewing direction, so the distance along a
    // ray grows as 1/cos of its angle to it.
    t_min = near_ / dot(direction, forward);
  }

  const Vec3& position() const { return position_; }
  /// The size of a pixel on the plane at distance one in the viewing direction.
  float pixel_size() const { return pixel_scale_; }

  /// Density per unit solid angle of a ray in unit `direction` when its film point is drawn
  /// with density one per pixel area: 1 / (p^2 cos^3(theta)), p the size of a pixel on the plane
  /// at distance 1 and theta the angle to the viewing direction (zero behind the camera).
  float solid_angle_density(const Vec3& direction) const {
    const float cosine = glm::dot(direction, forward_);
    if (!(cosine > 0.0f)) return 0.0f;
    return 1.0f / solid_angle_per_pixel(cosine);
  }

  /// Where the camera sees `point`: none when it is behind the camera or not beyond the near
  /// plane (ray_through's rays start there), the film position otherwise, on the film or not.
  std::optional<CameraConnection> connect(const Vec3& point) const {
    const Vec3 offset = point - position_;
    const float depth = glm::dot(offset, forward_);
    if (!(depth > near_) || !(depth > 0.0f)) return std::nullopt;
    const float distance2 = glm::dot(offset, offset);
    const float distance = std::sqrt(distance2);
    const float cosine = depth / distance;
    const float sx = glm::dot(offset, right_) / depth;
    const float sy = glm::dot(offset, up_) / depth;
    const Vec2 film(sx / pixel_scale_ + half_width_, half_height_ - sy / pixel_scale_);
    const float importance = 1.0f / (solid_angle_per_pixel(cosine) * distance2);
    return CameraConnection{film, -offset / distance, distance, distance - near_ / cosine,
                            importance};
  }

 private:
  /// The solid angle of the rays through one pixel's area of film at angle theta to the viewing
  /// direction (cos(theta) = `cosine`): p^2 cos^3(theta).
  float solid_angle_per_pixel(float cosine) const {
    return (pixel_scale_ * pixel_scale_) * (cosine * cosine * cosine);
  }

  Vec3 position_;
  Vec3 forward_{}, right_{}, up_{};
  float near_;
  float pixel_scale_ = 0.0f;
  float half_width_ = 0.0f, half_height_ = 0.0f;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
