// Camera rays aimed exactly where two spheres cross: the seam of two walls of radius 1e5, and the
// crease of two overlapping balls. The hit point, rounded to float, lies inside the other sphere
// or outside it by a rounding; either way the pixel must show one of the two surfaces lit as
// the independent model (scene_model.hpp, double precision, from the exact crossing point)
// lights it, in every renderer (both execution models), with the spheres in the linear sets,
// with light buffers (24 spheres or more) and in the hierarchy (past 64). And the lamp-room
// rendered through pixel centres, whose diagonals fall on the seams of its walls, has no pixel
// there much darker than the walls on both sides of it.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"
#include "scene_model.hpp"

using glint::Color;
using glint::Vec3;
using glint::test::to_double;
using glint::test::Vec3d;

namespace {

/// The point where spheres a and b cross nearest `guess`: alternating projections onto the two
/// spheres, in double.
Vec3d crossing_point(const glint::SphereDescription& a, const glint::SphereDescription& b,
                     Vec3d point) {
  for (int i = 0; i < 200; ++i) {
    for (const glint::SphereDescription* s : {&a, &b}) {
      const Vec3d f = point - to_double(s->center);
      point = to_double(s->center) + (double(s->radius) / glm::length(f)) * f;
    }
  }
  return point;
}

glint::SphereDescription diffuse_sphere(const Vec3& center, float radius, const Color& color) {
  glint::SphereDescription sphere;
  sphere.center = center;
  sphere.radius = radius;
  sphere.material.diffuse = 1.0f;
  sphere.material.diffuse_color = color;
  return sphere;
}

/// Spheres of radius 0.5 in a row behind the camera, where neither camera rays nor shadow rays
/// go: with them a scene's ordinary spheres are scanned with light buffers (24 or more) or go
/// to the hierarchy (past 64).
void add_spheres_behind(glint::SceneDescription& scene, int count, const Vec3& camera) {
  for (int i = 0; i < count; ++i)
    scene.spheres.push_back(
        diffuse_sphere(camera + Vec3(-20.0f + 1.2f * float(i % 32), 1.2f * float(i / 32), 3.0f),
                       0.5f, Color(0.5f)));
}

/// The radiance of sphere `s` of the model's scene at `point` on it, lit by the point lights
/// (direct light only): what a camera ray that meets it there carries.
double direct_radiance(const glint::test::SceneModel& model, int s, const Vec3d& point,
                       int channel) {
  const glint::SphereDescription& sphere = model.description().spheres[std::size_t(s)];
  const Vec3d normal = glm::normalize(point - to_double(sphere.center));
  unsigned visible = 0;
  const Vec3d irradiance = model.direct_irradiance(point, normal, visible);
  return (double(sphere.material.diffuse) / M_PI * model.surface_color(s, point) *
          irradiance)[channel];
}

/// Renders `scene` as one pixel looking at `target` (exactly: the ray through the centre of a
/// one-pixel image is the viewing direction; the box and tent filters, which ignore sigma, aim
/// within a pixel of 1e-3 degrees of it), with one sample of direct light only.
template <typename R>
Color render_towards(glint::SceneDescription scene, const Vec3& target) {
  scene.camera.look_at = target;
  scene.camera.fov_degrees = 1e-3f;
  glint::RenderSettings settings;
  settings.width = 1;
  settings.height = 1;
  settings.samples_per_pixel = 1;
  settings.max_depth = 0;
  settings.antialias_sigma = 0.0f;
  settings.threads = 1;
  const glint::RenderResult result = glint_test::render_by<R>(glint::Scene::build(scene), settings);
  CHECK(result.stats.invalid_samples == 0);
  return result.film.pixels()[0];
}

/// Aims at `count` points of the crossing of spheres a and b of `scene` (found from guesses
/// along `from` -> `to`) and checks that each pixel shows a or b as the model lights it there.
template <typename R>
void check_crossing(const glint::SceneDescription& scene, int a, int b, const Vec3d& from,
                    const Vec3d& to, int count) {
  const glint::test::SceneModel model(scene);
  const glint::SphereDescription& sa = scene.spheres[std::size_t(a)];
  const glint::SphereDescription& sb = scene.spheres[std::size_t(b)];
  const Vec3d eye = to_double(scene.camera.position);
  int checked = 0;
  for (int k = 0; k < count; ++k) {
    const Vec3d guess = from + (double(k) + 0.5) / double(count) * (to - from);
    const Vec3d point = crossing_point(sa, sb, guess);
    // The model sees the crossing there: the nearest sphere along the line of sight is met
    // where it crosses (to its precision).
    const double distance = glm::length(point - eye);
    const std::optional<glint::test::Hit> seen = model.cast(eye, (point - eye) / distance);
    REQUIRE(seen);
    REQUIRE(std::abs(seen->t - distance) < 1e-9 * distance);
    const Color pixel = render_towards<R>(scene, Vec3(point));
    INFO(R::Config::info.name << " (" << R::ExecutionModel::kName << "): crossing of spheres " << a
                              << " and " << b << " at (" << point.x << ", " << point.y << ", "
                              << point.z << "); pixel (" << pixel.x << ", " << pixel.y << ", "
                              << pixel.z << ")");
    bool like_a = true, like_b = true;
    double difference = 0.0;
    for (int channel = 0; channel < 3; ++channel) {
      const double on_a = direct_radiance(model, a, point, channel);
      const double on_b = direct_radiance(model, b, point, channel);
      INFO("channel " << channel << ": " << on_a << " on sphere " << a << ", " << on_b
                      << " on sphere " << b);
      REQUIRE(std::min(on_a, on_b) > 0.0);  // neither is dark
      difference = std::max(difference, std::abs(on_a - on_b) / std::max(on_a, on_b));
      const double value = pixel[channel];
      like_a = like_a && std::abs(value - on_a) <= 1e-3 * on_a;
      like_b = like_b && std::abs(value - on_b) <= 1e-3 * on_b;
    }
    REQUIRE(difference > 0.1);  // the two surfaces are told apart
    CHECK((like_a || like_b));
    ++checked;
  }
  CHECK(checked == count);
}

/// A closed room of six walls of radius 1e5, 80 across, as bench/scenes/lamp-room.scene: back,
/// behind the camera, left (red), right (blue), floor, ceiling (spheres 0 to 5); a point light.
glint::SceneDescription walled_room() {
  glint::SceneDescription scene;
  scene.camera.position = Vec3(0.0f, 0.0f, 95.0f);
  const Color grey(0.75f), red(0.75f, 0.25f, 0.25f), blue(0.25f, 0.25f, 0.75f);
  const Color sand(0.7f, 0.6f, 0.3f);
  scene.spheres = {diffuse_sphere({0.0f, 0.0f, -100040.0f}, 1e5f, grey),
                   diffuse_sphere({0.0f, 0.0f, 100100.0f}, 1e5f, grey),
                   diffuse_sphere({-100040.0f, 0.0f, 0.0f}, 1e5f, red),
                   diffuse_sphere({100040.0f, 0.0f, 0.0f}, 1e5f, blue),
                   diffuse_sphere({0.0f, -100040.0f, 0.0f}, 1e5f, sand),
                   diffuse_sphere({0.0f, 100040.0f, 0.0f}, 1e5f, grey)};
  glint::PointLight light;
  light.position = Vec3(6.0f, 12.0f, 10.0f);
  light.intensity = 2000.0f;
  scene.lights.push_back(light);
  return scene;
}

/// Two overlapping balls, red (0) and blue (1), crossing on the circle x = 0, y^2 + z^2 = 0.64,
/// seen from the front, a point light in front of the crease.
glint::SceneDescription overlapping_balls() {
  glint::SceneDescription scene;
  scene.camera.position = Vec3(0.25f, 0.4f, 6.0f);
  scene.spheres = {diffuse_sphere({-0.6f, 0.0f, 0.0f}, 1.0f, Color(0.8f, 0.3f, 0.2f)),
                   diffuse_sphere({0.6f, 0.0f, 0.0f}, 1.0f, Color(0.2f, 0.4f, 0.8f))};
  glint::PointLight light;
  light.position = Vec3(0.0f, 0.0f, 4.0f);
  light.intensity = 16.0f;
  scene.lights.push_back(light);
  return scene;
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("seams: a camera ray aimed where two walls cross shows one of them lit",
                        "[render][seam]", glint_test::CameraPathRenderers) {
  for (const int behind : {0, 30, 80}) {
    glint::SceneDescription scene = walled_room();
    add_spheres_behind(scene, behind, scene.camera.position);
    INFO(behind << " spheres behind the camera");
    // Left and ceiling, back and floor, right and floor, left and back.
    check_crossing<TestType>(scene, 2, 5, {-40, 40, -35}, {-40, 40, 60}, 6);
    check_crossing<TestType>(scene, 0, 4, {-35, -40, -40}, {35, -40, -40}, 6);
    check_crossing<TestType>(scene, 3, 4, {40, -40, -35}, {40, -40, 60}, 6);
    check_crossing<TestType>(scene, 2, 0, {-40, -35, -40}, {-40, 35, -40}, 6);
  }
}

TEMPLATE_LIST_TEST_CASE(
    "seams: a camera ray aimed where two overlapping balls cross shows one of them lit",
    "[render][seam]", glint_test::CameraPathRenderers) {
  for (const int behind : {0, 30, 80}) {
    glint::SceneDescription scene = overlapping_balls();
    add_spheres_behind(scene, behind, scene.camera.position);
    INFO(behind << " spheres behind the camera");
    // The front of the crease, from 40 to 140 degrees round the x axis.
    const double start = 40.0 * M_PI / 180.0, end = 140.0 * M_PI / 180.0;
    check_crossing<TestType>(scene, 0, 1, {0.0, 0.8 * std::cos(start), 0.8 * std::sin(start)},
                             {0.0, 0.8 * std::cos(end), 0.8 * std::sin(end)}, 12);
  }
}

namespace {

/// The luminance of a pixel (the sum of its channels: the walls differ in colour).
double brightness(const glint::Film& film, int x, int y) {
  const Color c = film.at(x, y);
  return double(c.x) + double(c.y) + double(c.z);
}

/// For each pixel on the image's diagonals whose centre's ray meets two walls where they cross
/// (the model says so): its brightness over that of the darker side, each side the mean of its
/// two neighbours off the diagonal (one where the pixel is on the image's edge).
std::vector<double> seam_ratios(const glint::SceneDescription& scene, const glint::Film& film) {
  const glint::test::SceneModel model(scene);
  const int n = film.width();
  const glint::test::Pinhole camera(scene.camera, n, n);
  std::vector<double> ratios;
  for (int y = 0; y < n; ++y) {
    for (const int x : {y, n - 1 - y}) {
      const std::optional<glint::test::Hit> hit =
          model.cast(camera.eye(), camera.direction(x + 0.5, y + 0.5));
      REQUIRE(hit);
      bool on_seam = false;
      for (std::size_t s = 0; s < scene.spheres.size(); ++s) {
        const glint::SphereDescription& other = scene.spheres[s];
        if (int(s) == hit->sphere || other.radius < 1e4f) continue;
        const double gap = glm::length(hit->point - to_double(other.center)) - other.radius;
        on_seam = on_seam || std::abs(gap) < 1e-3;
      }
      if (!on_seam) continue;
      // The pixel's neighbours on either side of the diagonal through it.
      const int dx = x == y ? 1 : -1;  // along the diagonal, x grows by dx as y grows by 1
      const auto side = [&](int sx, int sy, int tx, int ty) {
        double sum = 0.0;
        int count = 0;
        for (const auto& [px, py] : {std::pair{sx, sy}, std::pair{tx, ty}}) {
          if (px < 0 || px >= n || py < 0 || py >= n) continue;
          sum += brightness(film, px, py);
          ++count;
        }
        return sum / count;
      };
      // Below the diagonal (larger y for the same x) and above it.
      const double below = side(x - dx, y, x, y + 1);
      const double above = side(x + dx, y, x, y - 1);
      INFO("pixel (" << x << ", " << y << "): " << brightness(film, x, y) << ", sides " << below
                     << " and " << above);
      ratios.push_back(brightness(film, x, y) / std::min(below, above));
    }
  }
  return ratios;
}

glint::SceneDescription lamp_room() {
  return glint::read_scene_file(GLINT_SOURCE_DIR "/bench/scenes/lamp-room.scene");
}

template <typename R>
void check_lamp_room(int size, int spp) {
  const glint::SceneDescription scene = lamp_room();
  glint::RenderSettings settings;
  settings.width = size;
  settings.height = size;
  settings.samples_per_pixel = spp;
  settings.max_depth = 12;
  settings.antialias_sigma = 0.0f;  // the Gaussian variants through pixel centres too
  settings.seed = 5;
  const glint::RenderResult result = glint_test::render_by<R>(glint::Scene::build(scene), settings);
  CHECK(result.stats.invalid_samples == 0);
  const std::vector<double> ratios = seam_ratios(scene, result.film);
  INFO(R::Config::info.name << " (" << R::ExecutionModel::kName << ")");
  // Every corner of the image's square looks at two walls' seam, past the back wall.
  CHECK(ratios.size() >= 8);
  // A seam is a little darker than the walls beside it (less of the room lights it), and the
  // render is noisy; a pixel whose path continued inside a wall is dark as ink.
  for (const double ratio : ratios)
    CHECK(ratio > 0.25);
}

}  // namespace

TEST_CASE("seams: lamp-room through pixel centres has no dark pixel on its diagonals",
          "[render][seam]") {
  // The variant without antialiasing (bounces find the lamp by chance: few pixels, many
  // samples); emitter sampling through pixel centres with both execution models.
  check_lamp_room<glint::Renderer<glint::variants::no_antialiasing>>(22, 2048);
  check_lamp_room<glint::Renderer<glint::variants::emitter_sampling>>(32, 256);
  check_lamp_room<glint::Renderer<glint::variants::fast>>(32, 256);
  check_lamp_room<glint::WavefrontRenderer<glint::variants::fast>>(32, 256);
}
