// The bound on the tree model's rays per sample, against the closed form of the recursion
// it stands for, and the refusal it drives: the report's model refuses a room with a
// mirror-and-glass ball 20 bounces deep before tracing a ray, one-lobe variants render it.

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"

namespace {

// A closed room (so no path escapes early) with one ball that splits every ray into a
// mirror and a transmission ray, and one point light.
std::string split_room(int max_depth) {
  return "image width=4 height=4 spp=1 max_depth=" + std::to_string(max_depth) + R"(
camera position=0,0,30 look_at=0,0,0 up=0,1,0 fov=40
light position=0,20,0 intensity=100
sphere center=0,0,0 radius=1e3 color=0.5,0.5,0.5
sphere center=0,0,0 radius=5 mirror=0.3 transparent=0.7
)";
}

glint::Scene build(const std::string& text) {
  return glint::Scene::build(glint::read_scene_text(text, "split-room"));
}

}  // namespace

TEST_CASE("work estimate: the tree bound is the geometric sum of the branching") {
  // Each hit traces itself and s shadow rays, then b children while depth < D:
  // R = (1 + s) (b^(D+1) - 1) / (b - 1).
  const glint::Scene scene = build(split_room(3));
  for (const int depth : {0, 1, 3, 10, 19}) {
    for (const int shadow : {0, 1, 4}) {
      const glint::TreeWork work = glint::estimate_tree_work(scene, depth, shadow);
      CHECK(work.branching == 2);
      CHECK(work.widest_sphere == 1u);
      CHECK(work.rays_per_sample == Approx((1.0 + shadow) * (std::pow(2.0, depth + 1) - 1.0)));
    }
  }
  // One lobe per sphere: linear in depth.
  const glint::Scene plain = build(
      "sphere center=0,0,0 radius=1e3 color=0.5,0.5,0.5\nsphere center=0,0,0 radius=5 "
      "mirror=1\n");
  CHECK(glint::estimate_tree_work(plain, 12, 1).rays_per_sample == Approx(2.0 * 13));
  // Deep enough to overflow a double: capped, not infinite.
  const glint::TreeWork huge = glint::estimate_tree_work(scene, glint::limits::max_depth, 1);
  CHECK(std::isfinite(huge.rays_per_sample));
  CHECK(huge.rays_per_sample > glint::limits::max_tree_rays_per_sample);
}

TEST_CASE("work estimate: the tree model refuses an exponential scene, one-lobe variants do not") {
  const glint::Scene scene = build(split_room(20));
  const glint::RenderSettings settings = glint::RenderSettings::from(scene);
  // 2 (2^21 - 1) rays per sample: over the limit of 2^20.
  try {
    (void)glint_test::render_by<glint::Renderer<glint::variants::report>>(scene, settings);
    FAIL("the report's model rendered a scene beyond the work limit");
  } catch (const glint::SettingsError& error) {
    const std::string message = error.what();
    CHECK_THAT(message, Catch::Contains("tree model would trace up to"));
    CHECK_THAT(message, Catch::Contains("line 5 of split-room"));
    // 2 (2^(D+1) - 1) <= 2^20 holds up to D = 18.
    CHECK_THAT(message, Catch::Contains("Lower max_depth to 18"));
  }
  CHECK_NOTHROW(glint_test::render_by<glint::Renderer<glint::variants::fast>>(scene, settings));
  CHECK_NOTHROW(glint_test::render_by<glint::Renderer<glint::variants::stochastic_material>>(
      scene, settings));
  // The depth the message offers is the deepest within the limit.
  CHECK(glint::estimate_tree_work(scene, 18, 1).rays_per_sample <=
        glint::limits::max_tree_rays_per_sample);
  CHECK(glint::estimate_tree_work(scene, 19, 1).rays_per_sample >
        glint::limits::max_tree_rays_per_sample);
}
