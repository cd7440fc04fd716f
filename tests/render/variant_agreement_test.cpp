// Variants that say they estimate the report's image (VariantInfo::same_image_as_report: they
// change only how the integral is estimated, e.g. sampler, bounce direction, lobe selection,
// path termination, or `fast`, which combines them) must converge to the same image as the
// report's renderer. Each variant renders the same scene with several seeds; the
// mean radiance of every 4x4-pixel block must agree with the report's within five standard
// errors of the difference. The scene mixes every material lobe: glass (with Fresnel), a
// mirror, the report's "weird" material, octant shading, an emitter and a point light.

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "block_statistics.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"

namespace {

constexpr const char* kScene = R"(
image      width=16 height=16 spp=16 max_depth=6
camera     position=0,0,38 look_at=0,0,0 up=0,1,0 fov=55
light      position=-8,14,20 intensity=1500
sphere     center=-100020,0,0 radius=100000 color=0.8,0.3,0.3
sphere     center=100020,0,0 radius=100000 color=0.3,0.8,0.3
sphere     center=0,-100015,0 radius=100000 color=0.7,0.7,0.7
sphere     center=0,100020,0 radius=100000 color=0.7,0.7,0.7
sphere     center=0,0,-100020 radius=100000 color=0.7,0.7,0.7
sphere     center=0,0,100040 radius=100000 color=0.2,0.2,0.2
sphere     center=-9,-8,0 radius=6 transparent=1 ior=1.5
sphere     center=0,-2,-10 radius=4 transparent=1 ior=1.0
sphere     center=0,-2,-10 radius=7 transparent=1 ior=1.5
sphere     center=9,-9,2 radius=5 mirror=1 mirror_color=0.9,0.9,0.8
sphere     center=9,7,-6 radius=5 diffuse=0.33 color=0.2,0.2,0.9 mirror=0.33 mirror_color=0.2,0.9,0.2 transparent=0.33 transparent_color=0.9,0.2,0.2
sphere     center=-9,7,-6 radius=4 color=0.9,0.9,0.9 shading=octants
sphere     center=0,19,0 radius=2 diffuse=0 emission=6,6,5
)";

/// The shared scene, or (for variants whose shading policy lacks octants) the same scene with
/// that sphere uniformly coloured; each with report's statistics on it.
struct SceneAndReference {
  glint::Scene scene;
  glint_test::BlockStatistics report;
};

const SceneAndReference& shared_scene(bool with_octants) {
  const auto make = [](bool octants) {
    std::string text = kScene;
    if (!octants)
      text.replace(text.find(" shading=octants"), std::string(" shading=octants").size(), "");
    glint::Scene scene = glint::Scene::build(glint::read_scene_text(text, "agreement"));
    glint_test::BlockStatistics report =
        glint_test::render_blocks<glint::Renderer<glint::variants::report>>(scene, 100);
    return SceneAndReference{std::move(scene), report};
  };
  static const SceneAndReference with = make(true);
  static const SceneAndReference without = make(false);
  return with_octants ? with : without;
}

/// Every compiled variant that claims to estimate report's image (VariantInfo), but report.
template <typename... V>
auto same_image_variants(std::tuple<V...>*) -> decltype(std::tuple_cat(
    std::conditional_t<V::info.same_image_as_report && V::info.name != "report", std::tuple<V>,
                       std::tuple<>>{}...));
using SameImageVariants =
    decltype(same_image_variants(static_cast<glint::compiled::Variants*>(nullptr)));
static_assert(std::tuple_size_v<SameImageVariants> >= 1);
static_assert(std::tuple_size_v<SameImageVariants> >= 6 ||
              !std::is_same_v<glint::compiled::Variants, glint::variants::all>);

}  // namespace

TEMPLATE_LIST_TEST_CASE("variants that claim report's image converge to it",
                        "[render][statistical]", SameImageVariants) {
  const bool octants = glint::is_supported<TestType>(shared_scene(true).scene);
  INFO(TestType::info.name << (octants ? "" : ", on the scene without octant shading"));
  const SceneAndReference& shared = shared_scene(octants);
  const glint_test::BlockStatistics& reference = shared.report;
  const glint_test::BlockStatistics candidate =
      glint_test::render_blocks<glint::Renderer<TestType>>(shared.scene, 100);
  const double total_reference = glint_test::check_blocks_agree(reference, candidate);
  CHECK(total_reference > 1.0);  // the scene is lit: the comparison is not between zeros
}

TEST_CASE("Fresnel makes clear glass reflect", "[render]") {
  // Not an estimator choice: a glass ball in front of a black wall, with a bright wall behind
  // the camera. Without Fresnel, glass only refracts and the ball shows black; with it, the
  // ball reflects a few percent of the bright wall (0.04 at normal incidence, more at grazing).
  const glint::Scene scene = glint::Scene::build(glint::read_scene_text(R"(
image      width=9 height=9 spp=64 max_depth=4
camera     position=0,0,30 look_at=0,0,0 up=0,1,0 fov=20
sphere     center=0,0,-100020 radius=100000 diffuse=0 color=0,0,0
sphere     center=0,0,100040 radius=100000 diffuse=0 emission=1,1,1
sphere     center=0,0,0 radius=5 transparent=1 ior=1.5
)",
                                                                        "fresnel"));
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  const float with =
      glint_test::render_by<glint::Renderer<glint::variants::report>>(scene, settings)
          .film.at(4, 4)
          .x;
  const float without =
      glint_test::render_by<glint::Renderer<glint::variants::no_fresnel>>(scene, settings)
          .film.at(4, 4)
          .x;
  CHECK(without == 0.0f);
  CHECK(with > 0.02f);
  CHECK(with < 0.2f);
}
