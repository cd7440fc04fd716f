#pragma once
// An image texture as it lies on a sphere: the image (image/texture.hpp) wrapped around it by
// the equirectangular map (math/equirectangular.hpp), its north pole along an axis and turned
// about it by an angle.

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "glint/image/texture.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/equirectangular.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// How an image is placed on a sphere: its top edge (the north pole) towards `axis`, and turned
/// by `turn_degrees` about it, counterclockwise seen from above the pole. With the defaults the
/// pole is +y and the middle of the image faces +z, the default camera.
struct TexturePlacement {
  Vec3 axis{0.0f, 1.0f, 0.0f};  ///< finite, of any length but zero
  float turn_degrees = 0.0f;    ///< finite
};

class SphereTexture {
 public:
  /// `image` placed by `placement`; the axis must be finite and not zero (the scene's validation
  /// says so with the line).
  SphereTexture(std::shared_ptr<const Texture> image, const TexturePlacement& placement)
      : image_(std::move(image)) {
    // The rotation that takes +y to the axis along the great circle between them, applied to the
    // default middle of the image (+z); an axis of -y takes the half turn about x.
    // Scaled by its largest component first, so that neither a huge nor a tiny axis leaves
    // float's range on its way to unit length.
    const Vec3& axis = placement.axis;
    const float largest = std::max({std::abs(axis.x), std::abs(axis.y), std::abs(axis.z)});
    north_ = glm::normalize(axis / largest);
    const float n_x = north_.x, n_y = north_.y, n_z = north_.z;
    Vec3 front = n_y > -1.0f + 1e-6f
                     ? Vec3(-n_x * n_z / (1.0f + n_y), -n_z, 1.0f - n_z * n_z / (1.0f + n_y))
                     : Vec3(0.0f, 0.0f, -1.0f);
    front = glm::normalize(front - glm::dot(front, north_) * north_);
    const Vec3 east = glm::cross(north_, front);
    // The turn, reduced to [0, 360) degrees exactly before it becomes an angle for sincos.
    float degrees = std::fmod(placement.turn_degrees, 360.0f);
    if (degrees < 0.0f) degrees += 360.0f;
    float sine = 0.0f, cosine = 1.0f;
    sincos(degrees * (kPi / 180.0f), sine, cosine);
    front_ = cosine * front + sine * east;
    east_ = cosine * east - sine * front;
  }

  const Texture& image() const { return *image_; }
  const std::shared_ptr<const Texture>& shared_image() const { return image_; }
  /// The frame the image is wrapped in: +y of equirectangular_uv is north(), +z front(), +x
  /// east().
  const Vec3& north() const { return north_; }
  const Vec3& front() const { return front_; }
  const Vec3& east() const { return east_; }

  /// Where unit direction `d` from the centre meets the image.
  Vec2 uv(const Vec3& d) const {
    return equirectangular_uv({glm::dot(d, east_), glm::dot(d, north_), glm::dot(d, front_)});
  }
  /// The image's colour at unit direction `d` from the centre, filtered bilinearly.
  Color color(const Vec3& d) const {
    const Vec2 at = uv(d);
    return image_->filtered(at.x, at.y);
  }

 private:
  std::shared_ptr<const Texture> image_;
  Vec3 north_, front_, east_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
