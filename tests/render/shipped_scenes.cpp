// render_with, shared by the shipped-scene tests (shipped_scenes.hpp), compiled here once: a
// build that compiled fewer renderers than the named variants (GLINT_RENDERER_VARIANTS)
// compiles the ones the shipped scenes use here, and only here.

#include "shipped_scenes.hpp"

#include <tuple>

namespace glint::test {

namespace {
/// The variants the shipped scenes name: those variant_model has a model of.
using ShippedSceneVariants =
    std::tuple<variants::report, variants::no_fresnel, variants::no_antialiasing>;
}  // namespace

Film render_with(const std::string& variant, const SceneDescription& description,
                 const RenderSettings& settings) {
  const Scene scene = Scene::build(description);
  RenderResult result;
  bool known = false;
  [&]<typename... V>(std::tuple<V...>*) {
    ((!known && V::info.name == variant
          ? (known = true, result = glint_test::render_by<Renderer<V>>(scene, settings), 0)
          : 0),
     ...);
  }(static_cast<ShippedSceneVariants*>(nullptr));
  INFO("variant " << variant);
  REQUIRE(known);
  CHECK(result.stats.invalid_samples == 0);
  return std::move(result.film);
}

}  // namespace glint::test
