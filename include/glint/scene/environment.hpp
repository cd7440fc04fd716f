#pragma once
// The light that reaches a ray escaping the scene: a constant colour (black unless the scene
// gives one) or an equirectangular image around the scene, seen from inside. The image is laid
// out as glint's equirectangular camera films it (render/camera.hpp): a panorama rendered with
// the camera at the origin looking along +z with up +y lights a scene as that scene saw it, with
// the default placement. Its directions can be drawn in proportion to its light (sample, pdf),
// from a piecewise-constant table over the image (math/piecewise_constant.hpp), and uniformly
// over the sphere for a colour.
//
// Units: radiance, W / (m^2 sr). A direction points from the scene towards where the light comes
// from: an escaping ray's own direction.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "glint/image/texture.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/equirectangular.hpp"
#include "glint/math/piecewise_constant.hpp"
#include "glint/math/sampling.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"
#include "glint/scene/emitters.hpp"
#include "glint/scene/sphere_texture.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class Environment {
 public:
  /// A direction drawn by sample(): unit `direction`, at `uv` on the image, with density `pdf`
  /// per unit solid angle.
  struct DirectionSample {
    Vec3 direction;
    Vec2 uv;
    float pdf;
  };
  /// What a direction finds: the radiance from it and the density with which sample() gives it.
  struct Found {
    Color radiance;
    float pdf;
  };

  /// Black.
  Environment() = default;
  /// The same radiance `color` from every direction.
  explicit Environment(const Color& color) : color_(color) {}
  /// `image` around the scene, its top edge towards placement.axis and turned by
  /// placement.turn_degrees about it (counterclockwise seen from above), each texel times `scale`
  /// (finite, non-negative). The axis must be finite and not zero (validation says so with the
  /// line).
  Environment(std::shared_ptr<const Texture> image, const TexturePlacement& placement, float scale)
      : image_(std::make_shared<const SphereTexture>(std::move(image), placement)), scale_(scale) {
    build_distribution();
  }

  bool has_image() const { return image_ != nullptr; }
  /// The image and its frame; requires has_image().
  const SphereTexture& image() const { return *image_; }
  float scale() const { return scale_; }
  /// The constant radiance of an environment without an image.
  const Color& color() const { return color_; }
  /// Whether no direction brings light.
  bool is_black() const {
    return has_image() ? !(scale_ > 0.0f) || !(mean_ > 0.0)
                       : color_.r == 0.0f && color_.g == 0.0f && color_.b == 0.0f;
  }

  /// Where unit direction `d` meets the image: (u, v) as the equirectangular camera films it,
  /// u growing to the right of the image's middle for a viewer inside.
  Vec2 uv(const Vec3& d) const {
    const SphereTexture& frame = *image_;
    return equirectangular_uv(
        {-glm::dot(d, frame.east()), glm::dot(d, frame.north()), glm::dot(d, frame.front())});
  }
  /// The unit direction at (u, v): the inverse of uv().
  Vec3 direction(const Vec2& uv) const { return to_world(equirectangular_direction(uv)); }

  /// The radiance arriving from unit direction `d`.
  Color radiance(const Vec3& d) const {
    if (!image_) return color_;
    return radiance_at(uv(d));
  }
  /// The radiance at (u, v) of the image (the colour, without one).
  Color radiance_at(const Vec2& uv) const {
    if (!image_) return color_;
    return scale_ * image_->image().filtered(uv.x, uv.y);
  }
  /// radiance(d) and pdf(d), the map computed once.
  Found find(const Vec3& d) const {
    if (!image_) return {color_, kUniformPdf};
    const Vec2 at = uv(d);
    return {radiance_at(at), pdf_at(d, at)};
  }
  /// The radiance from each of a Float's lanes of unit directions, for the lanes of `lanes`
  /// (zero elsewhere where there is an image): lane by lane, the same bits as radiance(d).
  template <typename F>
  Vec3For<F> radiance(MaskFor<F> lanes, const Vec3For<F>& d) const {
    using V3 = Vec3For<F>;
    if constexpr (kLanesOf<F> == 1) {
      return lanes ? radiance(d) : Color(0.0f);
    } else {
      if (!image_) return splat_vector<V3>(color_);
      V3 result = splat_vector<V3>(Color(0.0f));
      for (int i = 0; i < kLanesOf<F>; ++i)
        if (lane(lanes, i)) set_lane(result, i, radiance(lane(d, i)));
      return result;
    }
  }

  /// A direction drawn in proportion to the image's light by two uniform numbers, with its
  /// density: the table's density at the drawn point of the image's square over the solid angle
  /// per unit area of the square there, 2 pi^2 sin(theta). That is pdf(direction) but where
  /// rounding moves the direction across a texel's edge. Without an image, uniform over the
  /// sphere of directions.
  DirectionSample sample(const Vec2& u) const {
    if (!image_) return {sample_uniform_sphere(u), Vec2(0.0f), kUniformPdf};
    const PiecewiseConstant2D::Sample drawn = distribution_.sample(u);
    const Vec3 local = equirectangular_direction(drawn.uv);
    const float sine = std::sqrt(local.x * local.x + local.z * local.z);
    return {to_world(local), drawn.uv,
            sine > 0.0f ? drawn.pdf / (kTwoPiSquared * std::min(sine, 1.0f)) : 0.0f};
  }
  /// The density per unit solid angle with which sample() gives unit direction `d`, zero at the
  /// poles of an image.
  float pdf(const Vec3& d) const { return image_ ? pdf_at(d, uv(d)) : kUniformPdf; }

  /// The mean radiance over all directions (of the channels' mean), in double.
  double mean_radiance() const {
    if (!image_) return channel_mean(color_);
    return mean_;
  }

 private:
  /// The table sample() draws from: each texel's weight the largest channel mean among the
  /// texels whose filtering can reach into its cell (its 3 x 3 neighbourhood, wrapped in u,
  /// clamped at the poles), so that a direction that brings light has a density; times the
  /// sine of its row's polar angle, the solid angle its cell spans.
  void build_distribution() {
    const Texture& texture = image_->image();
    const int width = texture.width(), height = texture.height();
    std::vector<double> means(texture.texels().size());
    for (std::size_t i = 0; i < means.size(); ++i)
      means[i] = channel_mean(texture.texels()[i]);
    const auto mean_at = [&](int x, int y) {
      return means[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    };
    std::vector<double> weights(std::size_t(width) * std::size_t(height));
    double sum = 0.0, solid_angle = 0.0;
    for (int y = 0; y < height; ++y) {
      float sine = 0.0f, cosine = 0.0f;
      sincos(kPi * (float(y) + 0.5f) / float(height), sine, cosine);
      for (int x = 0; x < width; ++x) {
        double largest = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            largest = std::max(
                largest, mean_at((x + dx + width) % width, std::clamp(y + dy, 0, height - 1)));
        weights[std::size_t(y) * std::size_t(width) + std::size_t(x)] = largest * double(sine);
        sum += mean_at(x, y) * double(sine);
      }
      solid_angle += double(width) * double(sine);
    }
    mean_ = double(scale_) * sum / solid_angle;
    distribution_ = PiecewiseConstant2D(weights, std::size_t(width), std::size_t(height));
  }

  static constexpr float kTwoPiSquared = 2.0f * kPi * kPi;
  static constexpr float kUniformPdf = 0.25f * kInvPi;

  /// A direction of the image's frame (equirectangular_uv's axes, u mirrored) in the scene's.
  Vec3 to_world(const Vec3& local) const {
    const SphereTexture& frame = *image_;
    return glm::normalize(-local.x * frame.east() + local.y * frame.north() +
                          local.z * frame.front());
  }
  /// pdf(d) for unit direction `d` at `at` = uv(d).
  float pdf_at(const Vec3& d, const Vec2& at) const {
    const SphereTexture& frame = *image_;
    const float east = glm::dot(d, frame.east()), front = glm::dot(d, frame.front());
    // sin(theta) from the components across the pole, which keep their precision near it.
    const float sine = std::sqrt(east * east + front * front);
    if (!(sine > 0.0f)) return 0.0f;
    return distribution_.pdf(at) / (kTwoPiSquared * std::min(sine, 1.0f));
  }

  Color color_{0.0f};
  /// Null for a colour. Shared rather than optional: the placed image never changes, and an
  /// empty std::optional of it trips GCC 12's -Wmaybe-uninitialized where it is destroyed.
  std::shared_ptr<const SphereTexture> image_;
  float scale_ = 1.0f;
  double mean_ = 0.0;
  PiecewiseConstant2D distribution_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
