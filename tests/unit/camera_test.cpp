// The camera: ray directions implied by the field of view and aspect ratio, the near clipping
// plane, connections back to the film, the importance integrating to the pixels, and with a thin
// lens its rays meeting on the plane in focus and the blur circle of the lens equation; and the
// rejection of degenerate cameras by validate().

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

#include "../support/float_values.hpp"
#include "glint/render/camera.hpp"
#include "glint/scene/validate.hpp"

using glint::Vec2;
using glint::Vec3;

namespace {

using glint_test::kDegree;

glint::CameraDescription oblique_camera() {
  glint::CameraDescription c;
  c.position = {1.0f, 2.0f, 3.0f};
  c.look_at = {4.0f, -1.0f, 7.0f};
  c.up = {0.0f, 1.0f, 0.0f};
  c.fov_degrees = 50.0f;
  return c;
}

/// The camera's viewing direction, right and up, as the camera builds them.
struct ViewFrame {
  Vec3 forward, right, up;
};
ViewFrame view_frame(const glint::CameraDescription& description) {
  const Vec3 forward = glm::normalize(description.look_at - description.position);
  const Vec3 right = glm::normalize(glm::cross(forward, description.up));
  return {forward, right, glm::cross(right, forward)};
}

double angle_between(const Vec3& a, const Vec3& b) {
  const double cosine = glm::dot(glm::normalize(a), glm::normalize(b));
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

/// A camera at distance `distance` on the z axis, looking at the origin.
glint::CameraDescription axis_camera(float distance, float fov_degrees, float aperture) {
  glint::CameraDescription description;
  description.position = {0.0f, 0.0f, distance};
  description.look_at = {0.0f, 0.0f, 0.0f};
  description.fov_degrees = fov_degrees;
  description.aperture = aperture;
  return description;
}

/// The integral of importance x cos over the part of the plane z = 0 that a width x height film
/// of `description` sees (its centre at the origin), by the midpoint rule; `connect(point)`
/// joins a point to the camera.
template <typename Connect>
double importance_over_window(const glint::CameraDescription& description, int width, int height,
                              const Connect& connect) {
  const double half_height =
      double(description.position.z) * std::tan(0.5 * description.fov_degrees * M_PI / 180.0);
  const double half_width = half_height * width / height;
  constexpr int kSteps = 400;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j) {
      const Vec3 point(float(-half_width + (i + 0.5) * 2.0 * half_width / kSteps),
                       float(-half_height + (j + 0.5) * 2.0 * half_height / kSteps), 0.0f);
      const std::optional<glint::CameraConnection> c = connect(point);
      REQUIRE(c.has_value());
      sum += double(c->importance) * c->direction.z;  // cos at the plane, whose normal is +z
    }
  return sum * (2.0 * half_width / kSteps) * (2.0 * half_height / kSteps);
}

}  // namespace

TEST_CASE("camera: the image centre looks at look_at", "[camera]") {
  const glint::CameraDescription description = oblique_camera();
  const Vec3 forward = glm::normalize(description.look_at - description.position);
  for (const auto& [w, h] : {std::pair{320, 200}, std::pair{101, 77}, std::pair{1, 1}}) {
    const glint::Camera camera(description, w, h);
    const glint::Ray ray = camera.ray_through(Vec2(0.5f * float(w), 0.5f * float(h)));
    CHECK(ray.origin == description.position);
    CHECK(glm::length(ray.direction - forward) < 1e-6f);
    CHECK(std::abs(glm::length(ray.direction) - 1.0f) < 1e-6f);
    CHECK(ray.t_min == 0.0f);
    CHECK(ray.origin_sphere == glint::kNoSphere);
  }
}

TEST_CASE("camera: edge and corner rays have the angles implied by fov and aspect", "[camera]") {
  const glint::CameraDescription description = oblique_camera();
  const int width = 320, height = 200;
  const glint::Camera camera(description, width, height);
  const auto [forward, right, up] = view_frame(description);
  const double half_fov = 0.5 * description.fov_degrees * kDegree;
  const double aspect = double(width) / height;

  // Top edge, middle: exactly half the vertical field of view, upwards.
  const Vec3 top = camera.ray_through(Vec2(0.5f * width, 0.0f)).direction;
  CHECK(angle_between(top, forward) == Approx(half_fov).epsilon(1e-5));
  CHECK(glm::dot(top, up) > 0.0f);
  CHECK(std::abs(glm::dot(top, right)) < 1e-6f);
  // Bottom edge: the same angle, downwards.
  const Vec3 bottom = camera.ray_through(Vec2(0.5f * width, float(height))).direction;
  CHECK(angle_between(bottom, forward) == Approx(half_fov).epsilon(1e-5));
  CHECK(glm::dot(bottom, up) < 0.0f);
  // Right edge, middle: horizontal half-angle atan(aspect tan(fov/2)).
  const Vec3 right_edge = camera.ray_through(Vec2(float(width), 0.5f * height)).direction;
  CHECK(angle_between(right_edge, forward) ==
        Approx(std::atan(aspect * std::tan(half_fov))).epsilon(1e-5));
  CHECK(glm::dot(right_edge, right) > 0.0f);
  // Top-left corner: tan^2 of the angle is (1 + aspect^2) tan^2(fov/2).
  const Vec3 corner = camera.ray_through(Vec2(0.0f, 0.0f)).direction;
  CHECK(angle_between(corner, forward) ==
        Approx(std::atan(std::tan(half_fov) * std::sqrt(1.0 + aspect * aspect))).epsilon(1e-5));
  CHECK(glm::dot(corner, right) < 0.0f);
  CHECK(glm::dot(corner, up) > 0.0f);
  CHECK(std::abs(glm::length(corner) - 1.0f) < 1e-6f);
  // Film coordinates are linear on the image plane: the quarter point is halfway in tangent.
  const Vec3 quarter = camera.ray_through(Vec2(0.5f * width, 0.25f * height)).direction;
  CHECK(std::tan(angle_between(quarter, forward)) ==
        Approx(0.5 * std::tan(half_fov)).epsilon(1e-5));
}

TEST_CASE("camera: the near plane is perpendicular to the view direction", "[camera]") {
  glint::CameraDescription description = oblique_camera();
  description.near = 2.5f;
  const int width = 64, height = 48;
  const glint::Camera camera(description, width, height);
  const Vec3 forward = glm::normalize(description.look_at - description.position);
  const double half_fov = 0.5 * description.fov_degrees * kDegree;
  const double aspect = double(width) / height;

  const glint::Ray centre = camera.ray_through(Vec2(32.0f, 24.0f));
  CHECK(centre.t_min == Approx(2.5).epsilon(1e-6));
  // Corner ray: t_min = near / cos(angle to the view direction).
  const glint::Ray corner = camera.ray_through(Vec2(0.0f, 0.0f));
  const double corner_angle = std::atan(std::tan(half_fov) * std::sqrt(1.0 + aspect * aspect));
  CHECK(corner.t_min == Approx(2.5 / std::cos(corner_angle)).epsilon(1e-5));
  // Every ray starts its visible part on the plane.
  for (const Vec2 film : {Vec2(0.0f), Vec2(64.0f, 0.0f), Vec2(10.5f, 40.25f), Vec2(64.0f, 48.0f)}) {
    const glint::Ray ray = camera.ray_through(film);
    CHECK(glm::dot(ray.at(ray.t_min) - description.position, forward) == Approx(2.5).epsilon(1e-5));
  }
}

TEST_CASE("validate rejects degenerate cameras", "[camera][validate]") {
  glint::SceneDescription scene;
  scene.source = "cam.scene";
  scene.camera.line = 7;
  REQUIRE_NOTHROW(glint::validate(scene));

  const auto expect_rejected = [](glint::SceneDescription bad, const char* what) {
    INFO(what);
    try {
      glint::validate(bad);
      FAIL("accepted: " << what);
    } catch (const glint::SceneError& e) {
      CHECK(e.line() == 7);
      CHECK(std::string(e.what()).rfind("cam.scene:7: error: ", 0) == 0);
    }
  };
  auto s = scene;
  s.camera.look_at = s.camera.position;
  expect_rejected(s, "look_at at the camera position");
  s = scene;
  s.camera.up = Vec3(0.0f);
  expect_rejected(s, "zero up vector");
  s = scene;
  s.camera.up = s.camera.look_at - s.camera.position;
  expect_rejected(s, "up along the view direction");
  s.camera.up = -s.camera.up;
  expect_rejected(s, "up against the view direction");
  for (const float fov : {0.0f, -10.0f, 180.0f, 200.0f, std::nanf("")}) {
    s = scene;
    s.camera.fov_degrees = fov;
    expect_rejected(s, "fov out of (0, 180)");
  }
  for (const float near : {-1.0f, std::nanf(""), std::numeric_limits<float>::infinity()}) {
    s = scene;
    s.camera.near = near;
    expect_rejected(s, "bad near");
  }
  s = scene;
  s.camera.position.x = std::numeric_limits<float>::infinity();
  expect_rejected(s, "infinite position");
  s = scene;
  s.camera.look_at.y = std::nanf("");
  expect_rejected(s, "NaN look_at");

  // Valid edge cases are accepted.
  s = scene;
  s.camera.fov_degrees = 179.0f;
  s.camera.near = 0.0f;
  s.camera.up = {0.3f, 1.0f, 0.2f};  // need not be perpendicular
  CHECK_NOTHROW(glint::validate(s));
}

namespace {

/// Points along the rays through `films`, near and far, connect back to their film positions,
/// along the ray reversed, at its distance, blockable from the ray's start on, through the
/// camera's position.
void check_connections_back(const glint::Camera& camera, std::initializer_list<Vec2> films) {
  for (const Vec2 film : films) {
    const glint::Ray ray = camera.ray_through(film);
    for (const float t : {1.0f, 7.5f, 300.0f}) {
      INFO("film " << film.x << ", " << film.y << ", distance " << t);
      const std::optional<glint::CameraConnection> c = camera.connect(ray.at(t));
      REQUIRE(c.has_value());
      CHECK(c->film.x == Approx(film.x).margin(2e-3));
      CHECK(c->film.y == Approx(film.y).margin(2e-3));
      CHECK(c->distance == Approx(t).epsilon(1e-5));
      CHECK(c->unclipped_distance == Approx(t - ray.t_min).epsilon(1e-5));
      CHECK(glm::dot(c->direction, ray.direction) == Approx(-1.0).margin(1e-6));
      CHECK(c->lens_point == camera.position());
    }
  }
}

}  // namespace

TEST_CASE("camera: a point seen through a film position connects back to that position",
          "[camera]") {
  glint::CameraDescription description = oblique_camera();
  description.near = 0.5f;
  const glint::Camera camera(description, 64, 48);
  check_connections_back(
      camera, {Vec2(0.5f, 0.5f), Vec2(31.7f, 20.2f), Vec2(63.9f, 47.1f), Vec2(-3.0f, 60.0f)});
  // Behind the camera, and between it and the near plane: not seen.
  const glint::Ray centre = camera.ray_through(Vec2(32.0f, 24.0f));
  CHECK_FALSE(camera.connect(centre.at(-2.0f)).has_value());
  CHECK_FALSE(camera.connect(centre.at(0.4f)).has_value());
}

TEST_CASE("camera: its importance integrates to the film's pixels", "[camera]") {
  // A pixel's measurement of a surface of unit radiance that fills the view is 1 (the mean
  // radiance over the filter). Written as an integral over the surface (a plane facing the
  // camera at distance 5), that is the integral of importance x cos x filter density per unit
  // area: summed over every pixel (each filter integrating to one over the film), the integral
  // of importance x cos over the part of the plane the film sees is the number of pixels.
  const glint::CameraDescription description = axis_camera(5.0f, 40.0f, 0.0f);
  const int width = 30, height = 20;
  const glint::Camera camera(description, width, height);
  const double sum = importance_over_window(
      description, width, height, [&](const Vec3& point) { return camera.connect(point); });
  CHECK(sum == Approx(double(width) * height).epsilon(1e-4));
}

namespace {

/// Hands out one fixed 2d value: a lens point chosen by the test.
struct FixedDraw {
  Vec2 u;
  Vec2 next_2d() { return u; }
};

/// The lens samples the thin-lens tests use: the centre, the rim and points between.
const Vec2 kLensSamples[] = {Vec2(0.0f, 0.0f), Vec2(0.999f, 0.1f), Vec2(0.25f, 0.6f),
                             Vec2(0.7f, 0.85f), Vec2(0.5f, 0.35f)};

glint::CameraDescription lens_camera() {
  glint::CameraDescription description = oblique_camera();
  description.aperture = 0.4f;
  description.focus_distance = 6.0f;
  return description;
}

}  // namespace

TEST_CASE("camera: a thin lens's rays leave the lens and meet on the plane in focus", "[camera]") {
  const glint::CameraDescription description = lens_camera();
  const glint::Camera camera(description, 64, 48);
  REQUIRE(camera.has_lens());
  const Vec3 forward = glm::normalize(description.look_at - description.position);
  for (const Vec2 film : {Vec2(32.0f, 24.0f), Vec2(3.5f, 40.25f), Vec2(60.0f, 2.0f)}) {
    // Where the central ray (the pinhole's) meets the plane in focus.
    const glint::Ray central = camera.ray_through(film);
    const Vec3 focal = central.at(6.0f / glm::dot(central.direction, forward));
    for (const Vec2 u : kLensSamples) {
      FixedDraw draw{u};
      const glint::Ray ray = camera.sample_ray(film, draw);
      const Vec3 from_centre = ray.origin - description.position;
      CHECK(std::abs(glm::dot(from_centre, forward)) < 1e-6f);  // on the lens, in its plane
      CHECK(glm::length(from_centre) <= 0.4f * 1.0001f);
      CHECK(glm::length(ray.direction) == Approx(1.0).epsilon(1e-6));
      const Vec3 on_focus_plane = ray.at(6.0f / glm::dot(ray.direction, forward));
      CHECK(glm::length(on_focus_plane - focal) < 2e-5f);
    }
  }
  // The lens is sampled uniformly: the rim at u.x -> 1, the centre at u.x = 0.
  FixedDraw rim{Vec2(0.9999999f, 0.3f)};
  CHECK(glm::length(camera.sample_ray(Vec2(10.0f, 10.0f), rim).origin - description.position) ==
        Approx(0.4).epsilon(1e-5));
}

TEST_CASE("camera: a thin lens connects a point back to the film and lens point of its ray",
          "[camera]") {
  glint::CameraDescription description = lens_camera();
  description.near = 0.5f;
  const glint::Camera camera(description, 64, 48);
  for (const Vec2 film : {Vec2(0.5f, 0.5f), Vec2(31.7f, 20.2f), Vec2(63.9f, 47.1f)})
    for (const Vec2 u : kLensSamples) {
      FixedDraw draw{u};
      const glint::Ray ray = camera.sample_ray(film, draw);
      for (const float t : {1.0f, 6.0f, 300.0f}) {
        FixedDraw again{u};
        const std::optional<glint::CameraConnection> c = camera.connect(ray.at(t), again);
        REQUIRE(c.has_value());
        CHECK(c->film.x == Approx(film.x).margin(3e-3));
        CHECK(c->film.y == Approx(film.y).margin(3e-3));
        CHECK(glm::length(c->lens_point - ray.origin) < 1e-6f);
        CHECK(c->distance == Approx(t).epsilon(1e-5));
        CHECK(c->unclipped_distance == Approx(t - ray.t_min).epsilon(1e-5));
        CHECK(glm::dot(c->direction, ray.direction) == Approx(-1.0).margin(1e-6));
      }
    }
}

TEST_CASE("camera: a point off the plane in focus spreads over the lens equation's circle",
          "[camera]") {
  // A point on the axis at depth d, seen through lens point rho (from the centre), lands where
  // the ray from rho through it meets the plane in focus at depth f: rho (1 - f / d) from the
  // axis, f p per pixel there (p: a pixel's size at depth one). So the rim of an aperture of
  // radius r draws a circle of radius r |1 - f / d| / (f p) pixels about the image centre, and a
  // point on the plane in focus stays a point.
  glint::CameraDescription description = axis_camera(10.0f, 30.0f, 0.25f);
  description.focus_distance = 8.0f;
  const int width = 200, height = 100;
  const glint::Camera camera(description, width, height);
  const double p = 2.0 * std::tan(15.0 * M_PI / 180.0) / height;
  for (const double d : {2.0, 4.0, 8.0, 16.0, 50.0}) {
    const double expected = 0.25 * std::abs(1.0 - 8.0 / d) / (8.0 * p);
    for (const float angle : {0.0f, 0.3f, 0.55f, 0.9f}) {
      FixedDraw rim{Vec2(0.99999994f, angle)};
      const std::optional<glint::CameraConnection> c =
          camera.connect(Vec3(0.0f, 0.0f, float(10.0 - d)), rim);
      REQUIRE(c.has_value());
      const double radius =
          std::hypot(double(c->film.x) - width / 2.0, double(c->film.y) - height / 2.0);
      INFO("depth " << d << ", angle " << angle);
      CHECK(radius == Approx(expected).margin(2e-3));
    }
  }
}

TEST_CASE("camera: a thin lens's importance integrates to the film's pixels from every lens point",
          "[camera]") {
  // As for the pinhole: the plane is the plane in focus, which every lens point sees through
  // the same window, so the integral of importance x cos over the window is the number of
  // pixels for each lens point drawn.
  const glint::CameraDescription description = axis_camera(5.0f, 40.0f, 0.6f);
  const int width = 30, height = 20;
  const glint::Camera camera(description, width, height);
  REQUIRE(camera.focus_distance() == 5.0f);  // look_at's distance, by default
  for (const Vec2 u : kLensSamples) {
    INFO("lens sample " << u.x << ", " << u.y);
    const double sum = importance_over_window(description, width, height, [&](const Vec3& point) {
      FixedDraw draw{u};
      return camera.connect(point, draw);
    });
    CHECK(sum == Approx(double(width) * height).epsilon(1e-4));
  }
}

TEST_CASE("validate rejects a bad aperture or focus", "[camera][validate]") {
  glint::SceneDescription scene;
  scene.source = "cam.scene";
  scene.camera.line = 3;
  for (const float aperture :
       {-0.1f, std::nanf(""), std::numeric_limits<float>::infinity(), 1e30f}) {
    glint::SceneDescription s = scene;
    s.camera.aperture = aperture;
    CHECK_THROWS_AS(glint::validate(s), glint::SceneError);
  }
  for (const float focus : {-1.0f, std::nanf(""), std::numeric_limits<float>::infinity()}) {
    glint::SceneDescription s = scene;
    s.camera.focus_distance = focus;
    CHECK_THROWS_AS(glint::validate(s), glint::SceneError);
  }
  glint::SceneDescription s = scene;
  s.camera.aperture = 0.5f;
  s.camera.focus_distance = 12.0f;
  CHECK_NOTHROW(glint::validate(s));
}

namespace {

glint::CameraDescription panorama_camera() {
  glint::CameraDescription description = oblique_camera();
  description.projection = glint::Projection::equirectangular;
  return description;
}

}  // namespace

TEST_CASE("camera: the panorama's film covers every direction, middle ahead, top up", "[camera]") {
  const glint::CameraDescription description = panorama_camera();
  const glint::Camera camera(description, 64, 32);
  const auto [forward, right, up] = view_frame(description);
  const auto direction = [&](float x, float y) { return camera.ray_through(Vec2(x, y)).direction; };
  // The chord between unit vectors: the angle, where acos of a float cosine near 1 cannot resolve
  // less than about 3e-4.
  const auto angle_between = [](const Vec3& a, const Vec3& b) {
    return double(glm::length(glm::normalize(a) - glm::normalize(b)));
  };
  CHECK(angle_between(direction(32.0f, 16.0f), forward) < 1e-6);
  CHECK(angle_between(direction(48.0f, 16.0f), right) < 1e-6);    // three quarters: right
  CHECK(angle_between(direction(16.0f, 16.0f), -right) < 1e-6);   // one quarter: left
  CHECK(angle_between(direction(0.0f, 16.0f), -forward) < 1e-6);  // the edges: behind
  CHECK(angle_between(direction(64.0f, 16.0f), -forward) < 1e-6);
  CHECK(angle_between(direction(32.0f, 0.0f), up) < 1e-6);  // the top row: up
  CHECK(angle_between(direction(32.0f, 32.0f), -up) < 1e-6);
  CHECK(angle_between(direction(32.0f, 8.0f), forward + up) < 1e-6);  // 45 degrees up
  // Its rays start at distance `near`, whatever their direction, and no lens is drawn.
  glint::CameraDescription near_description = description;
  near_description.near = 0.75f;
  const glint::Camera near_camera(near_description, 64, 32);
  CHECK(near_camera.ray_through(Vec2(3.0f, 29.0f)).t_min == 0.75f);
  CHECK_FALSE(near_camera.has_lens());
}

TEST_CASE("camera: the panorama connects a point back to its film position, in every direction",
          "[camera]") {
  glint::CameraDescription description = panorama_camera();
  description.near = 0.5f;
  const glint::Camera camera(description, 64, 32);
  CHECK(camera.ray_through(Vec2(10.0f, 3.0f)).t_min == 0.5f);  // along every ray
  check_connections_back(camera, {Vec2(0.5f, 0.5f), Vec2(31.7f, 20.2f), Vec2(63.2f, 31.1f),
                                  Vec2(10.0f, 3.0f), Vec2(50.0f, 27.0f)});
  // Within `near`: not seen; behind the viewing direction: seen.
  const glint::Ray ahead = camera.ray_through(Vec2(32.0f, 16.0f));
  CHECK_FALSE(camera.connect(ahead.at(0.4f)).has_value());
  CHECK(camera.connect(ahead.at(-2.0f)).has_value());
}

TEST_CASE("camera: the panorama's density integrates to the film's pixels over the sphere",
          "[camera]") {
  // Film points drawn with density one per pixel area give ray directions of density
  // solid_angle_density; over every direction it integrates to the film's area, width x height
  // pixels. By the midpoint rule in the polar angle from up and the longitude about it.
  const glint::CameraDescription description = panorama_camera();
  const int width = 40, height = 24;
  const glint::Camera camera(description, width, height);
  const auto [forward, right, up] = view_frame(description);
  constexpr int kSteps = 720;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < 2 * kSteps; ++j) {
      const double theta = (i + 0.5) * M_PI / kSteps, phi = (j + 0.5) * M_PI / kSteps;
      const Vec3 d = float(std::cos(theta)) * up +
                     float(std::sin(theta) * std::cos(phi)) * forward +
                     float(std::sin(theta) * std::sin(phi)) * right;
      sum += camera.solid_angle_density(d) * std::sin(theta) * (M_PI / kSteps) * (M_PI / kSteps);
    }
  CHECK(sum == Approx(double(width) * height).epsilon(1e-4));
}

TEST_CASE("validate rejects a lens on the panorama and reads its projection",
          "[camera][validate]") {
  glint::SceneDescription scene;
  scene.camera = panorama_camera();
  scene.camera.aperture = 0.5f;
  scene.camera.line = 4;
  CHECK_THROWS_WITH(glint::validate(scene),
                    Catch::Contains("a thin lens (aperture) is a perspective camera's"));
  scene.camera.aperture = 0.0f;
  CHECK_NOTHROW(glint::validate(scene));
}
