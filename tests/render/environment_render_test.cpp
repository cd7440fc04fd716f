// Scenes lit by an environment image (scene/environment.hpp) rendered: a diffuse ball under a sky
// with a sun shows albedo / pi times the irradiance of the sky on its normal, worked out here by
// quadrature of the image's radiance in double, and under a colour L albedo x L, with every
// estimator (the path tracer sampling the image and weighing what its bounces find, the path
// tracer finding it by bounces only, the report's tree with and without light sampling,
// bidirectional path tracing and vertex connection and merging, which also join to it and start
// light paths from it); on a scene of a floor, a diffuse ball, a glass ball, a mirror and a lamp
// under the sky, the path tracer with and without sampling the image, bidirectional path tracing
// and vertex merging agree (Holm family); the wavefront renderer gives the scalar one's bits, and
// the image is the same for any threads and tiles; light tracing refuses a scene lit by an image,
// naming the line.

#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "../support/significance.hpp"
#include "block_statistics.hpp"
#include "glint/error.hpp"
#include "glint/image/texture.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "renderer_types.hpp"
#include "same_bits.hpp"

namespace environment_render_test {

using glint::Color;
using glint::Vec3;

/// A sky of 32 x 16 texels: blue above, brighter to one side, a black band below the horizon
/// and a sun of 2 x 2 texels.
std::shared_ptr<const glint::Texture> sky() {
  std::vector<Color> texels;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      if (y >= 9 && y < 11)
        texels.emplace_back(0.0f);
      else if ((x == 11 || x == 12) && (y == 4 || y == 5))
        texels.emplace_back(30.0f, 28.0f, 22.0f);
      else
        texels.emplace_back(0.25f + 0.01f * float(x), 0.35f, 0.6f - 0.02f * float(y));
    }
  return std::make_shared<const glint::Texture>("sky", 32, 16, std::move(texels));
}

/// The scene of `text` under the sky, its top turned towards `axis`.
glint::Scene under_sky(const std::string& text, const Vec3& axis = Vec3(0.0f, 1.0f, 0.0f)) {
  glint::SceneDescription description = glint::read_scene_text(text, "sky scene");
  description.background_image = sky();
  description.background_placement.axis = axis;
  description.background_placement.turn_degrees = 25.0f;
  return glint::Scene::build(description);
}

/// The integral of the environment's radiance (the channels' sum, times `color` per channel)
/// times max(0, n . d) over the sphere of directions, by the midpoint rule on a grid of
/// n x 2n cells in (cos theta, phi) about +z, in double.
double irradiance(const glint::Environment& environment, const Vec3& normal, const Color& color,
                  int n) {
  double sum = 0.0;
  const double d_cos = 2.0 / n, d_phi = std::numbers::pi / n;
  for (int i = 0; i < n; ++i) {
    const double cosine = -1.0 + (i + 0.5) * d_cos, sine = std::sqrt(1.0 - cosine * cosine);
    for (int j = 0; j < 2 * n; ++j) {
      const double phi = (j + 0.5) * d_phi;
      const Vec3 d(float(sine * std::cos(phi)), float(sine * std::sin(phi)), float(cosine));
      const double facing = double(glm::dot(d, normal));
      if (facing <= 0.0) continue;
      const Color l = environment.radiance(d);
      sum += (double(l.r) * color.r + double(l.g) * color.g + double(l.b) * color.b) * facing;
    }
  }
  return sum * d_cos * d_phi;
}

TEST_CASE(
    "a diffuse ball under a sky shows albedo / pi times the sky's irradiance on its normal, and "
    "under a colour albedo times the colour",
    "[render][environment][statistical]") {
  // One pixel whose ray (through its centre: sigma 0) travels along -z and meets the unit ball
  // at (x, 0, sqrt(1 - x^2)); every direction above the ball's surface there escapes.
  const float x = 0.6f;
  const Vec3 normal(x, 0.0f, std::sqrt(1.0f - x * x));
  const Color albedo(0.7f, 0.5f, 0.3f);
  const std::string text =
      "image width=1 height=1 spp=1024 max_depth=2\n"
      "camera position=0.6,0,50 look_at=0.6,0,0 fov=0.5\n"
      "antialias sigma=0\n"
      "sphere center=0,0,0 radius=1 color=0.7,0.5,0.3\n";
  const Vec3 axis = glm::normalize(Vec3(0.4f, 1.0f, 0.3f));
  const glint::Scene sky_scene = under_sky(text, axis);
  const double sky_expected =
      irradiance(sky_scene.environment(), normal, albedo, 1024) / std::numbers::pi;
  // A furnace: a colour L all round, reflected as albedo x L.
  const glint::Scene colour_scene = glint::Scene::build(
      glint::read_scene_text(text + "background color=0.8,0.6,0.4\n", "colour furnace"));
  const double colour_expected = 0.7 * 0.8 + 0.5 * 0.6 + 0.3 * 0.4;
  glint_test::ComparisonFamily family;
  const auto check = [&]<typename R>() {
    for (const bool colour : {false, true}) {
      const glint::Scene& scene = colour ? colour_scene : sky_scene;
      const double expected = colour ? colour_expected : sky_expected;
      glint::RenderSettings settings = glint::RenderSettings::from(scene);
      settings.threads = 1;
      std::vector<double> differences;
      for (std::uint64_t seed = 1; seed <= 32; ++seed) {
        settings.seed = seed;
        const glint::RenderResult result = glint_test::render_by<R>(scene, settings);
        REQUIRE(result.stats.invalid_samples == 0);
        const Color c = result.film.at(0, 0);
        differences.push_back(double(c.x) + c.y + c.z - expected);
      }
      const glint_test::MeanEstimate difference = glint_test::estimate_mean(differences);
      const std::string name =
          glint_test::renderer_name<R>() + (colour ? " under a colour" : " under the sky");
      INFO(name << ": expected " << expected << ", rendered " << expected + difference.mean
                << " +- " << difference.standard_error);
      // The quadrature's error is well under 1e-3 of the value; the colour's is float rounding.
      family.add(name, glint_test::zero_mean_p_value(difference, 1e-3 * expected));
      CHECK(std::abs(difference.mean) < 0.05 * expected);
    }
  };
  check.template operator()<glint::Renderer<glint::variants::fast>>();
  check.template operator()<glint::Renderer<glint::variants::fast_no_emitter_sampling>>();
  check.template operator()<glint::Renderer<glint::variants::report>>();
  check.template operator()<glint::Renderer<glint::variants::emitter_sampling>>();
  check.template operator()<glint::Renderer<glint::variants::bidirectional>>();
  check.template operator()<glint::Renderer<glint::variants::vcm>>();
  family.check();
}

// A grey floor, a red ball, a glass ball, a mirror ball and a small warm lamp under the sky:
// light arrives from the image directly, through glass and by a mirror, and from the lamp, so
// that a light sample chooses between the image and the lamp.
constexpr const char* kSkyScene = R"(
image     width=16 height=16 spp=16 max_depth=4
camera    position=0,2.5,8 look_at=0,1,0 up=0,1,0 fov=45
antialias sigma=0.5
sphere    center=0,-100000,0 radius=1e5 color=0.6,0.6,0.6
sphere    center=-1.7,1,0 radius=1 color=0.8,0.3,0.2
sphere    center=1.7,1,0 radius=1 diffuse=0 transparent=1 ior=1.5
sphere    center=0,0.6,1.8 radius=0.6 diffuse=0.2 mirror=0.8
sphere    center=0,3.5,0 radius=0.3 diffuse=0 emission=6,5,4
)";

TEST_CASE(
    "under a sky, the path tracer with and without sampling it, bidirectional path tracing and "
    "vertex merging agree",
    "[render][environment][statistical]") {
  const glint::Scene scene = under_sky(kSkyScene);
  glint_test::ComparisonFamily family;
  const glint_test::BlockSamples sampled =
      glint_test::render_blocks<glint::Renderer<glint::variants::fast>>(scene, 100, 64);
  const double by_bounces = glint_test::compare_independent(
      family, "sky scene, bounces only against sampling the sky", sampled,
      glint_test::render_blocks<glint::Renderer<glint::variants::fast_no_emitter_sampling>>(
          scene, 200, 256));
  const double by_both = glint_test::compare_independent(
      family, "sky scene, bidirectional against path tracing", sampled,
      glint_test::render_blocks<glint::Renderer<glint::variants::bidirectional>>(scene, 300, 64));
  const double by_merging = glint_test::compare_independent(
      family, "sky scene, vertex merging against path tracing", sampled,
      glint_test::render_blocks<glint::Renderer<glint::variants::vcm>>(scene, 400, 64));
  CHECK(by_bounces > 0.01);
  CHECK(by_both > 0.01);
  CHECK(by_merging > 0.01);
  family.check();
}

TEST_CASE("under a sky, the wavefront renderer gives the scalar one's bits, for any threads",
          "[render][environment]") {
  const glint::Scene scene = under_sky(kSkyScene);
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.seed = 7;
  glint_test::check_same_image<glint::Renderer<glint::variants::fast>,
                               glint::WavefrontRenderer<glint::variants::fast>>(scene, settings);
  (void)glint_test::check_same_bits<glint::Renderer<glint::variants::fast>>(scene, settings);
  (void)glint_test::check_same_bits<glint::Renderer<glint::variants::bidirectional>>(scene,
                                                                                     settings);
  (void)glint_test::check_same_bits<glint::Renderer<glint::variants::vcm>>(scene, settings);
}

TEST_CASE("light tracing refuses a scene lit by an image, naming the background's line",
          "[render][environment]") {
  const glint::Scene scene = under_sky(
      "image width=4 height=4 spp=1\n"
      "background\n"
      "light position=0,4,0 intensity=10\n"
      "sphere center=0,0,0 radius=1\n");
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  CHECK_THROWS_WITH(
      (glint_test::render_by<glint::Renderer<glint::variants::light_tracing>>(scene, settings)),
      Catch::Contains("sky scene:2") && Catch::Contains("light tracing needs a black background"));
}

}  // namespace environment_render_test
