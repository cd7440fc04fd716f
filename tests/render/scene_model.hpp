#pragma once
// An independent model of a scene for the shipped-scene property tests, in double precision:
// the pinhole camera, ray casting against the scene's spheres, the point-light formula with
// hard shadows, mirror reflection, Snell refraction with nested indices and the Fresnel
// equations. Everything here is written from the definitions (the scene file format, the
// camera's documented convention, textbook optics), not from glint's renderer, so that a test
// compares two separate derivations of the same image.
//
// Two uses:
//  - `expected_pixel`: the exact expectation and per-sample variance of a pixel for renders
//    whose every path ends before a random diffuse bounce: max_depth bounces of mirrors and
//    glass (Fresnel choices included, as weighted branches) ending on direct light.
//  - `seen_surface`: the diffuse surface a camera ray reaches through mirrors and glass (the
//    refracted path, ignoring Fresnel reflection): what a mirror or a glass sphere shows.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "../support/dielectric_fresnel.hpp"
#include "glint/scene/scene_description.hpp"

namespace glint::test {

using Vec3d = glm::dvec3;

inline Vec3d to_double(const Vec3& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

/// The report's eight-coloured sphere: the colour of each octant around the centre, indexed
/// by (x > 0) + 2 (y > 0) + 4 (z > 0). This is the specification of `shading=octants`.
inline constexpr std::array<std::array<double, 3>, 8> kOctantPalette{{{0.85, 0.15, 0.15},
                                                                      {0.15, 0.75, 0.20},
                                                                      {0.15, 0.30, 0.85},
                                                                      {0.90, 0.80, 0.15},
                                                                      {0.15, 0.80, 0.80},
                                                                      {0.80, 0.20, 0.80},
                                                                      {0.95, 0.95, 0.95},
                                                                      {0.95, 0.50, 0.10}}};

/// The octant of `offset` from a sphere's centre.
inline int octant_of(const Vec3d& offset) {
  return (offset.x > 0.0 ? 1 : 0) | (offset.y > 0.0 ? 2 : 0) | (offset.z > 0.0 ? 4 : 0);
}

/// A pinhole camera from its description: the image plane spans the vertical field of view
/// over `height` pixels, pixels are square, film coordinates run from (0, 0) at the top-left
/// corner of the image to (width, height) at the bottom-right one.
class Pinhole {
 public:
  Pinhole(const CameraDescription& camera, int width, int height)
      : eye_(to_double(camera.position)), width_(width), height_(height) {
    forward_ = glm::normalize(to_double(camera.look_at) - eye_);
    right_ = glm::normalize(glm::cross(forward_, to_double(camera.up)));
    up_ = glm::cross(right_, forward_);
    // The top edge of the image (film y = 0) is fov/2 above the viewing direction.
    pixel_ = 2.0 * std::tan(0.5 * double(camera.fov_degrees) * M_PI / 180.0) / height;
  }

  const Vec3d& eye() const { return eye_; }
  int width() const { return width_; }
  int height() const { return height_; }

  /// The unit direction through film point (fx, fy).
  Vec3d direction(double fx, double fy) const {
    return glm::normalize(forward_ + (fx - 0.5 * width_) * pixel_ * right_ +
                          (0.5 * height_ - fy) * pixel_ * up_);
  }

 private:
  Vec3d eye_, forward_{}, right_{}, up_{};
  int width_, height_;
  double pixel_ = 0.0;
};

/// First and second moments per channel of a random radiance estimate.
struct Moments {
  Vec3d mean{0.0};
  Vec3d second{0.0};  ///< E[X^2]

  static Moments constant(const Vec3d& value) { return {value, value * value}; }
  Moments scaled(const Vec3d& factor) const { return {mean * factor, second * factor * factor}; }
  /// X + Y for independent X and Y.
  Moments plus(const Moments& y) const {
    return {mean + y.mean, second + 2.0 * mean * y.mean + y.second};
  }
  /// X with probability p, otherwise Y.
  static Moments choice(double p, const Moments& x, const Moments& y) {
    return {p * x.mean + (1.0 - p) * y.mean, p * x.second + (1.0 - p) * y.second};
  }
};

/// How the renderer variant treats what the model must reproduce.
struct ModelOptions {
  bool fresnel = true;  ///< fully transparent spheres reflect with the Fresnel probability
};

struct Hit {
  int sphere = -1;
  double t = 0.0;
  Vec3d point{0.0};
  Vec3d outward{0.0};  ///< unit normal pointing out of the sphere
};

/// A diffuse surface seen through mirrors and glass.
struct SeenSurface {
  int sphere = -1;
  Vec3d point{0.0};
  Vec3d albedo_color{0.0};  ///< the surface's colour there (octant palette included)
  Vec3d filter{1.0};        ///< product of the mirror and glass colours along the way
  int specular_bounces = 0;
  bool through_glass = false;
  std::uint64_t key = 0;  ///< the spheres along the path and the octant reached
};

class SceneModel {
 public:
  explicit SceneModel(SceneDescription description) : d_(std::move(description)) {
    if (d_.camera.near != 0.0f) throw std::invalid_argument("scene model: near plane unsupported");
    for (const SphereDescription& s : d_.spheres)
      if (s.shading != ShadingKind::uniform && s.shading != ShadingKind::octants)
        throw std::invalid_argument("scene model: only uniform and octant shading");
    // The medium around each sphere: the index of the smallest transparent sphere that
    // contains it, or the scene's medium.
    outside_ior_.resize(d_.spheres.size(), double(d_.medium_ior));
    for (std::size_t i = 0; i < d_.spheres.size(); ++i) {
      double best_radius = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < d_.spheres.size(); ++j) {
        const SphereDescription& a = d_.spheres[i];
        const SphereDescription& b = d_.spheres[j];
        if (i == j || !(b.material.transparent > 0.0f) || !(b.radius > a.radius)) continue;
        const double gap = glm::length(to_double(a.center) - to_double(b.center)) + a.radius;
        if (gap <= double(b.radius) && double(b.radius) < best_radius) {
          best_radius = b.radius;
          outside_ior_[i] = b.material.ior;
        }
      }
    }
  }

  const SceneDescription& description() const { return d_; }

  /// Replaces the index of the medium around sphere `sphere` (to model a wrong hypothesis).
  void assume_outside_ior(int sphere, double ior) { outside_ior_[std::size_t(sphere)] = ior; }

  /// The nearest sphere along origin + t direction (unit), t in (t_min, t_max).
  std::optional<Hit> cast(const Vec3d& origin, const Vec3d& direction,
                          double t_max = std::numeric_limits<double>::infinity()) const {
    constexpr double kMinT = 1e-6;
    Hit best;
    best.t = t_max;
    for (std::size_t i = 0; i < d_.spheres.size(); ++i) {
      const Vec3d oc = origin - to_double(d_.spheres[i].center);
      const double r = d_.spheres[i].radius;
      const double b = glm::dot(oc, direction);
      // |oc|^2 - r^2 as (|oc| - r)(|oc| + r): exact enough near the surface of a huge sphere.
      const double distance = glm::length(oc);
      const double c = (distance - r) * (distance + r);
      const double discriminant = b * b - c;
      if (discriminant < 0.0) continue;
      // The two roots without cancellation: q = -b -+ sqrt, roots q and c / q.
      const double q = b > 0.0 ? -b - std::sqrt(discriminant) : -b + std::sqrt(discriminant);
      double t0 = q, t1 = q != 0.0 ? c / q : 0.0;
      if (t0 > t1) std::swap(t0, t1);
      const double t = t0 > kMinT ? t0 : t1;
      if (t > kMinT && t < best.t) {
        best.t = t;
        best.sphere = int(i);
      }
    }
    if (best.sphere < 0) return std::nullopt;
    best.point = origin + best.t * direction;
    best.outward = glm::normalize(best.point - to_double(d_.spheres[best.sphere].center));
    return best;
  }

  /// Irradiance from the point lights at `point`, on the side `facing` (unit normal), with
  /// hard shadows (any sphere blocks, glass too); `visible` gets a bit per unblocked light.
  Vec3d direct_irradiance(const Vec3d& point, const Vec3d& facing, unsigned& visible) const {
    Vec3d irradiance(0.0);
    visible = 0;
    for (std::size_t i = 0; i < d_.lights.size(); ++i) {
      const PointLight& light = d_.lights[i];
      const Vec3d to_light = to_double(light.position) - point;
      const double distance = glm::length(to_light);
      const Vec3d direction = to_light / distance;
      const double cosine = glm::dot(direction, facing);
      if (!(cosine > 0.0)) continue;
      if (cast(point, direction, distance)) continue;
      visible |= 1u << i;
      irradiance +=
          double(light.intensity) * cosine / (distance * distance) * to_double(light.color);
    }
    return irradiance;
  }

  /// The diffuse colour of sphere `sphere` at `point` (without the diffuse coefficient).
  Vec3d surface_color(int sphere, const Vec3d& point) const {
    const SphereDescription& s = d_.spheres[std::size_t(sphere)];
    Vec3d color = to_double(s.material.diffuse_color);
    if (s.shading == ShadingKind::octants) {
      const auto& p = kOctantPalette[std::size_t(octant_of(point - to_double(s.center)))];
      color *= Vec3d(p[0], p[1], p[2]);
    }
    return color;
  }

  /// Whether a ray can meet light where no point light is: an emissive sphere or a background.
  bool rays_find_light() const {
    if (d_.background != Color(0.0f)) return true;
    for (const SphereDescription& sphere : d_.spheres)
      if (sphere.material.emission != Color(0.0f)) return true;
    return false;
  }

  /// The expectation (and second moment) of one sample along a ray that has made `depth`
  /// bounces, for a render with `max_depth` (light after at most max_depth + 1 scattering
  /// vertices: a hit at depth max_depth + 1 only shows its emission); none when a random diffuse
  /// bounce would follow, whose value the model does not know: on a diffuse surface at depth
  /// below max_depth, and at max_depth too where a ray can find light (emissive spheres or a
  /// background), which a last bounce collects. `key`
  /// collects what the path met, so that a pixel whose neighbourhood meets the same things
  /// is known to vary smoothly.
  std::optional<Moments> radiance(const Vec3d& origin, const Vec3d& direction, int depth,
                                  int max_depth, const ModelOptions& options,
                                  std::uint64_t& key) const {
    const std::optional<Hit> hit = cast(origin, direction);
    if (!hit) {
      mix(key, 0xbacc);
      return Moments::constant(to_double(d_.background));
    }
    mix(key, std::uint64_t(hit->sphere) + 1);
    const SphereDescription& sphere = d_.spheres[std::size_t(hit->sphere)];
    const Material& m = sphere.material;
    const bool from_inside = glm::dot(direction, hit->outward) > 0.0;
    const Vec3d facing = from_inside ? -hit->outward : hit->outward;
    Moments result = Moments::constant(to_double(m.emission));
    if (depth > max_depth) return result;  // beyond the last scattering vertex
    if (m.diffuse > 0.0f) {
      if (depth < max_depth || rays_find_light())
        return std::nullopt;  // a diffuse bounce: unknown radiance
      unsigned visible = 0;
      const Vec3d irradiance = direct_irradiance(hit->point, facing, visible);
      mix(key, visible + 0x100u * unsigned(octant_key(*hit)));
      result = result.plus(Moments::constant(double(m.diffuse) / M_PI *
                                             surface_color(hit->sphere, hit->point) * irradiance));
    }
    if (m.mirror > 0.0f) {
      const std::optional<Moments> reflected =
          radiance(hit->point, reflect(direction, facing), depth + 1, max_depth, options, key);
      if (!reflected) return std::nullopt;
      result = result.plus(reflected->scaled(double(m.mirror) * to_double(m.mirror_color)));
    }
    if (m.transparent > 0.0f) {
      const auto [n1, n2] = indices(hit->sphere, from_inside);
      const std::optional<Vec3d> refracted = refract(direction, facing, n1 / n2);
      std::optional<Moments> through;
      if (!refracted) {
        mix(key, 0x7e1);  // total internal reflection
        through =
            radiance(hit->point, reflect(direction, facing), depth + 1, max_depth, options, key);
      } else {
        through = radiance(hit->point, *refracted, depth + 1, max_depth, options, key);
        if (through && options.fresnel && m.transparent == 1.0f) {
          const double f = glint_test::dielectric_fresnel(-glm::dot(direction, facing), n1, n2);
          const std::optional<Moments> reflected =
              radiance(hit->point, reflect(direction, facing), depth + 1, max_depth, options, key);
          if (!reflected) return std::nullopt;
          through = Moments::choice(f, *reflected, *through);
        }
      }
      if (!through) return std::nullopt;
      result = result.plus(through->scaled(double(m.transparent) * to_double(m.transparent_color)));
    }
    return result;
  }

  /// The diffuse surface a ray reaches through pure mirrors (no diffuse or transparent part)
  /// and pure glass (transparent=1), following the refracted ray through glass; none if it
  /// escapes, meets a surface mixing lobes, or bounces more than `max_bounces` times.
  std::optional<SeenSurface> seen_surface(Vec3d origin, Vec3d direction,
                                          int max_bounces = 8) const {
    SeenSurface seen;
    for (int bounce = 0; bounce <= max_bounces; ++bounce) {
      const std::optional<Hit> hit = cast(origin, direction);
      if (!hit) return std::nullopt;
      mix(seen.key, std::uint64_t(hit->sphere) + 1);
      const Material& m = d_.spheres[std::size_t(hit->sphere)].material;
      const bool from_inside = glm::dot(direction, hit->outward) > 0.0;
      const Vec3d facing = from_inside ? -hit->outward : hit->outward;
      const bool pure_diffuse = m.mirror == 0.0f && m.transparent == 0.0f && m.diffuse > 0.0f;
      const bool pure_mirror = m.mirror > 0.0f && m.diffuse == 0.0f && m.transparent == 0.0f;
      const bool pure_glass = m.transparent == 1.0f && m.diffuse == 0.0f && m.mirror == 0.0f;
      if (pure_diffuse) {
        if (m.emission != Color(0.0f)) return std::nullopt;
        seen.sphere = hit->sphere;
        seen.point = hit->point;
        seen.albedo_color = surface_color(hit->sphere, hit->point);
        mix(seen.key, 0x200u + unsigned(octant_key(*hit)));
        seen.specular_bounces = bounce;
        return seen;
      }
      if (pure_mirror) {
        seen.filter *= double(m.mirror) * to_double(m.mirror_color);
        direction = reflect(direction, facing);
      } else if (pure_glass) {
        const auto [n1, n2] = indices(hit->sphere, from_inside);
        const std::optional<Vec3d> refracted = refract(direction, facing, n1 / n2);
        seen.filter *= to_double(m.transparent_color);
        seen.through_glass = true;
        if (refracted) {
          direction = *refracted;
        } else {
          mix(seen.key, 0x7e1);
          direction = reflect(direction, facing);
        }
      } else {
        return std::nullopt;
      }
      origin = hit->point;
    }
    return std::nullopt;
  }

  /// The refractive indices on the incident and transmitted sides of sphere `sphere`.
  std::pair<double, double> indices(int sphere, bool from_inside) const {
    const double inside = d_.spheres[std::size_t(sphere)].material.ior;
    const double outside = outside_ior_[std::size_t(sphere)];
    return from_inside ? std::pair{inside, outside} : std::pair{outside, inside};
  }

  static Vec3d reflect(const Vec3d& direction, const Vec3d& facing) {
    return direction - 2.0 * glm::dot(direction, facing) * facing;
  }

  /// Snell's law for a unit direction arriving against the unit normal `facing`, with
  /// eta = n_incident / n_transmitted; none on total internal reflection.
  static std::optional<Vec3d> refract(const Vec3d& direction, const Vec3d& facing, double eta) {
    const double cos_i = -glm::dot(direction, facing);
    const double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0) return std::nullopt;
    return glm::normalize(eta * direction + (eta * cos_i - std::sqrt(1.0 - sin2_t)) * facing);
  }

 private:
  /// The octant a hit lands in, for octant-shaded spheres (their colour changes between
  /// octants); 0 for the others.
  int octant_key(const Hit& hit) const {
    return d_.spheres[std::size_t(hit.sphere)].shading == ShadingKind::octants
               ? 1 + octant_of(hit.outward)
               : 0;
  }

  static void mix(std::uint64_t& key, std::uint64_t value) {
    key = (key ^ value) * 0x100000001b3ull + 0x9e3779b97f4a7c15ull;
  }

  SceneDescription d_;
  std::vector<double> outside_ior_;
};

}  // namespace glint::test
