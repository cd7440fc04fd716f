// The progress callback of Renderer::render: called on the calling thread only, with
// tiles_done rising to tiles_total = ceil(width / tile) * ceil(height / tile) and reaching it
// exactly once, in the last call; elapsed time never decreasing; fraction() in [0, 1].

#include <catch2/catch.hpp>

#include <thread>
#include <vector>

#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"

namespace {

glint::Scene small_scene() {
  glint::SceneDescription d;
  d.source = "progress";
  d.camera.position = {0.0f, 0.0f, 10.0f};
  glint::SphereDescription sphere;
  sphere.radius = 3.0f;
  d.spheres.push_back(sphere);
  glint::SphereDescription glass;
  glass.center = {2.0f, 1.0f, 3.0f};
  glass.material.diffuse = 0.0f;
  glass.material.transparent = 1.0f;
  d.spheres.push_back(glass);
  d.lights.push_back({{5.0f, 5.0f, 10.0f}, 100.0f, glint::Color(1.0f), 1});
  return glint::Scene::build(d);
}

}  // namespace

TEST_CASE("the progress callback counts tiles on the calling thread", "[render][progress]") {
  const glint::Scene scene = small_scene();
  struct Case {
    int width, height, tile;
    std::size_t tiles;  // ceil(width / tile) * ceil(height / tile), worked out by hand
  };
  const Case c = GENERATE(Case{40, 23, 8, 15}, Case{16, 16, 16, 1}, Case{17, 16, 16, 2},
                          Case{1, 1, 16, 1}, Case{33, 7, 4, 18});
  const int threads = GENERATE(1, 2, 5);
  INFO(c.width << "x" << c.height << " pixels in tiles of " << c.tile << ", " << threads
               << " threads");

  glint::RenderSettings settings;
  settings.width = c.width;
  settings.height = c.height;
  settings.tile_size = c.tile;
  // Enough work per tile (about a millisecond) that the calling thread usually wakes between
  // tiles and reports them as they come; how often it does is up to the scheduler.
  settings.samples_per_pixel = 64;
  settings.max_depth = 4;
  settings.threads = threads;

  const std::thread::id caller = std::this_thread::get_id();
  std::vector<glint::RenderProgress> calls;
  bool other_thread = false;
  const glint::RenderResult result = glint::Renderer<glint::variants::report>::render(
      scene, settings, [&](const glint::RenderProgress& p) {
        other_thread = other_thread || std::this_thread::get_id() != caller;
        calls.push_back(p);
      });

  INFO(calls.size() << " calls");
  CHECK_FALSE(other_thread);
  REQUIRE(!calls.empty());
  CHECK(calls.size() <= c.tiles);
  std::size_t previous = 0;
  double previous_elapsed = 0.0;
  for (std::size_t i = 0; i < calls.size(); ++i) {
    const glint::RenderProgress& p = calls[i];
    INFO("call " << i << ": " << p.tiles_done << " of " << p.tiles_total << " tiles at "
                 << p.elapsed_seconds << " s");
    CHECK(p.tiles_total == c.tiles);
    CHECK(p.tiles_done > previous);
    CHECK(p.tiles_done <= p.tiles_total);
    CHECK((p.tiles_done == p.tiles_total) == (i + 1 == calls.size()));
    CHECK(p.elapsed_seconds >= previous_elapsed);
    CHECK(p.fraction() >= 0.0);
    CHECK(p.fraction() <= 1.0);
    CHECK(p.fraction() == double(p.tiles_done) / double(c.tiles));
    previous = p.tiles_done;
    previous_elapsed = p.elapsed_seconds;
  }
  CHECK(calls.back().tiles_done == c.tiles);
  CHECK(calls.back().fraction() == 1.0);
  CHECK(calls.back().elapsed_seconds <= result.stats.seconds);
}

TEST_CASE("the progress callback does not change the image", "[render][progress]") {
  const glint::Scene scene = small_scene();
  glint::RenderSettings settings;
  settings.width = 24;
  settings.height = 20;
  settings.tile_size = 8;
  settings.samples_per_pixel = 2;
  settings.threads = 2;
  int calls = 0;
  const glint::RenderResult with = glint::Renderer<glint::variants::report>::render(
      scene, settings, [&](const glint::RenderProgress&) { ++calls; });
  const glint::RenderResult without =
      glint::Renderer<glint::variants::report>::render(scene, settings);
  CHECK(calls >= 1);
  CHECK(with.film.pixels() == without.film.pixels());
}

TEST_CASE("a progress with no tiles counts as done", "[render][progress]") {
  CHECK(glint::RenderProgress{0, 0, 0.0}.fraction() == 1.0);
  CHECK(glint::RenderProgress{3, 12, 0.5}.fraction() == 0.25);
}
