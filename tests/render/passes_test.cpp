// Progressive passes: the schedule of pass_ends, the finished image bit for bit the one-shot
// render_pixel mean, a stopped render bit for bit the mean of the samples of its completed
// passes, and neither depending on the thread count, the tile size or where a stop comes from.
// Renderer::render_tiles: the passes' tiles handed out by the caller, in any order and split
// across several sets of sums (as glint-render-mpi's processes hold them), give render()'s
// image bit for bit as long as each tile's passes come in order from the sums they left.

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <deque>
#include <mutex>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "glint/render/renderer.hpp"
#include "glint/render/tile_grid.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"
#include "small_scene.hpp"

namespace {

glint::Scene passes_scene() {
  return glint::test::small_scene("passes");
}

glint::RenderSettings small_settings(int spp, int max_pass, int threads, int tile) {
  glint::RenderSettings settings;
  settings.width = 19;
  settings.height = 13;
  settings.samples_per_pixel = spp;
  settings.max_pass_samples = max_pass;
  settings.max_depth = 4;
  settings.threads = threads;
  settings.tile_size = tile;
  settings.seed = 3;
  return settings;
}

using glint_test::same_bits;

/// The image of each pixel's first `samples` samples, summed in one go by render_pixel.
template <typename V>
glint::Film one_shot(const glint::Scene& scene, const glint::RenderSettings& settings,
                     int samples) {
  const glint::Camera camera(scene.camera(), settings.width, settings.height);
  const glint::PathTracer<V> tracer(scene, settings.max_depth);
  glint::TraceCounters counters;
  glint::Film film(settings.width, settings.height);
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x)
      film.at(x, y) = glint::ScalarExecution<V>::render_pixel(tracer, camera, settings, x, y,
                                                              counters, samples);
  return film;
}

/// A render stopped by the pass callback once `passes` passes are done.
template <typename V>
glint::RenderResult stopped_after(const glint::Scene& scene, const glint::RenderSettings& settings,
                                  int passes) {
  glint::RenderControl control;
  control.pass_done = [&](const glint::PassReport& r) { return r.passes_done < passes; };
  return glint_test::render_by<glint::Renderer<V>>(scene, settings, control);
}

/// A fixed list of pieces, handed out in order; counts what finished.
class ListSource {
 public:
  explicit ListSource(std::vector<glint::TileWork> work) : work_(work.begin(), work.end()) {}
  std::optional<glint::TileWork> next() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (work_.empty()) return std::nullopt;
    glint::TileWork piece = work_.front();
    work_.pop_front();
    return piece;
  }
  void finished(const glint::TileWork& piece) {
    const std::lock_guard<std::mutex> lock(mutex_);
    finished_.push_back(piece.id);
  }
  const std::vector<std::uint64_t>& finished_ids() const { return finished_; }

 private:
  std::mutex mutex_;
  std::deque<glint::TileWork> work_;
  std::vector<std::uint64_t> finished_;
};

void copy_tile(const glint::Tile& tile, const glint::PixelSums& from, glint::PixelSums& to) {
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x)
      to.at(x, y) = from.at(x, y);
}

}  // namespace

TEST_CASE("pass_ends: one sample, then doubling up to the cap, ending at the spp", "[passes]") {
  using glint::pass_ends;
  CHECK(pass_ends(1, 32) == std::vector<int>{1});
  CHECK(pass_ends(2, 32) == std::vector<int>{1, 2});
  CHECK(pass_ends(5, 32) == std::vector<int>{1, 2, 4, 5});
  CHECK(pass_ends(16, 32) == std::vector<int>{1, 2, 4, 8, 16});
  CHECK(pass_ends(13, 4) == std::vector<int>{1, 2, 4, 8, 12, 13});
  CHECK(pass_ends(100, 32) == std::vector<int>{1, 2, 4, 8, 16, 32, 64, 96, 100});
  CHECK(pass_ends(3, 1) == std::vector<int>{1, 2, 3});
  for (const int spp : {1, 7, 1000, glint::limits::max_samples_per_pixel}) {
    for (const int cap : {1, 3, 32, glint::limits::max_samples_per_pixel}) {
      INFO(spp << " spp, at most " << cap << " a pass");
      const std::vector<int> ends = pass_ends(spp, cap);
      REQUIRE(!ends.empty());
      CHECK(ends.front() == 1);
      CHECK(ends.back() == spp);
      int previous = 0;
      std::size_t bad_steps = 0;  // counted, not checked one by one: there can be a million
      for (const int end : ends) {
        if (end <= previous || end - previous > std::max(1, std::min(cap, previous))) ++bad_steps;
        previous = end;
      }
      CHECK(bad_steps == 0);
    }
  }
}

TEST_CASE("max_pass_samples is checked", "[passes]") {
  glint::RenderSettings settings = small_settings(4, 0, 1, 8);
  CHECK_THROWS_AS(glint::validate(settings), glint::SettingsError);
  settings.max_pass_samples = glint::limits::max_samples_per_pixel + 1;
  CHECK_THROWS_AS(glint::validate(settings), glint::SettingsError);
  settings.max_pass_samples = 1;
  CHECK_NOTHROW(glint::validate(settings));
}

TEMPLATE_TEST_CASE("all passes give the one-shot image bit for bit", "[passes]",
                   glint::variants::report, glint::variants::fast) {
  const glint::Scene scene = passes_scene();
  const int threads = GENERATE(1, 2, 5);
  const int tile = GENERATE(4, 16);
  const int max_pass = GENERATE(1, 4, 32);
  INFO(threads << " threads, tiles of " << tile << ", at most " << max_pass << " a pass");
  const glint::RenderSettings settings = small_settings(13, max_pass, threads, tile);

  const glint::RenderResult result =
      glint_test::render_by<glint::Renderer<TestType>>(scene, settings);
  CHECK(result.complete());
  CHECK(result.samples_per_pixel == 13);
  CHECK(result.passes_done == int(glint::pass_ends(13, max_pass).size()));
  CHECK(result.pass_count == result.passes_done);
  CHECK(result.stats.samples == 19u * 13u * 13u);
  CHECK(same_bits(result.film, one_shot<TestType>(scene, settings, 13)));
}

TEMPLATE_TEST_CASE("a render stopped after k passes holds exactly those passes' samples",
                   "[passes]", glint::variants::report, glint::variants::fast) {
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings base = small_settings(13, 4, 1, 8);
  const std::vector<int> ends = glint::pass_ends(13, 4);  // 1, 2, 4, 8, 12, 13
  const int passes = GENERATE(1, 2, 3, 5);
  const int samples = ends[std::size_t(passes) - 1];
  INFO("stopped after pass " << passes << ", " << samples << " samples per pixel");
  const glint::Film expected = one_shot<TestType>(scene, base, samples);

  for (const int threads : {1, 2, 5}) {
    INFO(threads << " threads");
    glint::RenderSettings settings = base;
    settings.threads = threads;
    const glint::RenderResult result = stopped_after<TestType>(scene, settings, passes);
    CHECK_FALSE(result.complete());
    CHECK(result.passes_done == passes);
    CHECK(result.pass_count == 6);
    CHECK(result.samples_per_pixel == samples);
    CHECK(result.stats.samples == 19u * 13u * std::uint64_t(samples));
    CHECK(same_bits(result.film, expected));
  }
}

TEST_CASE("the pass callback sees each pass's image, the one a stop there returns", "[passes]") {
  using V = glint::variants::report;
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings settings = small_settings(13, 4, 2, 8);
  const std::vector<int> ends = glint::pass_ends(13, 4);
  std::vector<glint::Film> images;
  std::vector<int> samples;
  glint::RenderControl control;
  control.pass_done = [&](const glint::PassReport& r) {
    CHECK(r.passes_done == int(images.size()) + 1);
    CHECK(r.pass_count == int(ends.size()));
    images.push_back(r.image());
    samples.push_back(r.samples_per_pixel);
    return true;
  };
  const glint::RenderResult result =
      glint_test::render_by<glint::Renderer<V>>(scene, settings, control);
  CHECK(samples == ends);
  REQUIRE(images.size() == ends.size());
  CHECK(same_bits(images.back(), result.film));
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    INFO("pass " << k + 1);
    CHECK(same_bits(images[k], stopped_after<V>(scene, settings, int(k) + 1).film));
  }
}

TEST_CASE("a stop request ends the render after the current pass", "[passes]") {
  using V = glint::variants::report;
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings settings = small_settings(13, 4, 2, 8);
  std::atomic<bool> stop{false};

  SECTION("requested before the render: nothing is rendered") {
    stop = true;
    const glint::RenderResult result = glint_test::render_by<glint::Renderer<V>>(
        scene, settings, glint::RenderControl{{}, {}, &stop});
    CHECK(result.passes_done == 0);
    CHECK(result.samples_per_pixel == 0);
    CHECK(result.stats.samples == 0);
    CHECK(result.film.width() == 19);
    for (const glint::Color& c : result.film.pixels())
      CHECK(c == glint::Color(0.0f));
  }
  SECTION("requested while rendering, as a signal handler would: the current pass completes") {
    // Set from the progress callback (on the calling thread, while workers render): whichever
    // pass is running then completes, and no other starts.
    int passes_at_request = -1;
    glint::RenderControl control;
    control.stop = &stop;
    control.progress = [&](const glint::RenderProgress& p) {
      if (passes_at_request < 0 && p.passes_done >= 2) {
        passes_at_request = p.passes_done;
        stop = true;
      }
    };
    const glint::RenderResult result =
        glint_test::render_by<glint::Renderer<V>>(scene, settings, control);
    REQUIRE(passes_at_request >= 2);
    CHECK(result.passes_done >= passes_at_request);
    CHECK(result.passes_done <= passes_at_request + 1);
    CHECK(result.samples_per_pixel == glint::pass_ends(13, 4)[std::size_t(result.passes_done) - 1]);
    CHECK(same_bits(result.film, one_shot<V>(scene, settings, result.samples_per_pixel)));
  }
}

TEST_CASE("keep_sums returns the sums of the passes done, as the last pass reported them",
          "[passes]") {
  using V = glint::variants::report;
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings settings = small_settings(13, 4, 2, 8);
  std::vector<glint::ColorSum> reported;
  glint::RenderControl control;
  control.pass_done = [&](const glint::PassReport& r) {
    reported = r.sums.pixels();
    return r.passes_done < 3;  // stop after pass 3 of 5
  };
  control.keep_sums = true;
  const glint::RenderResult kept =
      glint_test::render_by<glint::Renderer<V>>(scene, settings, control);
  REQUIRE(kept.passes_done == 3);
  REQUIRE(kept.sums.pixels().size() == reported.size());
  CHECK(std::memcmp(kept.sums.pixels().data(), reported.data(),
                    reported.size() * sizeof(glint::ColorSum)) == 0);
  control.keep_sums = false;
  CHECK(glint_test::render_by<glint::Renderer<V>>(scene, settings, control).sums.pixels().empty());
}

TEST_CASE("a callback that throws ends the render and reaches the caller", "[passes]") {
  using V = glint::variants::report;
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings settings = small_settings(13, 4, 5, 4);
  glint::RenderControl control;
  control.pass_done = [](const glint::PassReport& r) -> bool {
    if (r.passes_done == 2) throw std::runtime_error("enough");
    return true;
  };
  // The workers waiting for pass 3 must be told to stop, or this would never return.
  CHECK_THROWS_WITH(glint_test::render_by<glint::Renderer<V>>(scene, settings, control), "enough");
}

TEMPLATE_TEST_CASE("a render resumed after k passes ends bit for bit as an uninterrupted one",
                   "[passes][resume]", glint::Renderer<glint::variants::report>,
                   glint::Renderer<glint::variants::fast>,
                   glint::WavefrontRenderer<glint::variants::fast>) {
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings base = small_settings(13, 4, 2, 8);  // passes end 1 2 4 8 12 13
  const glint::Film full = glint_test::render_by<TestType>(scene, base).film;
  const int passes = GENERATE(1, 2, 3, 5, 6);
  INFO("resumed after pass " << passes);

  // The sums after `passes` passes, as a checkpoint would save them.
  glint::PixelSums sums;
  glint::RenderControl first;
  first.pass_done = [&](const glint::PassReport& r) {
    sums = r.sums;
    return r.passes_done < passes;
  };
  glint_test::render_by<TestType>(scene, base, first);
  REQUIRE(sums.width() == 19);

  for (const int threads : {1, 2, 5}) {
    INFO(threads << " threads");
    glint::RenderSettings settings = base;
    settings.threads = threads;
    std::vector<int> seen;
    glint::RenderControl control;
    control.pass_done = [&](const glint::PassReport& r) {
      seen.push_back(r.passes_done);
      return true;
    };
    std::uint64_t at_start = 0;
    control.progress = [&](const glint::RenderProgress& p) { at_start = p.samples_at_start; };
    const glint::RenderResult result =
        glint_test::render_by<TestType>(scene, settings, control, {&sums, passes});
    CHECK(result.complete());
    CHECK(result.passes_done == 6);
    CHECK(result.samples_per_pixel == 13);
    CHECK(same_bits(result.film, full));
    std::vector<int> remaining;
    for (int p = passes + 1; p <= 6; ++p)
      remaining.push_back(p);
    CHECK(seen == remaining);
    CHECK(at_start == 19u * 13u * std::uint64_t(glint::pass_ends(13, 4)[std::size_t(passes) - 1]));
  }
}

TEST_CASE("a resumed render that is stopped again holds its passes' samples", "[passes][resume]") {
  using V = glint::variants::report;
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings settings = small_settings(13, 4, 2, 8);
  glint::PixelSums sums;
  glint::RenderControl first;
  first.pass_done = [&](const glint::PassReport& r) {
    sums = r.sums;
    return r.passes_done < 2;
  };
  glint_test::render_by<glint::Renderer<V>>(scene, settings, first);

  std::atomic<bool> stop{true};
  const glint::RenderResult none = glint_test::render_by<glint::Renderer<V>>(
      scene, settings, glint::RenderControl{{}, {}, &stop}, {&sums, 2});
  CHECK(none.passes_done == 2);
  CHECK(none.samples_per_pixel == 2);
  CHECK(same_bits(none.film, one_shot<V>(scene, settings, 2)));

  const glint::RenderResult later = stopped_after<V>(scene, settings, 4);  // passes end 1 2 4 8
  glint::RenderControl control;
  control.pass_done = [](const glint::PassReport& r) { return r.passes_done < 4; };
  const glint::RenderResult resumed =
      glint_test::render_by<glint::Renderer<V>>(scene, settings, control, {&sums, 2});
  CHECK(resumed.passes_done == 4);
  CHECK(resumed.samples_per_pixel == 8);
  CHECK(same_bits(resumed.film, later.film));
}

TEST_CASE("a start that does not fit the settings is refused", "[passes][resume]") {
  using V = glint::variants::report;
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings settings = small_settings(13, 4, 2, 8);  // 6 passes
  const glint::PixelSums right(19, 13), wrong(13, 19);
  const auto refused = [&](const glint::RenderStart& from) {
    CHECK_THROWS_AS(
        glint_test::render_by<glint::Renderer<V>>(scene, settings, glint::RenderControl{}, from),
        glint::SettingsError);
  };
  refused({&wrong, 1});
  refused({nullptr, 2});
  refused({&right, 7});
  refused({&right, -1});
  CHECK(glint_test::render_by<glint::Renderer<V>>(scene, settings, glint::RenderControl{},
                                                  {&right, 6})
            .samples_per_pixel == 13);
}

TEST_CASE("the tile grid covers the image once, row by row", "[render_tiles]") {
  const glint::TileGrid grid(21, 14, 8);
  REQUIRE(grid.count == 6);
  std::vector<int> covered(21 * 14, 0);
  for (std::size_t i = 0; i < grid.count; ++i) {
    const glint::Tile tile = grid.tile(i);
    CHECK(tile.pixel_count() == std::size_t(tile.width()) * std::size_t(tile.height()));
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        ++covered[std::size_t(y * 21 + x)];
  }
  CHECK(std::all_of(covered.begin(), covered.end(), [](int n) { return n == 1; }));
  CHECK(grid.tile(2).x1 == 21);
  CHECK(grid.tile(2).width() == 5);
  CHECK(grid.tile(5).height() == 6);
}

TEMPLATE_TEST_CASE("render_tiles, tile by tile in any order over two sets of sums, is render()",
                   "[render_tiles]", glint::Renderer<glint::variants::report>,
                   glint::Renderer<glint::variants::fast>,
                   glint::WavefrontRenderer<glint::variants::fast>,
                   glint::Renderer<glint::variants::light_tracing>,
                   glint::Renderer<glint::variants::bidirectional>,
                   glint::Renderer<glint::variants::vcm>) {
  const glint::Scene scene = passes_scene();
  const glint::RenderSettings settings = small_settings(13, 4, 2, 8);
  const glint::RenderResult whole = glint_test::render_by<TestType>(scene, settings);
  const glint::TileGrid grid(settings);
  const std::vector<int> ends = glint::pass_ends(13, 4);  // 1 2 4 8 12 13

  // Two "processes", each with its own sums; every pass, each tile goes to one of them at
  // random, its sums copied over when it moves, and the tiles come in a shuffled order. Splats
  // stay where they land: the image is the two splat layers' sum. A tile's samples of a pass
  // come as one piece, so vertex merging's light phases are run again and again, its threads
  // meeting pieces of different sample indices (glint-render-mpi hands out one index at a time).
  std::mt19937 random(GENERATE(1u, 2u, 3u));
  constexpr bool splats = glint::kExecutionSplats<typename TestType::ExecutionModel>;
  glint::PixelSums sums[2] = {{19, 13, splats}, {19, 13, splats}};
  std::vector<int> holder(grid.count, 0);
  std::uint64_t samples = 0;
  for (std::size_t pass = 0; pass < ends.size(); ++pass) {
    std::vector<glint::TileWork> work[2];
    std::vector<std::size_t> order(grid.count);
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = i;
    std::shuffle(order.begin(), order.end(), random);
    for (const std::size_t tile : order) {
      const int to = int(random() % 2);
      if (holder[tile] != to) copy_tile(grid.tile(tile), sums[holder[tile]], sums[to]);
      holder[tile] = to;
      work[to].push_back({tile, pass == 0 ? 0 : ends[pass - 1], ends[pass], tile});
    }
    for (int p = 0; p < 2; ++p) {
      ListSource source(work[p]);
      const glint::RenderStats stats =
          TestType::render_tiles(scene, small_settings(13, 4, p + 1, 8), sums[p], source);
      CHECK(source.finished_ids().size() == work[p].size());
      CHECK(stats.threads == std::min<int>(p + 1, int(grid.count)));
      samples += stats.samples;
    }
  }
  glint::PixelSums gathered(19, 13, splats);
  for (std::size_t tile = 0; tile < grid.count; ++tile)
    copy_tile(grid.tile(tile), sums[holder[tile]], gathered);
  if constexpr (splats) {
    gathered.splats().add(sums[0].splats());
    gathered.splats().add(sums[1].splats());
  }
  CHECK(samples == 19u * 13u * 13u);
  CHECK(same_bits(glint::mean_image(gathered, 13).film, whole.film));
}

TEST_CASE("render_tiles with no work returns at once; sums of another size are refused",
          "[render_tiles]") {
  using V = glint::variants::fast;
  const glint::Scene scene = passes_scene();
  glint::PixelSums sums(19, 13);
  ListSource none({});
  const glint::RenderStats stats =
      glint::Renderer<V>::render_tiles(scene, small_settings(13, 4, 3, 8), sums, none);
  CHECK(stats.samples == 0);
  CHECK(stats.threads == 3);
  glint::PixelSums wrong(13, 19);
  CHECK_THROWS_AS(glint::Renderer<V>::render_tiles(scene, small_settings(13, 4, 1, 8), wrong, none),
                  glint::SettingsError);
}
