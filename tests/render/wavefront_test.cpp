// The wavefront execution model against the scalar one. With the same seed, WavefrontRenderer<V>
// must give Renderer<V>'s image bit for bit for every chain variant, whether it shades eight
// paths at a time or one (a policy without a lane-wise form), on the bench scenes, the report's
// scenes and a scene that mixes every material and light (also through a thin lens). Its own
// bookkeeping (the batch refilled from the next samples, the window of samples waiting to be added
// to their pixels, tiles and passes) must not change a bit of the image. The physical checks
// (analytic_sphere_test, physics_test) and the pass and tile tests (passes_test) also run it.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/variants.hpp"
#include "lens_scene.hpp"
#include "renderer_types.hpp"

namespace {

namespace fs = std::filesystem;

using glint_test::ChainVariants;
static_assert(std::tuple_size_v<ChainVariants> >= 1);
static_assert(std::tuple_size_v<ChainVariants> >= 3 ||
              !std::is_same_v<glint::compiled::Variants, glint::variants::all>);

/// ExactFresnel without its lane-wise form, as a user's policy may be: the wavefront renderer
/// then shades path by path (ChainEstimator's own code) instead of eight paths at a time.
struct ScalarOnlyFresnel {
  static constexpr bool enabled = true;
  static float reflectance(float cos_incident, float eta_incident, float eta_transmitted) {
    return glint::ExactFresnel::reflectance(cos_incident, eta_incident, eta_transmitted);
  }
};
struct fast_path_by_path : glint::variants::fast::with_fresnel<ScalarOnlyFresnel> {
  static constexpr glint::VariantInfo info{"fast_path_by_path", "`fast`, shaded path by path",
                                           true};
};
static_assert(glint::WavefrontExecution<fast_path_by_path>::kWidth == 1);
#if defined(GLINT_AVX2) && defined(__AVX512F__)
static_assert(glint::WavefrontExecution<glint::variants::fast>::kWidth == 16);
#elif defined(GLINT_AVX2)
static_assert(glint::WavefrontExecution<glint::variants::fast>::kWidth == 8);
#endif

/// `fast` with StratifiedSampler, a sampler without a form for several lanes: the wavefront
/// shades eight paths at a time and draws their samples path by path.
struct fast_stratified : glint::variants::fast::with_sampler<glint::StratifiedSampler> {
  static constexpr glint::VariantInfo info{"fast_stratified", "`fast`, stratified samples", true};
};
static_assert(!glint::WavefrontExecution<fast_stratified>::kSamplersInLanes);

/// The chain variants, `fast` shaded path by path and `fast` with a sampler drawn path by path.
using WavefrontConfigs =
    decltype(std::tuple_cat(ChainVariants{}, std::tuple<fast_path_by_path, fast_stratified>{}));

using glint_test::comparison_scenes;
using glint_test::same_bits;

const char* const kMixedScene = R"(
image      width=16 height=16 spp=16 max_depth=6
camera     position=0,0,38 look_at=0,0,0 up=0,1,0 fov=55
light      position=-8,14,20 intensity=1500
light      position=8,-10,25 intensity=300 color=0.5,0.6,1
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
sphere     center=-9,7,-6 radius=4 color=0.9,0.9,0.9
sphere     center=0,19,0 radius=2 diffuse=0 emission=6,6,5
sphere     center=-4,12,4 radius=1 diffuse=0 emission=20,10,5
)";

glint::Scene mixed_scene() {
  return glint::Scene::build(glint::read_scene_text(kMixedScene, "wavefront"));
}

}  // namespace

TEMPLATE_LIST_TEST_CASE(
    "with the same seed, the wavefront gives the scalar renderer's image bit "
    "for bit",
    "[render][wavefront]", WavefrontConfigs) {
  // Both call ChainEstimator::step, one path at a time or a SIMD register's paths at once, and
  // the batched queries answer what the single-ray ones do: the same draws, the same hits and
  // the same operations in the same order. Every bench and report scene at a small size, and
  // the mixed scene with two threads.
  std::vector<fs::path> files = comparison_scenes();
  REQUIRE(files.size() >= 20);
  for (const fs::path& file : files) {
    const glint::Scene scene = glint::Scene::build(glint::read_scene_file(file.string()));
    if (!glint::is_supported<TestType>(scene)) continue;
    INFO(TestType::info.name << " on " << file.filename().string());
    glint::RenderSettings settings = glint::RenderSettings::from(scene);
    settings.width = 12;
    settings.height = 10;
    settings.samples_per_pixel = 4;
    settings.seed = 3;
    settings.threads = 1;
    glint_test::check_same_image<glint::Renderer<TestType>, glint::WavefrontRenderer<TestType>>(
        scene, settings);
  }
  const glint::Scene scene = mixed_scene();
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.width = 24;
  settings.height = 20;
  settings.seed = 5;
  settings.threads = 2;
  glint_test::check_same_image<glint::Renderer<TestType>, glint::WavefrontRenderer<TestType>>(
      scene, settings);
  // Through a thin lens: each lane's lens point drawn after its filter offset, as one path's.
  const glint::Scene lens = glint::Scene::build(glint::read_scene_text(
      glint_test::through_lens(kMixedScene, "aperture=3 focus=30"), "wavefront, lens"));
  glint_test::check_same_image<glint::Renderer<TestType>, glint::WavefrontRenderer<TestType>>(
      lens, settings);
}

TEST_CASE("the wavefront image depends neither on tiles nor on passes", "[render][wavefront]") {
  // One pixel per tile with every sample in one pass starts far more samples than the window
  // of samples waiting for their pixel holds; tiles cut at the image's edge and one sample per
  // pass leave most batches nearly empty. All must give the same bits.
  using V = glint::variants::fast;
  const glint::Scene scene = mixed_scene();
  glint::RenderSettings base = glint::RenderSettings::from(scene);
  base.width = 7;
  base.height = 5;
  base.samples_per_pixel = 1500;
  base.max_depth = 4;
  base.seed = 11;
  base.threads = 2;
  const glint::Film reference =
      glint_test::render_by<glint::WavefrontRenderer<V>>(scene, base).film;
  glint::RenderSettings one_pixel_tiles = base;
  one_pixel_tiles.tile_size = 1;
  one_pixel_tiles.max_pass_samples = 1500;
  CHECK(same_bits(glint_test::render_by<glint::WavefrontRenderer<V>>(scene, one_pixel_tiles).film,
                  reference));
  glint::RenderSettings ragged = base;
  ragged.tile_size = 3;
  ragged.max_pass_samples = 1;
  ragged.samples_per_pixel = 1500;
  ragged.threads = 3;
  CHECK(
      same_bits(glint_test::render_by<glint::WavefrontRenderer<V>>(scene, ragged).film, reference));
}

TEST_CASE("the wavefront counts and drops samples that are not finite as the scalar renderer does",
          "[render][wavefront]") {
  // Inside an enclosure that emits 3e38, a mirror that also emits 3e38 returns 3e38 + 3e38:
  // infinite. Pixels that see only the enclosure are finite.
  const glint::Scene scene = glint::Scene::build(glint::read_scene_text(R"(
image      width=12 height=12 spp=8 max_depth=3
camera     position=0,0,30 look_at=0,0,0 up=0,1,0 fov=60
sphere     center=0,0,0 radius=100 diffuse=0 emission=3e38,3e38,3e38
sphere     center=0,0,0 radius=8 diffuse=0 mirror=1 emission=3e38,3e38,3e38
)",
                                                                        "overflow"));
  using V = glint::variants::fast;
  const glint::RenderSettings settings = glint::RenderSettings::from(scene);
  const glint::RenderResult scalar = glint_test::render_by<glint::Renderer<V>>(scene, settings);
  const glint::RenderResult wavefront =
      glint_test::render_by<glint::WavefrontRenderer<V>>(scene, settings);
  CHECK(scalar.stats.invalid_samples > 0);
  CHECK(scalar.stats.invalid_samples < scalar.stats.samples);
  CHECK(wavefront.stats.invalid_samples == scalar.stats.invalid_samples);
  CHECK(same_bits(wavefront.film, scalar.film));
}

TEST_CASE("fast is a chain variant, which the wavefront renders, and report a tree variant",
          "[wavefront]") {
  STATIC_REQUIRE(glint::WavefrontConfig<glint::variants::fast>);
  STATIC_REQUIRE_FALSE(glint::WavefrontConfig<glint::variants::report>);
}
