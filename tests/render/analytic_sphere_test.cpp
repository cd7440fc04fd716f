// The furnace-style analytic test from the issue: a closed diffuse sphere of radius R and
// albedo rho with a point light of intensity I at its centre. Every point of the inner wall
// receives direct irradiance I/R^2 and, by symmetry, the same indirect light, so the radiance
// L satisfies L = rho/pi * (I/R^2 + pi L): L = rho I / (pi R^2 (1 - rho)). With at most n
// bounces the series stops after n+1 terms: L_n = rho I/(pi R^2) * (1 - rho^(n+1)) / (1 - rho).

#include <catch2/catch.hpp>
#include <cmath>

#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"

namespace {

glint::SceneDescription lit_sphere_interior(float radius, float albedo, float intensity) {
  glint::SceneDescription scene;
  scene.source = "analytic";
  scene.camera.position = {0.0f, 0.0f, 0.3f * radius};
  scene.camera.look_at = {0.0f, 0.0f, -radius};
  scene.camera.fov_degrees = 90.0f;
  glint::SphereDescription wall;
  wall.center = glint::Vec3(0.0f);
  wall.radius = radius;
  wall.material.diffuse = albedo;
  wall.material.diffuse_color = glint::Color(1.0f);
  scene.spheres.push_back(wall);
  glint::PointLight light;
  light.position = glint::Vec3(0.0f);
  light.intensity = intensity;
  scene.lights.push_back(light);
  return scene;
}

double expected_radiance(double radius, double albedo, double intensity, int max_depth) {
  const double direct = albedo * intensity / (M_PI * radius * radius);
  return direct * (1.0 - std::pow(albedo, max_depth + 1)) / (1.0 - albedo);
}

/// The mean over the image of renderer R (a Renderer or a WavefrontRenderer).
template <typename R>
double mean_radiance(const glint::Scene& scene, int spp, int max_depth, double& standard_error) {
  glint::RenderSettings settings;
  settings.width = 16;
  settings.height = 16;
  settings.samples_per_pixel = spp;
  settings.max_depth = max_depth;
  settings.threads = 2;
  settings.seed = 7;
  const glint::RenderResult result = glint_test::render_by<R>(scene, settings);
  REQUIRE(result.stats.invalid_samples == 0);
  double sum = 0.0, sum2 = 0.0;
  for (const glint::Color& c : result.film.pixels()) {
    // A grey world: every channel must agree exactly.
    REQUIRE(c.x == c.y);
    REQUIRE(c.y == c.z);
    sum += c.x;
    sum2 += double(c.x) * c.x;
  }
  const double n = double(result.film.pixels().size());
  const double mean = sum / n;
  standard_error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  return mean;
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("a lit closed diffuse sphere shows rho I / (pi R^2 (1 - rho))",
                        "[render][analytic]", glint_test::CameraPathRenderers) {
  const float radius = 10.0f, albedo = 0.5f, intensity = 400.0f;
  const glint::Scene scene = glint::Scene::build(lit_sphere_interior(radius, albedo, intensity));

  SECTION("direct light only at depth 0: exact, no noise") {
    double error = 0.0;
    const double mean = mean_radiance<TestType>(scene, 4, 0, error);
    CHECK(mean == Approx(expected_radiance(radius, albedo, intensity, 0)).epsilon(1e-5));
    CHECK(error < 1e-6);
  }
  SECTION("converged series with many bounces") {
    const int depth = 40;  // rho^41 is negligible
    double error = 0.0;
    const double mean = mean_radiance<TestType>(scene, 64, depth, error);
    const double expected = albedo * intensity / (M_PI * radius * radius * (1.0 - albedo));
    CHECK(std::abs(expected_radiance(radius, albedo, intensity, depth) - expected) < 1e-9);
    // Pixel means are independent; allow five standard errors plus float accumulation slack.
    CHECK(std::abs(mean - expected) < 5.0 * error + 1e-4 * expected);
  }
  SECTION("truncated series with two bounces") {
    double error = 0.0;
    const double mean = mean_radiance<TestType>(scene, 64, 2, error);
    CHECK(std::abs(mean - expected_radiance(radius, albedo, intensity, 2)) <
          5.0 * error + 1e-4 * mean);
  }
}
