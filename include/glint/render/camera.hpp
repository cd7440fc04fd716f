#pragma once
// The camera: a pinhole, or a thin lens (an aperture of radius r focused at distance f) where the
// scene gives an aperture, or an equirectangular panorama of every direction around a point. Every
// estimator asks it the same things: a ray through a film point (from a point of the lens drawn
// from the sampler, with a lens), the density of a ray's direction, and for light paths where a
// scene point lands on the film, with the camera's importance there (connect).
//
// A thin lens is a pinhole at a lens point e drawn uniformly on the aperture, whose rays are
// bent to pass through the plane in focus where the central ray does: film point x sees along
// the ray from e through F(x), the central ray's point at depth f. So the density of a ray's
// direction from e, for a film point of density one per pixel, is the pinhole's formula in that
// direction (the film maps onto the plane in focus as it does through the centre), and the
// importance of a connection from e, divided by the lens point's density 1 / (pi r^2), is again
// the pinhole's formula from e: the lens's density cancels, and every strategy of a path draws
// e alike, so the bidirectional estimators' weights need no term for it. With no aperture the
// lens point is the centre, bit for bit the pinhole's arithmetic, and no value is drawn for it.
//
// The equirectangular camera maps film (x, y) to the direction of math/equirectangular.hpp at
// (x / width, y / height) in its frame (right, up, forward): the film's middle looks forward, its
// right half to the right, its top row up; the image it makes is what an environment lookup in
// the same frame reads back. A unit of film area there covers 2 pi^2 sin(theta) / (width
// height) of solid angle, theta the angle from up, and its rays start at distance `near`.

#include <cmath>
#include <optional>

#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/equirectangular.hpp"
#include "glint/math/sampling.hpp"
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
  /// With a lens, this is per lens point drawn (the lens's density divided out).
  float importance;
  /// The point of the lens the connection passes through: the camera's position for a pinhole.
  Vec3 lens_point;
};

/// The camera. Film coordinates are in pixels: (0,0) is the top-left corner of the image,
/// (width, height) the bottom-right one, so pixel (x, y) has its centre at (x + 0.5, y + 0.5).
class Camera {
 public:
  Camera(const CameraDescription& description, int width, int height)
      : position_(description.position),
        near_(description.near),
        lens_radius_(description.projection == Projection::perspective ? description.aperture
                                                                       : 0.0f),
        equirectangular_(description.projection == Projection::equirectangular),
        focus_(description.focus_distance > 0.0f
                   ? description.focus_distance
                   : glm::length(description.look_at - description.position)) {
    forward_ = glm::normalize(description.look_at - description.position);
    right_ = glm::normalize(glm::cross(forward_, description.up));
    up_ = glm::cross(right_, forward_);
    // glint's own sine and cosine, not the C library's tangent: every ray depends on it.
    float sin_half, cos_half;
    sincos(0.5f * description.fov_degrees * kPi / 180.0f, sin_half, cos_half);
    const float tan_half = sin_half / cos_half;
    pixel_scale_ = equirectangular_ ? kPi / static_cast<float>(height)
                                    : 2.0f * tan_half / static_cast<float>(height);
    half_width_ = 0.5f * static_cast<float>(width);
    half_height_ = 0.5f * static_cast<float>(height);
    // The solid angle of a unit of film area at sin(theta) = 1.
    panorama_solid_angle_ =
        2.0f * kPi * kPi / (static_cast<float>(width) * static_cast<float>(height));
  }

  /// Whether the camera is an equirectangular panorama (Projection::equirectangular): its film
  /// wraps around (panorama_direction).
  bool is_equirectangular() const { return equirectangular_; }

  /// Whether the camera has an aperture: its rays leave from points of the lens, drawn from the
  /// sampler (two values per ray and per connection).
  bool has_lens() const { return lens_radius_ > 0.0f; }
  float lens_radius() const { return lens_radius_; }
  /// The distance along the viewing direction of the plane in focus.
  float focus_distance() const { return focus_; }

  /// The central ray through film point `film`: the pinhole's, or a lens's through its centre.
  Ray ray_through(Vec2 film) const {
    Ray ray;
    ray.origin = position_;
    rays_through(film, ray.direction, ray.t_min);
    return ray;
  }

  /// A ray through film point `film`: with a lens, from the lens point of sample `sampler`'s
  /// next two values; without one, the central ray, drawing nothing.
  template <typename Sampler>
  Ray sample_ray(Vec2 film, Sampler& sampler) const {
    if (!has_lens()) return ray_through(film);
    Ray ray;
    rays_through(film, sampler.next_2d(), ray.origin, ray.direction, ray.t_min);
    return ray;
  }

  /// ray_through for a Float's lanes of film points at once (V2 is Vec2 or a Vector2 of
  /// lanes), the same bits in every lane: the directions and t_min (the origin is position()).
  template <typename V2>
  void rays_through(const V2& film, Vec3For<FloatOf<V2>>& direction, FloatOf<V2>& t_min) const {
    using V3 = Vec3For<FloatOf<V2>>;
    if (equirectangular_) {
      // Lane by lane, each lane one film point's arithmetic.
      for (int i = 0; i < kLanesOf<FloatOf<V2>>; ++i)
        set_lane(direction, i, panorama_direction(Vec2(lane(film.x, i), lane(film.y, i))));
      t_min = splat<FloatOf<V2>>(near_);
      return;
    }
    const FloatOf<V2> sx = (film.x - half_width_) * pixel_scale_;
    const FloatOf<V2> sy = (half_height_ - film.y) * pixel_scale_;
    const V3 forward = splat_vector<V3>(forward_);
    direction = normalize(forward + sx * splat_vector<V3>(right_) + sy * splat_vector<V3>(up_));
    // The clipping plane is perpendicular to the viewing direction, so the distance along a
    // ray grows as 1/cos of its angle to it.
    t_min = near_ / dot(direction, forward);
  }

  /// The rays through a Float's lanes of film points from the lens points of samples `lens` (in
  /// [0,1)^2, uniform on the aperture), the same bits in every lane: their origins on the lens,
  /// directions and t_min. Requires has_lens().
  template <typename V2>
  void rays_through(const V2& film, const V2& lens, Vec3For<FloatOf<V2>>& origin,
                    Vec3For<FloatOf<V2>>& direction, FloatOf<V2>& t_min) const {
    using V3 = Vec3For<FloatOf<V2>>;
    rays_through(film, direction, t_min);
    const V3 forward = splat_vector<V3>(forward_);
    // The central ray's point on the plane in focus, from the centre.
    const V3 focal = (focus_ / dot(direction, forward)) * direction;
    const V2 disc = sample_uniform_disc(lens);
    const V3 from_centre = (lens_radius_ * disc.x) * splat_vector<V3>(right_) +
                           (lens_radius_ * disc.y) * splat_vector<V3>(up_);
    origin = splat_vector<V3>(position_) + from_centre;
    direction = normalize(focal - from_centre);
    // The lens is in the plane of the centre, perpendicular to the viewing direction.
    t_min = near_ / dot(direction, forward);
  }

  const Vec3& position() const { return position_; }
  /// The size of a pixel on the plane at distance one in the viewing direction; for the
  /// panorama, the angle a pixel spans.
  float pixel_size() const { return pixel_scale_; }

  /// Density per unit solid angle of a ray in unit `direction` when its film point is drawn
  /// with density one per pixel area: 1 / (p^2 cos^3(theta)), p the size of a pixel on the plane
  /// at distance 1 and theta the angle to the viewing direction (zero behind the camera).
  float solid_angle_density(const Vec3& direction) const {
    if (equirectangular_) {
      const float across = glm::dot(direction, right_), ahead = glm::dot(direction, forward_);
      const float sine = std::sqrt(across * across + ahead * ahead);
      if (!(sine > 0.0f)) return 0.0f;
      return 1.0f / (panorama_solid_angle_ * sine);
    }
    const float cosine = glm::dot(direction, forward_);
    if (!(cosine > 0.0f)) return 0.0f;
    return 1.0f / solid_angle_per_pixel(cosine);
  }

  /// Where the camera sees `point` through the centre of its lens: none when it is behind the
  /// camera or not beyond the near plane (the camera's rays start there), the film position
  /// otherwise, on the film or not.
  std::optional<CameraConnection> connect(const Vec3& point) const {
    return connect_through(point, Vec2(0.0f));
  }

  /// connect, through the lens point of sample `sampler`'s next two values where the camera has
  /// a lens (drawing nothing otherwise).
  template <typename Sampler>
  std::optional<CameraConnection> connect(const Vec3& point, Sampler& sampler) const {
    if (!has_lens()) return connect(point);
    return connect_through(point, lens_radius_ * sample_uniform_disc(sampler.next_2d()));
  }

  /// Calls `visit` with each film point within `reach` of the film (beyond its edges by less)
  /// that shows the direction film point `film` shows: `film` itself for a perspective camera;
  /// for the panorama also the points a whole width round and those folded over a pole, mirrored
  /// in the top or bottom edge half a width round, as panorama_direction unfolds them.
  template <typename Visit>
  void film_images(Vec2 film, float reach, Visit&& visit) const {
    if (!equirectangular_) return visit(film);
    const float width = 2.0f * half_width_, height = 2.0f * half_height_;
    for (int fold = 0; fold < 2; ++fold) {
      const float y = fold == 0 ? film.y : -film.y;
      const float x = fold == 0 ? film.x : film.x + half_width_;
      for (float y_image = y - 2.0f * height * std::ceil((y + reach) / (2.0f * height));
           y_image < height + reach; y_image += 2.0f * height) {
        if (y_image <= -reach) continue;
        for (float x_image = x - width * std::ceil((x + reach) / width); x_image < width + reach;
             x_image += width)
          if (x_image > -reach) visit(Vec2(x_image, y_image));
      }
    }
  }

 private:
  /// connect through the lens point `disc` (along right and up) from the centre.
  std::optional<CameraConnection> connect_through(const Vec3& point, Vec2 disc) const {
    if (equirectangular_) return connect_panorama(point);
    const Vec3 lens_point = position_ + (disc.x * right_ + disc.y * up_);
    const Vec3 offset = point - lens_point;
    const float depth = glm::dot(offset, forward_);
    if (!(depth > near_) || !(depth > 0.0f)) return std::nullopt;
    const float distance2 = glm::dot(offset, offset);
    const float distance = std::sqrt(distance2);
    const float cosine = depth / distance;
    // Where the ray from the lens point through `point` meets the plane in focus, seen from the
    // centre (at depth one): the lens point's offset over f, plus the point's direction's.
    const float sx = disc.x / focus_ + glm::dot(offset, right_) / depth;
    const float sy = disc.y / focus_ + glm::dot(offset, up_) / depth;
    const Vec2 film(sx / pixel_scale_ + half_width_, half_height_ - sy / pixel_scale_);
    const float importance = 1.0f / (solid_angle_per_pixel(cosine) * distance2);
    return CameraConnection{film,       -offset / distance, distance, distance - near_ / cosine,
                            importance, lens_point};
  }

  /// The panorama's direction at film point `film`, on the film or off it (a pixel filter's
  /// offsets reach past the edges): the film is the sphere of directions, so its left and right
  /// edges meet and each of its top and bottom edges folds over a pole onto itself, half a turn
  /// round (film_images lists the film points so unfolded).
  Vec3 panorama_direction(Vec2 film) const {
    const float width = 2.0f * half_width_, height = 2.0f * half_height_;
    float y = film.y - 2.0f * height * std::floor(film.y / (2.0f * height));  // [0, 2 height)
    float x = film.x;
    if (y > height) {
      y = 2.0f * height - y;
      x += half_width_;
    }
    x -= width * std::floor(x / width);  // [0, width)
    const Vec3 d = equirectangular_direction(Vec2(x / width, std::fmin(y / height, 1.0f)));
    return glm::normalize(d.x * right_ + d.y * up_ + d.z * forward_);
  }

  /// connect for the panorama: any direction, beyond `near`.
  std::optional<CameraConnection> connect_panorama(const Vec3& point) const {
    const Vec3 offset = point - position_;
    const float distance2 = glm::dot(offset, offset);
    const float distance = std::sqrt(distance2);
    if (!(distance > near_) || !(distance > 0.0f)) return std::nullopt;
    const Vec3 direction = offset / distance;
    const Vec2 uv = equirectangular_uv(
        Vec3(glm::dot(direction, right_), glm::dot(direction, up_), glm::dot(direction, forward_)));
    const float density = solid_angle_density(direction);
    if (!(density > 0.0f)) return std::nullopt;
    return CameraConnection{Vec2(uv.x * 2.0f * half_width_, uv.y * 2.0f * half_height_),
                            -direction,
                            distance,
                            distance - near_,
                            density / distance2,
                            position_};
  }

  /// The solid angle of the rays through one pixel's area of film at angle theta to the viewing
  /// direction (cos(theta) = `cosine`): p^2 cos^3(theta).
  float solid_angle_per_pixel(float cosine) const {
    return (pixel_scale_ * pixel_scale_) * (cosine * cosine * cosine);
  }

  Vec3 position_;
  Vec3 forward_{}, right_{}, up_{};
  float near_;
  float lens_radius_;
  bool equirectangular_;
  float panorama_solid_angle_ = 0.0f;
  float focus_;
  float pixel_scale_ = 0.0f;
  float half_width_ = 0.0f, half_height_ = 0.0f;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
