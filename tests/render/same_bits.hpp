#pragma once
// The determinism every renderer owes: the same bits for any thread count, tile size and pass
// split, and after a render stopped between passes is resumed from its sums on another thread
// count (splats included, for the renderers that splat).

#include <array>
#include <catch2/catch.hpp>
#include <vector>

#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"

namespace glint_test {

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
