// Huge spheres near the camera: a floor of radius 1e3 to 1e10 (the largest the scene
// format accepts) under a camera 1e-3 to 1e3 above it, against the analytic answer: rays from
// the camera meet the exact sphere (solved in long double), which is the plane h / -d.y where
// the curvature is negligible, and rays pointing up miss; a camera 1e-3 above the report's room
// floor does not see through it; and a render of a floor lit by a point light gives the
// point-light formula. Shading's normal there is exact to a few float roundings.

#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <vector>

#include "../support/float_values.hpp"
#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"

using glint::Color;
using glint::Vec3;

namespace {

using glint_test::kDegree;

using Long = long double;
constexpr double kUnitRoundoff = 0x1p-24;

const std::vector<float>& floor_radii() {
  static const std::vector<float> radii = {1e3f, 1e4f, 1e5f, 1e6f, 1e7f, 1e8f, 1e9f, 1e10f};
  return radii;
}
const std::vector<float>& camera_heights() {
  static const std::vector<float> heights = {1e-3f, 1e-2f, 1e-1f, 1.0f, 1e1f, 1e2f, 1e3f};
  return heights;
}

/// A floor: the sphere of radius r centred at (0, -r, 0), exactly representable, whose top is
/// the plane y = 0; the camera at height h above it, looking down at 45 degrees.
glint::SceneDescription floor_scene(float radius, float height) {
  glint::SceneDescription scene;
  scene.source = "huge floor";
  scene.camera.position = {0.0f, height, 0.0f};
  scene.camera.look_at = {0.0f, 0.0f, -height};
  scene.background = Color(0.0f);
  glint::SphereDescription floor;
  floor.center = {0.0f, -radius, 0.0f};
  floor.radius = radius;
  floor.line = 10;
  scene.spheres.push_back(floor);
  return scene;
}

/// Where a ray from (0, h, 0) meets the floor of radius r, solved in long double from the
/// floats: |o + t d - c|^2 = r^2 with o - c = (0, h + r, 0), whose constant term
/// |o - c|^2 - r^2 = h (h + 2r) is formed without cancellation. Nothing if it misses, or if the
/// ray is so nearly tangent that float rounding may decide.
std::optional<double> exact_floor_distance(float radius, float height, const Vec3& d) {
  const Long r = radius, h = height;
  const Long dd = Long(d.x) * d.x + Long(d.y) * d.y + Long(d.z) * d.z;
  const Long b = (h + r) * d.y;
  const Long c = h * (h + 2 * r);
  const Long discriminant = b * b - dd * c;
  if (discriminant <= 1e-4L * b * b) return std::nullopt;
  const Long q = -(b + std::copysign(std::sqrt(discriminant), b));
  const Long near = std::min(c / q, q / dd);
  return near > 0 ? std::optional<double>(double(near)) : std::nullopt;
}

/// Downward directions at `degrees` below the horizon, around the vertical.
std::vector<Vec3> directions_below_horizon(double degrees) {
  std::vector<Vec3> directions;
  for (int k = 0; k < 8; ++k) {
    const double phi = (45.0 * k + 10.0) * kDegree;
    const double a = degrees * kDegree;
    directions.push_back(
        glm::normalize(Vec3(float(std::cos(a) * std::cos(phi)), float(-std::sin(a)),
                            float(std::cos(a) * std::sin(phi)))));
  }
  return directions;
}

}  // namespace

TEST_CASE("huge floors: rays from the camera meet the analytic plane, rays up miss",
          "[render][huge_sphere]") {
  int plane_comparisons = 0, sphere_comparisons = 0;
  double worst_plane = 0.0, worst_sphere = 0.0;
  for (const float radius : floor_radii()) {
    for (const float height : camera_heights()) {
      const glint::Scene scene = glint::Scene::build(floor_scene(radius, height));
      for (const double degrees : {90.0, 60.0, 30.0, 10.0, 3.0, 1.0}) {
        for (const Vec3& d : directions_below_horizon(degrees)) {
          glint::Ray ray;
          ray.origin = {0.0f, height, 0.0f};
          ray.direction = d;
          const std::optional<glint::SphereHit> hit = scene.closest_hit(ray);
          const std::optional<double> exact = exact_floor_distance(radius, height, d);
          INFO("radius " << radius << ", camera " << height << " above, " << degrees
                         << " degrees down; exact " << exact.value_or(-1.0) << ", got "
                         << (hit ? hit->t : -1.0f));
          if (!exact) {
            // Past the horizon of a small floor seen from high up: the ray misses the sphere.
            if (height < 1e-4f * radius) FAIL("a floor much larger than the height was missed");
            continue;
          }
          REQUIRE(hit);
          CHECK(hit->sphere == 0u);
          CHECK(scene.occluded(ray));
          // Shading's normal, normalize(point - centre) in float, is exact to a few u: each
          // component of point - centre is rounded relative to the radius.
          const glm::dvec3 exact_point = glm::dvec3(ray.origin) + *exact * glm::dvec3(d);
          const glm::dvec3 exact_normal =
              (exact_point - glm::dvec3(0.0, -double(radius), 0.0)) / double(radius);
          const glint::SurfaceHit surface = scene.surface_hit(ray, *hit);
          CHECK(glm::length(glm::dvec3(surface.outward_normal) - exact_normal) <=
                8.0 * kUnitRoundoff);
          // Float's error model for the anchored kernel: a few u relative to t, grown by the
          // obliquity (1 / sin of the angle to the surface, at most 57 at 1 degree): 16 u /
          // sin(angle) is 1e-6 straight down and 5.5e-5 at one degree.
          const double sine = -double(d.y) / glm::length(glm::dvec3(d));
          const double tolerance = 16.0 * kUnitRoundoff / sine;
          const double sphere_error = std::abs(hit->t - *exact) / *exact;
          worst_sphere = std::max(worst_sphere, sphere_error / tolerance);
          CHECK(sphere_error <= tolerance);
          ++sphere_comparisons;
          // The plane y = 0 is the answer where the floor's drop at the hit, about
          // (horizontal distance)^2 / 2r, is below 1e-6 of the height.
          const double plane = double(height) / -double(d.y);
          const double horizontal = plane * std::sqrt(1.0 - sine * sine);
          if (horizontal * horizontal / (2.0 * radius) > 1e-6 * height) continue;
          const double plane_error = std::abs(hit->t - plane) / plane;
          worst_plane = std::max(worst_plane, plane_error / (tolerance + 2e-6));
          CHECK(plane_error <= tolerance + 2e-6);
          ++plane_comparisons;
        }
      }
      // Upwards: away from the floor, which the camera is outside of.
      for (const double degrees : {90.0, 30.0, 1.0, 0.01}) {
        for (const Vec3& down : directions_below_horizon(degrees)) {
          glint::Ray ray;
          ray.origin = {0.0f, height, 0.0f};
          ray.direction = {down.x, -down.y, down.z};
          INFO("radius " << radius << ", camera " << height << " above, " << degrees
                         << " degrees up");
          CHECK_FALSE(scene.closest_hit(ray));
          CHECK_FALSE(scene.occluded(ray));
        }
      }
    }
  }
  CHECK(sphere_comparisons > 2000);
  CHECK(plane_comparisons > 1000);
  WARN("worst error / tolerance: sphere " << worst_sphere << ", plane " << worst_plane);
}

TEST_CASE("huge floors: a camera 1e-3 above the report's room floor does not see through it",
          "[render][huge_sphere]") {
  // The report's room (scenes/fig1a-diffuse.scene): walls of radius 1e5, the floor's top at
  // y = -10; the camera 0.001 above that top, among ordinary spheres (the room's one, then 100
  // more, so that the other spheres go to the hierarchy while the walls stay in the WallSet).
  for (const int extra : {0, 100}) {
    glint::SceneDescription scene;
    scene.camera.position = {0.0f, -9.999f, 0.0f};
    scene.camera.look_at = {0.0f, -10.0f, -30.0f};
    const Vec3 walls[] = {{0.0f, 0.0f, -100060.0f}, {0.0f, 0.0f, 100060.0f},
                          {0.0f, -100010.0f, 0.0f}, {0.0f, 100060.0f, 0.0f},
                          {-100060.0f, 0.0f, 0.0f}, {100060.0f, 0.0f, 0.0f}};
    for (const Vec3& c : walls) {
      glint::SphereDescription wall;
      wall.center = c;
      wall.radius = 1e5f;
      scene.spheres.push_back(wall);
    }
    for (int i = 0; i < 1 + extra; ++i) {
      glint::SphereDescription ball;
      ball.center = {-40.0f + 0.8f * float(i % 100), 20.0f, -40.0f};
      ball.radius = 0.3f;
      if (i == 0) {
        ball.center = {0.0f, 0.0f, -30.0f};
        ball.radius = 10.0f;
      }
      scene.spheres.push_back(ball);
    }
    const glint::Scene built = glint::Scene::build(scene);
    // The camera's height above the floor's top, as stored: -9.999f + 10 is exact.
    const float h = float(double(scene.camera.position.y) + 10.0);
    for (const double degrees : {90.0, 45.0, 10.0, 1.0}) {
      for (const Vec3& d : directions_below_horizon(degrees)) {
        glint::Ray ray;
        ray.origin = scene.camera.position;
        ray.direction = d;
        const std::optional<glint::SphereHit> hit = built.closest_hit(ray);
        const std::optional<double> exact = exact_floor_distance(1e5f, h, d);
        REQUIRE(exact);
        INFO(extra << " extra spheres, " << degrees << " degrees down: exact " << *exact << ", got "
                   << (hit ? hit->t : -1.0f));
        REQUIRE(hit);
        CHECK(hit->sphere == 2u);  // the floor
        CHECK(std::abs(hit->t - *exact) <= 1e-4 * *exact);
      }
    }
  }
}

TEMPLATE_TEST_CASE("huge floors: a lit floor renders with the point-light formula",
                   "[render][huge_sphere]", glint::variants::report, glint::variants::fast) {
  // Direct light only: the floor at the centre of a tiny field of view, the point light along
  // its normal there at distance l = max(h, 1): radiance rho I cos / (pi d^2), computed for the
  // exact sphere in double. Before the anchored kernel a camera near a huge floor saw through
  // it and rendered black.
  const float albedo = 0.8f;
  for (const float radius : floor_radii()) {
    for (const float height : camera_heights()) {
      for (const double degrees : {45.0, 10.0}) {
        glint::SceneDescription scene = floor_scene(radius, height);
        scene.spheres[0].material.diffuse = albedo;
        const double a = degrees * kDegree;
        const Vec3 forward(0.0f, float(-std::sin(a)), float(-std::cos(a)));
        scene.camera.look_at = scene.camera.position + forward;
        scene.camera.fov_degrees = 1e-3f;
        const Vec3 d = glm::normalize(scene.camera.look_at - scene.camera.position);
        const std::optional<double> t = exact_floor_distance(radius, height, d);
        INFO("radius " << radius << ", camera " << height << " above, " << degrees
                       << " degrees down");
        if (!t) continue;  // past the horizon of a small floor
        const glm::dvec3 center(0.0, -double(radius), 0.0);
        const glm::dvec3 point = glm::dvec3(scene.camera.position) + *t * glm::dvec3(d);
        const glm::dvec3 normal = (point - center) / double(radius);
        const double l = std::max(double(height), 1.0);
        glint::PointLight light;
        light.position = Vec3(point + l * normal);
        light.intensity = float(M_PI * l * l);
        scene.lights.push_back(light);
        const glm::dvec3 to_light = glm::dvec3(light.position) - point;
        const double distance = glm::length(to_light);
        const double expected = albedo * double(light.intensity) *
                                glm::dot(normal, to_light / distance) /
                                (M_PI * distance * distance);

        glint::RenderSettings s;
        s.width = 4;
        s.height = 4;
        s.samples_per_pixel = 2;
        s.max_depth = 0;
        s.seed = 3;
        s.threads = 1;
        const glint::Scene built = glint::Scene::build(scene);
        const glint::RenderResult result =
            glint_test::render_by<glint::Renderer<TestType>>(built, s);
        CHECK(result.stats.invalid_samples == 0);
        for (const Color& c : result.film.pixels())
          CHECK(c.x == Approx(expected).epsilon(1e-3));
      }
    }
  }
}

TEST_CASE("huge floors: geometry at the scene format's limits renders without overflow",
          "[render][huge_sphere]") {
  // The largest floor at the largest coordinates the validator accepts (limits in
  // scene/validate.hpp), the camera 1e6 above it looking straight down, a light 1e6 above the
  // camera: every squared distance the kernels form stays finite, and the floor shows the
  // point-light formula rho I / (pi d^2).
  const float radius = glint::limits::max_sphere_radius;
  const float edge = glint::limits::max_coordinate;
  glint::SceneDescription scene;
  scene.background = Color(0.0f);
  glint::SphereDescription floor;
  floor.center = {edge, -edge, -edge};
  floor.radius = radius;
  floor.material.diffuse = 0.5f;
  scene.spheres.push_back(floor);
  const double top = double(floor.center.y) + double(radius);
  scene.camera.position = {edge, float(top + 1e6), -edge};
  scene.camera.look_at = scene.camera.position - Vec3(0.0f, 1e6f, 0.0f);
  scene.camera.up = {0.0f, 0.0f, -1.0f};
  scene.camera.fov_degrees = 1e-3f;
  glint::PointLight light;
  light.position = scene.camera.position + Vec3(0.0f, 1e6f, 0.0f);
  light.intensity = 1e12f;
  scene.lights.push_back(light);
  REQUIRE_NOTHROW(glint::validate(scene));

  glint::RenderSettings s;
  s.width = 4;
  s.height = 4;
  s.samples_per_pixel = 2;
  s.max_depth = 2;
  s.threads = 1;
  const glint::RenderResult result =
      glint_test::render_by<glint::Renderer<glint::variants::report>>(glint::Scene::build(scene),
                                                                      s);
  CHECK(result.stats.invalid_samples == 0);
  // Near 9e10 floats are 8192 apart: the floor's top as the kernel stores it (its anchor, the
  // top rounded to float) is where the light's distance is measured from.
  const double d = double(light.position.y) - double(float(top));
  const double expected = 0.5 * double(light.intensity) / (M_PI * d * d);
  for (const Color& c : result.film.pixels())
    CHECK(c.x == Approx(expected).epsilon(1e-3));
}
