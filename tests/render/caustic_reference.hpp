#pragma once
// The caustic of a glass ball under a point light, worked out independently of the renderer: a
// point light on the axis above a glass ball above a grey floor, and the floor's irradiance from
// a deterministic fan of rays through and off the ball with its own ray-sphere and Fresnel
// arithmetic. Shared by the estimators that see caustics (light tracing, bidirectional).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "../support/dielectric_fresnel.hpp"
#include "block_statistics.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/policy/antialiasing.hpp"
#include "glint/render/camera.hpp"
#include "glint/scene/scene.hpp"

namespace caustic_reference {

// A point light on the axis above a glass ball above a grey floor; the camera looks at the floor
// from the side, under the ball. max_depth 2 lets the point light's paths have three vertices
// (light, glass in, glass out, floor, camera): the floor's direct light, the light the ball
// reflects onto it and the light refracted through it without an internal reflection, which is
// what the fan below follows. The camera, below the ball, sees only the floor, within 4.5 of
// the axis.
inline constexpr float kBallHeight = 3.0f, kBallRadius = 1.0f, kIor = 1.5f;
inline constexpr float kLightHeight = 10.0f, kIntensity = 200.0f, kAlbedo = 0.5f;
inline constexpr const char* kCaustic = R"(
image     width=16 height=16 spp=1024 max_depth=2
camera    position=0,1.5,3.5 look_at=0,0,0 up=0,1,0 fov=24
antialias sigma=0.5
light     position=0,10,0 intensity=200
sphere    center=0,-100000,0 radius=1e5 color=0.5,0.5,0.5
sphere    center=0,3,0 radius=1 diffuse=0 transparent=1 ior=1.5
)";

using glint_test::dielectric_fresnel;

struct D3 {
  double x, y, z;
};
inline D3 operator+(D3 a, D3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline D3 operator-(D3 a, D3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline D3 operator*(double s, D3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline double dot(D3 a, D3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline D3 unit(D3 a) {
  return (1.0 / std::sqrt(dot(a, a))) * a;
}

/// The floor's irradiance from the light, as a function of the distance r from the axis: the
/// direct light where the ball does not shadow it, plus the flux of a fan of rays through and
/// off the ball (entry Fresnel, refraction in and out, exit Fresnel; a ray that reflects inside
/// is dropped, as such paths are longer than max_depth allows), binned by r.
class FloorIrradiance {
 public:
  static constexpr double kMaxRadius = 8.0;
  static constexpr int kBins = 4000;

  FloorIrradiance() : flux_(kBins, 0.0) {
    const D3 light{0.0, kLightHeight, 0.0}, center{0.0, kBallHeight, 0.0};
    const double d = kLightHeight - kBallHeight;
    const double cos_max = std::sqrt(1.0 - (kBallRadius / d) * (kBallRadius / d));
    // Rays uniform in solid angle in the ball's cone, one azimuth (the scene is symmetric):
    // each carries intensity x solid angle of its ring, 2 pi (1 - cos_max) / rays in all.
    constexpr int kRays = 8000000;
    const double ray_solid_angle = 2.0 * M_PI * (1.0 - cos_max) / kRays;
    for (int i = 0; i < kRays; ++i) {
      const double cos_theta = 1.0 - (1.0 - cos_max) * (i + 0.5) / kRays;
      const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
      const D3 dir{sin_theta, -cos_theta, 0.0};
      const double power = kIntensity * ray_solid_angle;
      // Entry.
      double t;
      if (!hit_sphere(light, dir, center, t, false)) continue;
      const D3 p = light + t * dir;
      const D3 n = unit(p - center);
      const double cos_i = -dot(dir, n);
      const double reflect = dielectric_fresnel(cos_i, 1.0, kIor);
      land(p, dir + (2.0 * cos_i) * n, power * reflect);
      const D3 in = refract(dir, n, cos_i, 1.0 / kIor);
      // Exit.
      if (!hit_sphere(p, in, center, t, true)) continue;
      const D3 q = p + t * in;
      const D3 m = unit(center - q);  // the normal facing the ray, inside
      const double cos_j = -dot(in, m);
      const double exit_reflect = dielectric_fresnel(cos_j, kIor, 1.0);
      if (exit_reflect >= 1.0) continue;
      land(q, refract(in, m, cos_j, kIor), power * (1.0 - reflect) * (1.0 - exit_reflect));
    }
    cos_shadow_ = cos_max;
  }

  /// Irradiance at distance r from the axis on the floor.
  double at(double r) const {
    const double d2 = r * r + double(kLightHeight) * kLightHeight;
    const double cos_floor = kLightHeight / std::sqrt(d2);
    // The direct light unless the ray from the light meets the ball: its angle to the axis
    // is within the ball's cone.
    const double direct = cos_floor > cos_shadow_ ? 0.0 : kIntensity * cos_floor / d2;
    const int bin = std::min(kBins - 1, int(r / kMaxRadius * kBins));
    const double r0 = kMaxRadius * bin / kBins, r1 = kMaxRadius * (bin + 1) / kBins;
    return direct + flux_[std::size_t(bin)] / (M_PI * (r1 * r1 - r0 * r0));
  }

 private:
  static bool hit_sphere(D3 origin, D3 dir, D3 center, double& t, bool inside) {
    const D3 oc = origin - center;
    const double b = dot(oc, dir);
    const double c = dot(oc, oc) - double(kBallRadius) * kBallRadius;
    const double disc = b * b - c;
    if (disc < 0.0) return false;
    t = inside ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
    return t > 0.0;
  }
  static D3 refract(D3 dir, D3 n, double cos_i, double eta) {
    const double k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    return unit(eta * dir + (eta * cos_i - std::sqrt(k)) * n);
  }
  /// The flux `power` leaving `from` along `dir`: onto the floor (y = 0) if it goes down.
  void land(D3 from, D3 dir, double power) {
    if (dir.y >= 0.0) return;
    const double t = -from.y / dir.y;
    // The azimuth is symmetric: the ray stands for its whole ring, so only |x| matters.
    const double r = std::abs(from.x + t * dir.x);
    if (r < kMaxRadius) flux_[std::size_t(r / kMaxRadius * kBins)] += power;
  }

  std::vector<double> flux_;
  double cos_shadow_ = 1.0;
};

/// The expected mean radiance of each block of kCaustic's image (and of the whole image) rendered
/// at the block statistics' size, with the Gaussian pixel filter or through pixel centres.
inline std::array<double, glint_test::kBlocks + 1> expected_blocks(const glint::Scene& scene,
                                                                   bool pixel_centres = false) {
  // The expected radiance of each pixel: albedo / pi x irradiance, averaged over the pixel
  // filter (the normal density of sigma 0.5 pixels, to the 5.77 sigmas its offsets reach) by a
  // 48 x 48 quadrature of offsets.
  const FloorIrradiance irradiance;
  const glint::Camera camera(scene.camera(), glint_test::kBlockImageSize,
                             glint_test::kBlockImageSize);
  std::array<double, glint_test::kBlocks + 1> expected{};
  const int kSteps = pixel_centres ? 1 : 48;
  const double kReach = pixel_centres ? 0.0 : glint::GaussianAntialiasing::kLargestRadius;
  double weights = 0.0;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const double ox = (-1.0 + 2.0 * (i + 0.5) / kSteps) * kReach,
                   oy = (-1.0 + 2.0 * (j + 0.5) / kSteps) * kReach;
      weights += std::exp(-0.5 * (ox * ox + oy * oy));
    }
  for (int y = 0; y < glint_test::kBlockImageSize; ++y)
    for (int x = 0; x < glint_test::kBlockImageSize; ++x) {
      double pixel = 0.0;
      for (int i = 0; i < kSteps; ++i)
        for (int j = 0; j < kSteps; ++j) {
          const double ox = (-1.0 + 2.0 * (i + 0.5) / kSteps) * kReach,
                       oy = (-1.0 + 2.0 * (j + 0.5) / kSteps) * kReach;
          const glint::Ray ray =
              camera.ray_through(glint::Vec2(float(x + 0.5 + 0.5 * ox), float(y + 0.5 + 0.5 * oy)));
          REQUIRE(ray.direction.y < 0.0f);  // every ray meets the floor, none the ball
          const double t = -double(ray.origin.y) / ray.direction.y;
          const double px = ray.origin.x + t * ray.direction.x,
                       pz = ray.origin.z + t * ray.direction.z;
          pixel +=
              std::exp(-0.5 * (ox * ox + oy * oy)) * irradiance.at(std::sqrt(px * px + pz * pz));
        }
      // Three channels of albedo / pi x irradiance.
      const double radiance = 3.0 * kAlbedo / M_PI * pixel / weights;
      expected[std::size_t((y / glint_test::kBlock) * glint_test::kBlocksPerSide +
                           x / glint_test::kBlock)] +=
          radiance / (glint_test::kBlock * glint_test::kBlock);
      expected[glint_test::kWholeImage] +=
          radiance / (glint_test::kBlockImageSize * glint_test::kBlockImageSize);
    }

  return expected;
}

/// The rendered blocks against the fan's values times `scale`, one comparison per block; `name`
/// names the estimator. The fan's own error is allowed as 0.5% of its value: its bins and
/// quadrature, and the light the ball reflects back onto the floor from the floor (a path of
/// three vertices that it does not follow, about 0.1%).
inline glint_test::ComparisonFamily compare(
    const glint_test::BlockSamples& rendered,
    const std::array<double, glint_test::kBlocks + 1>& expected, double scale,
    const std::string& name) {
  glint_test::ComparisonFamily family;
  for (std::size_t b = 0; b <= glint_test::kBlocks; ++b) {
    const glint_test::MeanEstimate r = glint_test::estimate_mean(rendered.per_seed[b]);
    const double fan = scale * expected[b];
    std::ostringstream line;
    line << "caustic, " << glint_test::block_name(b) << ": fan of rays " << fan << ", " << name
         << " " << r.mean << " +- " << r.standard_error;
    glint_test::MeanEstimate difference = r;
    difference.mean = r.mean - fan;
    family.add(line.str(), glint_test::zero_mean_p_value(difference, 0.005 * fan));
  }
  return family;
}

/// Renders kCaustic with renderer R (seeds from `first_seed`) and checks its blocks against the
/// fan's values; and that the same comparison with the fan's values 5% higher is rejected, so
/// that the test has the power to see a bias of that size. `name` names the estimator.
template <typename R>
void check_caustic(std::uint64_t first_seed, const std::string& name, bool pixel_centres = false) {
  const glint::Scene scene = glint::Scene::build(glint::read_scene_text(kCaustic, "caustic"));
  const glint_test::BlockSamples rendered =
      glint_test::render_blocks<R>(scene, first_seed, glint::RenderSettings::from(scene));
  const auto expected = expected_blocks(scene, pixel_centres);
  compare(rendered, expected, 1.0, name).check();
  CHECK_FALSE(compare(rendered, expected, 1.05, name).rejected().empty());
}

}  // namespace caustic_reference
