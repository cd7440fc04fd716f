// Rough and metal mirrors rendered (render/materials/microfacet_material.hpp): a rough mirror in
// a uniform background shows the background times its directional albedo, worked out here from
// the textbook forms (a furnace: single scattering on a convex sphere); the path tracer, light
// tracing and bidirectional path tracing agree on a room of rough metals (every estimator takes
// the lobe through the Bsdf, unchanged); vertex merging and bidirectional path tracing give the
// same bits for any threads, tiles and passes there; a scene without rough or metal mirrors
// renders to the bit as with the report's material; a mirror smoother than the narrowest
// microfacet lobe renders as the ideal one; and the report's material refuses a rough mirror.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/microfacet_reference.hpp"
#include "../support/significance.hpp"
#include "block_statistics.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "renderer_types.hpp"
#include "same_bits.hpp"

namespace microfacet_render_test {

using glint::Color;

glint::Scene build(const std::string& text, const char* label) {
  return glint::Scene::build(glint::read_scene_text(text, label));
}

/// A unit sphere with a rough mirror of `roughness` in a background of radiance `background`,
/// seen by one pixel whose ray (through its centre: sigma 0) travels along -z and meets the
/// sphere at angle `theta` from its normal.
std::string furnace(float roughness, double theta) {
  const double x = std::sin(theta);
  return "image width=1 height=1 spp=4096 max_depth=3\n"
         "camera position=" +
         std::to_string(x) + ",0,50 look_at=" + std::to_string(x) +
         ",0,0 fov=0.5\n"
         "antialias sigma=0\n"
         "background color=1,0.5,0.25\n"
         "sphere center=0,0,0 radius=1 mirror=1 mirror_roughness=" +
         std::to_string(roughness) + "\n";
}

TEST_CASE("a rough mirror in a uniform background shows the background times its albedo",
          "[render][microfacet][statistical]") {
  glint_test::ComparisonFamily family;
  for (const float roughness : {0.3f, 0.7f, 1.0f})
    for (const double theta : {0.0, 1.0}) {
      const glint::Scene scene = build(furnace(roughness, theta), "furnace");
      glint::RenderSettings settings = glint::RenderSettings::from(scene);
      settings.threads = 1;
      // Light leaves the sphere at the pixel's angle; nothing reflected hits it again (it is
      // convex), so the pixel is the background times the directional albedo there.
      const double albedo = glint_test::textbook_ggx_albedo(double(roughness) * roughness, theta);
      const double expected = 1.75 * albedo;
      std::vector<double> differences;
      for (std::uint64_t seed = 1; seed <= 32; ++seed) {
        settings.seed = seed;
        const glint::RenderResult result =
            glint_test::render_by<glint::Renderer<glint::variants::fast>>(scene, settings);
        REQUIRE(result.stats.invalid_samples == 0);
        const Color c = result.film.at(0, 0);
        differences.push_back(double(c.x) + c.y + c.z - expected);
      }
      const glint_test::MeanEstimate difference = glint_test::estimate_mean(differences);
      INFO("roughness " << roughness << ", theta " << theta << ": expected " << expected
                        << ", rendered " << expected + difference.mean << " +- "
                        << difference.standard_error);
      // The quadrature's error is well under 2e-5 of the value.
      family.add("roughness " + std::to_string(roughness) + ", theta " + std::to_string(theta),
                 glint_test::zero_mean_p_value(difference, 2e-5 * expected));
      CHECK(std::abs(difference.mean) < 0.05 * expected);
    }
  family.check();
}

// A gold ball and a ball of aluminium over blue paint filling most of the view, before a floor
// and a back wall, lit by a point light and a small lamp, on black: every light path there is
// a rough reflection or a diffuse one, which the path tracer, light tracing and bidirectional
// path tracing all reach.
constexpr const char* kRoughRoom = R"(
image     width=16 height=16 spp=16 max_depth=5
camera    position=0,2.5,8 look_at=0,1.5,0 up=0,1,0 fov=40
antialias sigma=0.5
light     position=-3,7,6 intensity=150
sphere    center=0,-100000,0 radius=1e5 color=0.6,0.6,0.6
sphere    center=0,0,-100006 radius=1e5 color=0.5,0.55,0.6
sphere    center=-1.6,1.5,0 radius=1.5 metal=gold mirror_roughness=0.45
sphere    center=1.6,1.5,0 radius=1.5 metal=aluminium mirror_roughness=0.6 mirror=0.7 color=0.3,0.5,0.8
sphere    center=2,5,3 radius=0.5 diffuse=0 emission=25,22,18
)";

TEST_CASE("rough metals: light tracing and bidirectional path tracing agree with the path tracer",
          "[render][microfacet][statistical]") {
  const glint::Scene scene = build(kRoughRoom, "rough room");
  glint_test::ComparisonFamily family;
  const glint_test::BlockSamples path =
      glint_test::render_blocks<glint::Renderer<glint::variants::fast>>(scene, 100, 64);
  const double by_light = glint_test::compare_independent(
      family, "rough room, light tracing against path tracing", path,
      glint_test::render_blocks<glint::Renderer<glint::variants::light_tracing>>(scene, 200, 1024));
  const double by_both = glint_test::compare_independent(
      family, "rough room, bidirectional against path tracing", path,
      glint_test::render_blocks<glint::Renderer<glint::variants::bidirectional>>(scene, 300, 64));
  CHECK(by_light > 0.01);
  CHECK(by_both > 0.01);
  family.check();
}

TEST_CASE(
    "rough metals: bidirectional estimators give the same bits for any threads, tiles and "
    "passes, and after a resume",
    "[render][microfacet]") {
  const glint::Scene scene = build(kRoughRoom, "rough room");
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.seed = 5;
  (void)glint_test::check_same_bits<glint::Renderer<glint::variants::bidirectional>>(scene,
                                                                                     settings);
  (void)glint_test::check_same_bits<glint::Renderer<glint::variants::vcm>>(scene, settings);
}

TEST_CASE(
    "without rough or metal mirrors, the microfacet material renders the report's image "
    "to the bit",
    "[render][microfacet]") {
  using Microfacet = glint::variants::fast;
  using Ideal = glint::variants::fast_ideal_mirrors;
  int compared = 0;
  for (const std::filesystem::path& file : glint_test::comparison_scenes()) {
    const glint::Scene scene = glint::Scene::build(glint::read_scene_file(file.string()));
    if (!glint::is_supported<Ideal>(scene)) continue;
    INFO(file.filename().string());
    glint::RenderSettings settings = glint::RenderSettings::from(scene);
    settings.width = 12;
    settings.height = 10;
    settings.samples_per_pixel = 4;
    settings.seed = 3;
    const glint::RenderResult a =
        glint_test::render_by<glint::Renderer<Microfacet>>(scene, settings);
    const glint::RenderResult b = glint_test::render_by<glint::Renderer<Ideal>>(scene, settings);
    CHECK(glint_test::same_bits(a.film, b.film));
    ++compared;
  }
  CHECK(compared >= 20);
}

TEST_CASE("a mirror smoother than the narrowest microfacet lobe renders as the ideal mirror",
          "[render][microfacet]") {
  const std::string ideal = R"(
image  width=12 height=10 spp=4 max_depth=4
camera position=0,2,12 look_at=0,1,0
light  position=3,8,6 intensity=80
sphere center=0,-100000,0 radius=1e5 color=0.6,0.6,0.6
sphere center=0,1,0 radius=1 mirror=0.7 mirror_color=0.9,0.8,0.7 metal=copper)";
  std::string barely_rough = ideal;
  barely_rough += " mirror_roughness=0.03\n";
  glint::RenderSettings settings = glint::RenderSettings::from(build(ideal, "ideal"));
  settings.seed = 9;
  const glint::RenderResult a = glint_test::render_by<glint::Renderer<glint::variants::fast>>(
      build(ideal, "ideal"), settings);
  const glint::RenderResult b = glint_test::render_by<glint::Renderer<glint::variants::fast>>(
      build(barely_rough, "barely rough"), settings);
  CHECK(glint_test::same_bits(a.film, b.film));
}

TEST_CASE("the report's material refuses a rough or metal mirror, naming its line",
          "[render][microfacet]") {
  for (const char* key : {"mirror_roughness=0.5", "metal=silver"}) {
    const glint::Scene scene =
        build(std::string("sphere center=0,0,0 radius=1\nsphere center=3,0,0 radius=1 mirror=1 ") +
                  key + "\n",
              "refused");
    INFO(key);
    CHECK_FALSE(glint::is_supported<glint::variants::report>(scene));
    CHECK(glint::is_supported<glint::variants::fast>(scene));
    try {
      glint::check_supported<glint::variants::report>(scene);
      FAIL("accepted");
    } catch (const glint::UnsupportedSceneError& error) {
      CHECK(std::string(error.what()).find(":2:") != std::string::npos);
      CHECK(std::string(error.what()).find("rough or metal mirror") != std::string::npos);
    }
  }
}

}  // namespace microfacet_render_test
