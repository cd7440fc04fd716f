// The wavefront renderer at every shading width (one path, eight and sixteen paths in SIMD
// lanes) against the scalar renderer, for every chain variant: the same image bit for bit, and
// the same number of rays, on every bench and report scene and with several threads. Widths
// other than the default are instantiated here for a copy of each variant (an unnamed
// configuration, so that the named renderers stay compiled once, in glint-renderers).

#include <catch2/catch.hpp>
#include <filesystem>
#include <tuple>
#include <vector>

#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "renderer_types.hpp"

namespace {

namespace fs = std::filesystem;

/// Variant V shaded W paths at a time.
template <typename V, int W>
struct AtWidth {
  using Variant = V;
  static constexpr int kWidth = W;
};

template <typename... V>
auto at_every_width(std::tuple<V...>*) -> decltype(std::tuple_cat(
#if defined(GLINT_AVX2)
    std::tuple<AtWidth<V, 1>, AtWidth<V, 8>, AtWidth<V, 16>>{}...
#else
    std::tuple<AtWidth<V, 1>>{}...
#endif
    ));
using Widths = decltype(at_every_width(static_cast<glint_test::ChainVariants*>(nullptr)));

}  // namespace

TEMPLATE_LIST_TEST_CASE("at every shading width, the wavefront gives the scalar renderer's image",
                        "[render][wavefront]", Widths) {
  using V = typename TestType::Variant;
  struct Copy : V {};
  using Wavefront = glint::Renderer<Copy, glint::WavefrontExecution<Copy, TestType::kWidth>>;
  const std::vector<fs::path> files = glint_test::comparison_scenes();
  REQUIRE(files.size() >= 20);
  for (const fs::path& file : files) {
    const glint::Scene scene = glint::Scene::build(glint::read_scene_file(file.string()));
    if (!glint::is_supported<V>(scene)) continue;
    INFO(V::info.name << " at width " << TestType::kWidth << " on " << file.filename().string());
    glint::RenderSettings settings = glint::RenderSettings::from(scene);
    settings.width = 13;
    settings.height = 11;
    settings.samples_per_pixel = 3;
    settings.seed = 21;
    settings.threads = 3;
    glint_test::check_same_image<glint::Renderer<V>, Wavefront>(scene, settings);
  }
}
