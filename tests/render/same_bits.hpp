#pragma once
// The determinism every renderer owes: the same bits for any thread count, tile size and pass
// split, and after a render stopped between passes is resumed from its sums on another thread
// count (splats included, for the renderers that splat).

#include <array>
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"

namespace glint_test {

/// A small room for the same-bits checks of the estimators that follow light paths: a point light
/// and a small emissive sphere, glass, a half-mirror and a diffuse floor, a pixel filter with an
/// area. Black behind: light tracing renders it too; the others add a background.
inline constexpr const char* kMixedRoom = R"(
image      width=23 height=17 spp=5 max_depth=4
camera     position=0,0,20 look_at=0,0,0 up=0,1,0 fov=50
antialias  sigma=0.5
light      position=0,9,5 intensity=300
sphere     center=0,-100008,0 radius=1e5 color=0.7,0.7,0.7
sphere     center=-3,-3,0 radius=3 diffuse=0 transparent=1 ior=1.5
sphere     center=4,-4,-2 radius=2 mirror=0.5 diffuse=0.5
sphere     center=0,6,-4 radius=1 diffuse=0 emission=5,5,5
)";

/// kMixedRoom with a background.
inline const std::string kMixedRoomWithBackground =
    std::string(kMixedRoom) + "background color=0.1,0.2,0.3\n";

/// Renders `scene` with renderer R and `settings` on 1, 2 and 5 threads with other tile sizes
/// and pass splits, and stopped after two passes of one sample and resumed on three threads;
/// checks that every film has the first one's bits and that no sample was invalid. Returns the
/// first film.
template <typename R>
glint::Film check_same_bits(const glint::Scene& scene, glint::RenderSettings settings) {
  std::vector<glint::Film> films;
  for (const auto& [threads, tile, pass] :
       std::vector<std::array<int, 3>>{{1, 16, 32}, {2, 7, 1}, {5, 3, 2}}) {
    settings.threads = threads;
    settings.tile_size = tile;
    settings.max_pass_samples = pass;
    const glint::RenderResult result = render_by<R>(scene, settings);
    REQUIRE(result.complete());
    CHECK(result.stats.invalid_samples == 0);
    films.push_back(result.film);
  }
  for (std::size_t i = 1; i < films.size(); ++i)
    CHECK(films[i].pixels() == films[0].pixels());

  settings.max_pass_samples = 1;
  settings.threads = 2;
  glint::RenderControl stop_early;
  stop_early.keep_sums = true;
  stop_early.pass_done = [](const glint::PassReport& report) { return report.passes_done < 2; };
  const glint::RenderResult first = render_by<R>(scene, settings, stop_early);
  REQUIRE(first.passes_done == 2);
  settings.threads = 3;
  const glint::RenderResult resumed =
      render_by<R>(scene, settings, {}, glint::RenderStart{&first.sums, first.passes_done});
  REQUIRE(resumed.complete());
  CHECK(resumed.film.pixels() == films[0].pixels());
  return films[0];
}

}  // namespace glint_test
