// Glass spheres that touch as written in decimals: a radius-12.6 ball centred 87.4 from the
// centre of a radius-100 ball, which read as floats pokes 1.9e-6 out of it. The scene format
// allows touching, so the scene renders (the inner ball inside the outer, in its glass), with
// every sample finite, for the tree and the chain estimators.

#include <catch2/catch.hpp>
#include <cmath>

#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"

TEMPLATE_TEST_CASE("glass touching glass from inside, written in decimals, renders",
                   "[render][inclusion]", glint::variants::report, glint::variants::fast) {
  const glint::SceneDescription description = glint::read_scene_text(
      "image width=16 height=16 spp=4 max_depth=6\n"
      "camera position=0,0,400 look_at=0,0,0 fov=40\n"
      "background color=0.2,0.3,0.4\n"
      "light position=0,300,300 intensity=100000\n"
      "sphere center=0,0,0 radius=100 transparent=1 diffuse=0 ior=1.5\n"
      "sphere center=87.4,0,0 radius=12.6 transparent=1 diffuse=0 ior=1.2\n"
      "sphere center=0,-87.4,0 radius=12.6 diffuse=1 color=0.8,0.8,0.8\n",
      "touching.scene");
  REQUIRE(double(87.4f) + double(12.6f) > 100.0);  // the overlap that rounding makes
  const glint::Scene scene = glint::Scene::build(description);
  CHECK(scene.surface(1).ior_outside == 1.5f);
  CHECK(scene.surface(2).ior_outside == 1.5f);
  const glint::RenderResult result =
      glint_test::render_by<glint::Renderer<TestType>>(scene, glint::RenderSettings::from(scene));
  CHECK(result.stats.invalid_samples == 0);
  bool lit = false;
  for (const glint::Color& c : result.film.pixels()) {
    CHECK((std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)));
    lit = lit || c.x > 0.0f;
  }
  CHECK(lit);
}
