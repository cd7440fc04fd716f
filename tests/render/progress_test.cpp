// The progress callback of Renderer::render: called on the calling thread only, counting
// samples (so it moves within a pass), rising to width x height x spp and reaching it in the
// last call, which alone is marked last; elapsed time never decreasing; passes and the samples
// per pixel of the completed passes consistent with pass_ends; and calls that keep coming
// while a single sample takes as long as it likes.

#include <catch2/catch.hpp>

#include <atomic>
#include <thread>
#include <vector>

#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"
#include "small_scene.hpp"

namespace {

glint::Scene progress_scene() {
  return glint::test::small_scene("progress");
}

// Held closed, the first sample of pixel (0, 0) does not start: a sample that takes as long
// as the test wants, without relying on how fast the machine is.
std::atomic<bool> gate_open{true};

class GatedSampler : public glint::IndependentSampler {
 public:
  void start(const glint::PixelSample& s) {
    if (s.x == 0 && s.y == 0 && s.index == 0) gate_open.wait(false);
    IndependentSampler::start(s);
  }
};
using Gated = glint::variants::report::with_sampler<GatedSampler>;

}  // namespace

TEST_CASE("the progress callback counts samples on the calling thread", "[render][progress]") {
  const glint::Scene scene = progress_scene();
  struct Case {
    int width, height, tile, spp;
  };
  const Case c = GENERATE(Case{40, 23, 8, 9}, Case{16, 16, 16, 1}, Case{17, 16, 16, 40},
                          Case{1, 1, 16, 5}, Case{33, 7, 4, 64});
  const int threads = GENERATE(1, 2, 5);
  INFO(c.width << "x" << c.height << " pixels in tiles of " << c.tile << ", " << c.spp << " spp, "
               << threads << " threads");

  glint::RenderSettings settings;
  settings.width = c.width;
  settings.height = c.height;
  settings.tile_size = c.tile;
  settings.samples_per_pixel = c.spp;
  settings.max_pass_samples = 16;
  settings.max_depth = 4;
  settings.threads = threads;
  const std::vector<int> ends = glint::pass_ends(c.spp, 16);
  const std::uint64_t pixels = std::uint64_t(c.width) * std::uint64_t(c.height);
  const std::uint64_t total = pixels * std::uint64_t(c.spp);

  const std::thread::id caller = std::this_thread::get_id();
  std::vector<glint::RenderProgress> calls;
  bool other_thread = false;
  const glint::RenderResult result =
      glint_test::render_by<glint::Renderer<glint::variants::report>>(
          scene, settings, [&](const glint::RenderProgress& p) {
            other_thread = other_thread || std::this_thread::get_id() != caller;
            calls.push_back(p);
          });

  INFO(calls.size() << " calls");
  CHECK_FALSE(other_thread);
  // At least one call after every pass but the last, and the last call.
  REQUIRE(calls.size() >= ends.size());
  std::uint64_t previous = 0;
  double previous_elapsed = 0.0;
  int previous_passes = 0;
  for (std::size_t i = 0; i < calls.size(); ++i) {
    const glint::RenderProgress& p = calls[i];
    INFO("call " << i << ": " << p.samples_done << " of " << p.samples_total << " samples, "
                 << p.passes_done << " passes at " << p.elapsed_seconds << " s");
    CHECK(p.samples_total == total);
    CHECK(p.samples_done >= previous);
    CHECK(p.samples_done <= total);
    CHECK(p.last == (i + 1 == calls.size()));
    CHECK(p.elapsed_seconds >= previous_elapsed);
    CHECK(p.pass_count == int(ends.size()));
    CHECK(p.passes_done >= previous_passes);
    CHECK(p.passes_done <= p.pass_count);
    CHECK(p.samples_per_pixel_done == (p.passes_done ? ends[std::size_t(p.passes_done) - 1] : 0));
    // The completed passes' samples are all counted.
    CHECK(p.samples_done >= pixels * std::uint64_t(p.samples_per_pixel_done));
    CHECK(p.fraction() >= 0.0);
    CHECK(p.fraction() <= 1.0);
    CHECK(p.fraction() == double(p.samples_done) / double(total));
    previous = p.samples_done;
    previous_elapsed = p.elapsed_seconds;
    previous_passes = p.passes_done;
  }
  CHECK(calls.back().samples_done == total);
  CHECK(calls.back().fraction() == 1.0);
  CHECK(calls.back().passes_done == int(ends.size()));
  CHECK(calls.back().samples_per_pixel_done == c.spp);
  CHECK(calls.back().elapsed_seconds <= result.stats.seconds);
}

TEST_CASE("progress keeps coming while a sample takes long", "[render][progress]") {
  const glint::Scene scene = progress_scene();
  glint::RenderSettings settings;
  settings.width = 8;
  settings.height = 8;
  settings.samples_per_pixel = 4;
  settings.max_depth = 2;
  settings.tile_size = 2;  // 16 tiles: with 3 threads, the others render while one is stuck
  const int threads = GENERATE(1, 3);
  settings.threads = threads;

  // The gate opens only after the callback has been called three times with no sample done:
  // without calls on a timer while no tile (not even a sample) completes, this would hang.
  gate_open = false;
  int calls_while_stuck = 0;
  bool last_seen = false;
  const glint::RenderResult result = glint_test::render_by<glint::Renderer<Gated>>(
      scene, settings, [&](const glint::RenderProgress& p) {
        if (!gate_open && (threads > 1 || p.samples_done == 0) && p.passes_done == 0 &&
            ++calls_while_stuck == 3) {
          gate_open = true;
          gate_open.notify_all();
        }
        last_seen = p.last;
      });
  CHECK(calls_while_stuck == 3);
  CHECK(last_seen);
  CHECK(result.complete());
}

TEST_CASE("the progress callback does not change the image", "[render][progress]") {
  const glint::Scene scene = progress_scene();
  glint::RenderSettings settings;
  settings.width = 24;
  settings.height = 20;
  settings.tile_size = 8;
  settings.samples_per_pixel = 2;
  settings.threads = 2;
  int calls = 0;
  const glint::RenderResult with = glint_test::render_by<glint::Renderer<glint::variants::report>>(
      scene, settings, [&](const glint::RenderProgress&) { ++calls; });
  const glint::RenderResult without =
      glint_test::render_by<glint::Renderer<glint::variants::report>>(scene, settings);
  CHECK(calls >= 2);
  CHECK(with.film.pixels() == without.film.pixels());
}

TEST_CASE("a progress with no samples counts as done", "[render][progress]") {
  CHECK(glint::RenderProgress{0, 0, 0.0}.fraction() == 1.0);
  CHECK(glint::RenderProgress{3, 12, 0.5}.fraction() == 0.25);
}
