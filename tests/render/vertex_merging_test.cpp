// Vertex connection and merging (render/bidirectional_execution.hpp with merging,
// render/merge_grid.hpp): the same bits whatever the threads, tiles and passes, and after a
// resume; a point light's caustic under a glass ball seen through pixel centres, which only
// merging can render there (no join reaches the light through the glass, and no join to the
// camera lands on a pixel centre), against the fan of rays of tests/render/caustic_reference.hpp,
// with a small radius; and the bias of a large radius caught by the same comparison. The weights
// of its strategies are checked with bidirectional path tracing's (bidirectional_test.cpp).

#include <catch2/catch.hpp>
#include <optional>
#include <string>

#include "block_statistics.hpp"
#include "caustic_reference.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/bidirectional_execution.hpp"
#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"
#include "same_bits.hpp"

namespace vertex_merging_test {

using Chain = glint::variants::report::with_estimator<glint::PathTracing>;
using PixelCentres = Chain::with_antialiasing<glint::NoAntialiasing>;

/// Vertex merging whose first radius is `Tenths` tenths of a pixel at the median distance.
template <typename C, int Tenths>
class MergingWithRadius : public glint::VertexMergingExecution<C> {
 public:
  MergingWithRadius(const glint::Scene& scene, const glint::RenderSettings& settings)
      : glint::VertexMergingExecution<C>(scene, settings, float(Tenths) / 10.0f) {}
};
template <typename C, int Tenths>
using Merging = glint::Renderer<C, MergingWithRadius<C, Tenths>>;

TEST_CASE("vertex merging: the same bits for any threads, tiles and passes, and after a resume",
          "[render][light]") {
  const glint::Scene scene =
      glint::Scene::build(glint::read_scene_text(glint_test::kMixedRoomWithBackground, "mixed"));
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.seed = 7;
  (void)glint_test::check_same_bits<glint::Renderer<Chain, glint::VertexMergingExecution<Chain>>>(
      scene, settings);
}

TEST_CASE("vertex merging: a caustic seen through pixel centres matches a fan of rays",
          "[render][light][statistical]") {
  caustic_reference::check_caustic<Merging<PixelCentres, 5>>(500, "vertex merging", true);
}

TEST_CASE("vertex merging: the bias of a large radius is caught", "[render][light][statistical]") {
  const glint::Scene scene =
      glint::Scene::build(glint::read_scene_text(caustic_reference::kCaustic, "caustic"));
  const glint_test::BlockSamples rendered = glint_test::render_blocks<Merging<PixelCentres, 150>>(
      scene, 600, glint::RenderSettings::from(scene));
  const auto expected = caustic_reference::expected_blocks(scene, true);
  const glint_test::ComparisonFamily family =
      caustic_reference::compare(rendered, expected, 1.0, "merging, radius 15 pixels");
  for (const std::string& line : family.rejected())
    UNSCOPED_INFO(line);
  CHECK_FALSE(family.rejected().empty());
}

}  // namespace vertex_merging_test
