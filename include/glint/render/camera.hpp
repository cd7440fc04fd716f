#pragma once

#include <cmath>

#include "glint/geometry/ray.hpp"
#include "glint/math/lanes.hpp"
#include "glint/scene/scene_description.hpp"

namespace glint {

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
    const float tan_half = std::tan(0.5f * description.fov_degrees * kPi / 180.0f);
    pixel_scale_ = 2.0f * tan_half / static_cast<float>(height);
    half_width_ = 0.5f * static_cast<float>(width);
    half_height_ = 0.5f * static_cast<float>(height);
  }

  Ray ray_through(Vec2 film) const {
    const float sx = (film.x - half_width_) * pixel_scale_;
    const float sy = (half_height_ - film.y) * pixel_scale_;
    Ray ray;
    ray.origin = position_;
    ray.direction = glm::normalize(forward_ + sx * right_ + sy * up_);
    // The clipping plane is perpendicular to the viewing direction, so the distance along a
    // ray grows as 1/cos of its angle to it.
    ray.t_min = near_ / glm::dot(ray.direction, forward_);
    return ray;
  }

#if defined(GLINT_AVX2)
  /// ray_through for eight film points: the directions and t_min (the origin is position()).
  void rays_through(const Vec2Lanes& film, Vec3Lanes& direction, FloatLanes& t_min) const {
    const FloatLanes sx = (film.x - half_width_) * pixel_scale_;
    const FloatLanes sy = (half_height_ - film.y) * pixel_scale_;
    direction = normalize(Vec3Lanes::broadcast(forward_) + sx * Vec3Lanes::broadcast(right_) +
                          sy * Vec3Lanes::broadcast(up_));
    t_min = near_ / dot(direction, Vec3Lanes::broadcast(forward_));
  }
#endif
  const Vec3& position() const {
    return position_;
  }

 private:
  Vec3 position_;
  Vec3 forward_{}, right_{}, up_{};
  float near_;
  float pixel_scale_ = 0.0f;
  float half_width_ = 0.0f, half_height_ = 0.0f;
};

}  // namespace glint
