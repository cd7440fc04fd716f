// Variants that say they estimate the report's image (VariantInfo::same_image_as_report: they
// change only how the integral is estimated, e.g. sampler, bounce direction, lobe selection,
// path termination, or `fast`, which combines them) must converge to the same image as the
// report's renderer. Each variant renders the same scene with many seeds; the mean radiance of
// every 4x4-pixel block and of the whole image must agree with the report's (Welch's test, the
// comparisons of a variant judged together at the suite's false-alarm budget: see
// block_statistics.hpp). The scene mixes every material lobe: glass (with Fresnel), a mirror,
// the report's "weird" material, octant shading, an emitter and a point light.

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

// A closed diffuse room under an emissive ceiling: most of its light has bounced off diffuse
// walls several times, so a bias in the diffuse lobe shows in every block, and the ceiling is
// large enough for the report's bounces to find it often: the image is smooth enough for a
// bias of 1% to stand out (`a 1% bias in the diffuse lobe is caught`).
constexpr const char* kDiffuseRoom = R"(
image      width=16 height=16 spp=16 max_depth=6
camera     position=0,0,38 look_at=0,0,0 up=0,1,0 fov=55
sphere     center=-100020,0,0 radius=100000 color=0.8,0.5,0.5
sphere     center=100020,0,0 radius=100000 color=0.5,0.8,0.5
sphere     center=0,-100015,0 radius=100000 color=0.75,0.75,0.75
sphere     center=0,100020,0 radius=100000 diffuse=0 emission=1,1,1
sphere     center=0,0,-100020 radius=100000 color=0.75,0.75,0.75
sphere     center=0,0,100040 radius=100000 color=0.75,0.75,0.75
sphere     center=-6,-9,-4 radius=6 color=0.8,0.8,0.8
sphere     center=8,-10,4 radius=5 color=0.6,0.6,0.9
)";

/// A scene with report's blocks on it, and the samples per pixel of each of a candidate's
/// kReplicates renders. The reference, shared by every variant, takes four times as many, so
/// that its noise does not dominate. The room takes more than the mixed scene, whose report's
/// tree of rays is expensive and whose caustics stay noisy anyway.
struct SceneAndReference {
  glint::Scene scene;
  int samples_per_render;
  glint_test::BlockSamples report;
};

SceneAndReference with_reference(const std::string& text, const char* label,
                                 int samples_per_render) {
  glint::Scene scene = glint::Scene::build(glint::read_scene_text(text, label));
  glint_test::BlockSamples report =
      glint_test::render_blocks<glint::Renderer<glint::variants::report>>(scene, 100,
                                                                          4 * samples_per_render);
  return SceneAndReference{std::move(scene), samples_per_render, std::move(report)};
}

/// The mixed scene, or (for variants whose shading policy lacks octants) the same scene with
/// that sphere uniformly coloured.
const SceneAndReference& mixed_scene(bool with_octants) {
  const auto make = [](bool octants) {
    std::string text = kScene;
    if (!octants)
      text.replace(text.find(" shading=octants"), std::string(" shading=octants").size(), "");
    return with_reference(text, "agreement", 8);
  };
  static const SceneAndReference with = make(true);
  static const SceneAndReference without = make(false);
  return with_octants ? with : without;
}

const SceneAndReference& diffuse_room() {
  static const SceneAndReference room = with_reference(kDiffuseRoom, "diffuse room", 64);
  return room;
}

/// Adds the comparisons of variant V with report on both scenes to `family`.
template <typename V>
void compare_with_report(glint_test::ComparisonFamily& family, const std::string& name) {
  const bool octants = glint::is_supported<V>(mixed_scene(true).scene);
  const SceneAndReference& mixed = mixed_scene(octants);
  const std::uint64_t seed = 100 + glint_test::kReplicates;  // independent of the reference's
  CHECK(glint_test::compare_independent(
            family, name + (octants ? " on the mixed scene" : " on the mixed scene, no octants"),
            mixed.report,
            glint_test::render_blocks<glint::Renderer<V>>(mixed.scene, seed,
                                                          mixed.samples_per_render)) > 0.1);
  CHECK(glint_test::compare_independent(
            family, name + " in the diffuse room", diffuse_room().report,
            glint_test::render_blocks<glint::Renderer<V>>(
                diffuse_room().scene, seed, diffuse_room().samples_per_render)) > 0.1);
}

/// cosine_hemisphere with its diffuse bounces weighted 1% too much: a biased renderer that
/// the comparison must catch.
struct OnePercentHeavyCosine {
  static glint::DirectionSample sample(glint::Vec2 u) {
    glint::DirectionSample s = glint::CosineHemisphere::sample(u);
    s.weight *= 1.01f;
    return s;
  }
  static float pdf(float cos_theta) { return glint::CosineHemisphere::pdf(cos_theta); }
};
struct biased_cosine_hemisphere
    : glint::variants::cosine_hemisphere::with_diffuse_sampling<OnePercentHeavyCosine> {
  static constexpr glint::VariantInfo info{"biased_cosine_hemisphere",
                                           "cosine_hemisphere, diffuse bounces 1% too heavy",
                                           glint::variants::kDifferentImage};
};

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
  glint_test::ComparisonFamily family;
  compare_with_report<TestType>(family, std::string(TestType::info.name));
  family.check();
}

TEST_CASE("statistical comparisons: a 1% bias in the diffuse lobe is caught", "[render]") {
  // The same comparison, at the same sample counts and level, as the test above; only the
  // candidate is wrong.
  glint_test::ComparisonFamily family;
  compare_with_report<biased_cosine_hemisphere>(family, "biased_cosine_hemisphere");
  const std::vector<std::string> rejected = family.rejected();
  INFO(rejected.size() << " of " << family.size() << " comparisons rejected");
  REQUIRE(!rejected.empty());
  INFO("the most significant: " << rejected.front());
  CHECK(rejected.front().find("diffuse room, whole image") != std::string::npos);
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
