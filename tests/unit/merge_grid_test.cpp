// The merge grid (render/merge_grid.hpp): a query finds exactly the candidates within its radius
// (against a scan of them all), each once, for radii that put many candidates in a cell and
// few, and the order in which it meets them depends on the candidates alone, not on the order
// in which the chunks were filled.

#include "glint/render/merge_grid.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "glint/math/random.hpp"
#include "random_vectors.hpp"

namespace {

struct PointCandidate {
  glint::Vec3 point;
  std::uint32_t id;
};

/// Path `path`'s candidates, (path % 5) of them at points drawn from its index, appended to
/// `out`.
template <typename Out>
void path_candidates(std::size_t path, Out& out) {
  glint::Pcg32 rng(path, 3u);
  for (std::size_t k = 0; k < path % 5; ++k) {
    const float x = glint::test::uniform(rng, -4.0f, 4.0f);
    const float y = glint::test::uniform(rng, -4.0f, 4.0f);
    out.push_back(
        {glint::Vec3(x, y, glint::test::uniform(rng, -1.0f, 1.0f)), std::uint32_t(path * 8 + k)});
  }
}

/// A grid over `paths` paths, its chunks filled in the order `order` gives.
glint::MergeGrid<PointCandidate> grid_of(std::size_t paths, const std::vector<std::size_t>& order,
                                         float radius) {
  glint::MergeGrid<PointCandidate> grid(paths);
  for (const std::size_t chunk : order)
    grid.fill_chunk(chunk,
                    [](std::size_t path, auto& candidates) { path_candidates(path, candidates); });
  grid.build_grid(radius);
  return grid;
}

}  // namespace

TEST_CASE("merge grid: a query meets exactly the candidates within its radius, in a fixed order",
          "[merge_grid]") {
  const std::size_t paths = 5 * glint::MergeGrid<PointCandidate>::kChunkPaths + 37;
  const std::size_t chunks = glint::MergeGrid<PointCandidate>(paths).chunk_count();
  std::vector<std::size_t> forwards(chunks), backwards(chunks);
  for (std::size_t c = 0; c < chunks; ++c) {
    forwards[c] = c;
    backwards[c] = chunks - 1 - c;
  }
  // All candidates, as a scan sees them.
  std::vector<PointCandidate> all;
  for (std::size_t path = 0; path < paths; ++path)
    path_candidates(path, all);
  for (const float radius : {0.05f, 0.4f, 3.0f}) {
    const glint::MergeGrid<PointCandidate> grid = grid_of(paths, forwards, radius);
    const glint::MergeGrid<PointCandidate> reversed = grid_of(paths, backwards, radius);
    CHECK(grid.candidate_count() == all.size());
    glint::Pcg32 rng(11u, radius > 1.0f ? 1u : 2u);
    for (int query = 0; query < 300; ++query) {
      const glint::Vec3 at(glint::test::uniform(rng, -4.5f, 4.5f),
                           glint::test::uniform(rng, -4.5f, 4.5f),
                           glint::test::uniform(rng, -1.5f, 1.5f));
      std::vector<std::uint32_t> met, met_reversed, expected;
      grid.for_each_near(at, [&](const PointCandidate& c) { met.push_back(c.id); });
      reversed.for_each_near(at, [&](const PointCandidate& c) { met_reversed.push_back(c.id); });
      for (const PointCandidate& c : all) {
        const glint::Vec3 offset = c.point - at;
        if (glm::dot(offset, offset) < radius * radius) expected.push_back(c.id);
      }
      REQUIRE(met == met_reversed);
      std::sort(met.begin(), met.end());
      REQUIRE(std::adjacent_find(met.begin(), met.end()) == met.end());
      REQUIRE(met == expected);
    }
  }
}
