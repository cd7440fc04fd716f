// The equirectangular camera rendered: inside a glowing sphere every pixel, poles and seam
// included, sees its emission; the path tracer, light tracing, bidirectional path tracing and
// vertex merging agree on a room seen whole (light tracing and the joins to the camera go
// through the panorama's connection and importance); the wavefront gives the scalar renderer's
// bits, and the splatting estimators the same bits for any threads, tiles and passes.

#include <catch2/catch.hpp>
#include <string>

#include "../support/significance.hpp"
#include "block_statistics.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"
#include "same_bits.hpp"

namespace panorama_render_test {

glint::Scene build(const std::string& text, const char* label) {
  return glint::Scene::build(glint::read_scene_text(text, label));
}

TEST_CASE("a panorama inside a glowing sphere sees its emission in every pixel",
          "[render][panorama]") {
  const glint::Scene scene = build(
      "image width=24 height=12 spp=4 max_depth=3\n"
      "camera position=0.3,-0.2,0.1 look_at=1,0.5,-2 projection=equirectangular\n"
      "sphere center=0,0,0 radius=5 diffuse=0 emission=0.25,0.5,2\n",
      "inside");
  const auto check = [&]<typename R>() {
    INFO(glint_test::renderer_name<R>());
    const glint::RenderResult result =
        glint_test::render_by<R>(scene, glint::RenderSettings::from(scene));
    int wrong = 0;
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 24; ++x)
        wrong += glm::length(result.film.at(x, y) - glint::Color(0.25f, 0.5f, 2.0f)) > 1e-5f;
    CHECK(wrong == 0);
  };
  check.template operator()<glint::Renderer<glint::variants::fast>>();
  check.template operator()<glint::WavefrontRenderer<glint::variants::fast>>();
  check.template operator()<glint::Renderer<glint::variants::report>>();
}

/// A room seen whole from inside it: a point light, a lamp, coloured walls and two balls, all
/// diffuse: every estimator sees all of its light (light tracing misses what a mirror shows, the
/// path tracer a point light's caustic, and vertex merging blurs a glossy reflection).
constexpr const char* kRoom = R"(
image     width=16 height=16 spp=4 max_depth=6
camera    position=0,1,0 look_at=0,1,-1 projection=equirectangular near=0.1
antialias sigma=0.5
light     position=1.5,2.5,1 intensity=30
sphere    center=0,-100000,0 radius=1e5 color=0.6,0.6,0.6
sphere    center=0,100004,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,-100004 radius=1e5 color=0.7,0.3,0.2
sphere    center=0,0,100004 radius=1e5 color=0.2,0.5,0.7
sphere    center=-100004,0,0 radius=1e5 color=0.5,0.5,0.5
sphere    center=100004,0,0 radius=1e5 color=0.4,0.6,0.3
sphere    center=-1.5,0.7,-1.5 radius=0.7 color=0.9,0.8,0.3
sphere    center=1.2,0.6,-2 radius=0.6 color=0.3,0.5,0.9
sphere    center=-2,3,2 radius=0.4 diffuse=0 emission=15,14,12
)";

TEST_CASE(
    "a panorama: light tracing, bidirectional path tracing and vertex merging agree with the "
    "path tracer",
    "[render][panorama][statistical]") {
  const glint::Scene scene = build(kRoom, "panorama room");
  glint_test::ComparisonFamily family;
  const glint_test::BlockSamples path =
      glint_test::render_blocks<glint::Renderer<glint::variants::fast>>(scene, 100, 64);
  const double by_light = glint_test::compare_independent(
      family, "panorama room, light tracing against path tracing", path,
      glint_test::render_blocks<glint::Renderer<glint::variants::light_tracing>>(scene, 200, 256));
  const double by_both = glint_test::compare_independent(
      family, "panorama room, bidirectional against path tracing", path,
      glint_test::render_blocks<glint::Renderer<glint::variants::bidirectional>>(scene, 300, 64));
  const double by_merging = glint_test::compare_independent(
      family, "panorama room, vertex merging against path tracing", path,
      glint_test::render_blocks<glint::Renderer<glint::variants::vcm>>(scene, 400, 64));
  CHECK(by_light > 0.01);
  CHECK(by_both > 0.01);
  CHECK(by_merging > 0.01);
  family.check();
}

TEST_CASE("a panorama gives the same bits at every width, thread count, tile and pass",
          "[render][panorama]") {
  const glint::Scene scene = build(kRoom, "panorama room");
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.width = 20;
  settings.height = 10;
  settings.threads = 2;
  glint_test::check_same_image<glint::Renderer<glint::variants::fast>,
                               glint::WavefrontRenderer<glint::variants::fast>>(scene, settings);
  (void)glint_test::check_same_bits<glint::Renderer<glint::variants::light_tracing>>(scene,
                                                                                     settings);
  (void)glint_test::check_same_bits<glint::Renderer<glint::variants::bidirectional>>(scene,
                                                                                     settings);
  (void)glint_test::check_same_bits<glint::Renderer<glint::variants::vcm>>(scene, settings);
}

}  // namespace panorama_render_test
