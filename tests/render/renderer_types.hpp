#pragma once
// The renderers the render tests run: every variant the build compiled (glint::compiled::Variants,
// all the named variants unless the build chose fewer) that follows camera paths, with the scalar
// execution (Renderer<V>), and every chain variant among them also with the wavefront one
// (WavefrontRenderer<V>), so that a physical check written once holds for both execution models.
// (A light-tracing variant sees neither the background nor anything through glass or in a
// mirror: tests/render/light_tracing_test.cpp holds its checks.)
//
// They come compiled from the glint-renderers library (cmake/GlintRenderers.cmake): its header
// declares them extern, so a test that renders with them compiles none of them. A test's own
// configuration is compiled where the test uses it.

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "glint_renderers.hpp"

namespace glint_test {

/// std::tuple<WavefrontRenderer<V>> for a chain variant, else std::tuple<> (without naming
/// WavefrontRenderer<V>, which a tree variant fails to compile).
template <typename V, bool = glint::WavefrontConfig<V>>
struct WavefrontOf {
  using type = std::tuple<>;
};
template <typename V>
struct WavefrontOf<V, true> {
  using type = std::tuple<glint::WavefrontRenderer<V>>;
};

/// std::tuple<Renderer<V>> for a variant that follows camera paths, else std::tuple<>.
template <typename V>
using CameraPathRendererOf = std::conditional_t<glint::kFollowsCameraPaths<typename V::estimator>,
                                                std::tuple<glint::Renderer<V>>, std::tuple<>>;

template <typename... V>
auto renderers_of(std::tuple<V...>*)
    -> decltype(std::tuple_cat(CameraPathRendererOf<V>{}..., typename WavefrontOf<V>::type{}...));

/// Renderer<V> for every compiled variant V that follows camera paths, then WavefrontRenderer<V>
/// for the chain ones.
using CameraPathRenderers =
    decltype(renderers_of(static_cast<glint::compiled::Variants*>(nullptr)));

template <typename... V>
auto chain_variants(std::tuple<V...>*) -> decltype(std::tuple_cat(
    std::conditional_t<glint::WavefrontConfig<V>, std::tuple<V>, std::tuple<>>{}...));
/// Every compiled chain variant (one lobe per bounce): the ones WavefrontRenderer renders.
using ChainVariants = decltype(chain_variants(static_cast<glint::compiled::Variants*>(nullptr)));

/// Calls `visit.template operator()<V>()` for each compiled variant V, in order.
template <typename Visit>
void for_each_compiled_variant(Visit&& visit) {
  [&]<typename... V>(std::tuple<V...>*) {
    (visit.template operator()<V>(), ...);
  }(static_cast<glint::compiled::Variants*>(nullptr));
}

/// R::render(scene, settings, control, from): compiled by glint-renderers for the named
/// variants, here for a test's own configuration.
template <typename R>
glint::RenderResult render_by(const glint::Scene& scene, const glint::RenderSettings& settings,
                              const glint::RenderControl& control = {},
                              const glint::RenderStart& from = {}) {
  return R::render(scene, settings, control, from);
}

/// render_by with only a progress callback, as R::render(scene, settings, progress).
template <typename R>
glint::RenderResult render_by(const glint::Scene& scene, const glint::RenderSettings& settings,
                              const glint::ProgressCallback& progress) {
  return render_by<R>(scene, settings, glint::RenderControl{progress, {}, nullptr});
}

/// The bench scenes and the report's scenes, sorted by name.
inline std::vector<std::filesystem::path> comparison_scenes() {
  std::vector<std::filesystem::path> files;
  for (const char* dir : {GLINT_SOURCE_DIR "/bench/scenes", GLINT_SOURCE_DIR "/scenes"})
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      if (entry.is_regular_file() && entry.path().extension() == ".scene")
        files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// Whether two films hold the same pixels bit for bit.
inline bool same_bits(const glint::Film& a, const glint::Film& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.pixels().data(), b.pixels().data(),
                     a.pixels().size() * sizeof(glint::Color)) == 0;
}

/// Renders `scene` with the scalar renderer of A and with renderer B, and checks that B gives
/// the same image bit for bit, with the same numbers of rays and of dropped samples.
template <typename A, typename B>
void check_same_image(const glint::Scene& scene, const glint::RenderSettings& settings) {
  const glint::RenderResult a = render_by<A>(scene, settings);
  const glint::RenderResult b = render_by<B>(scene, settings);
  REQUIRE(b.stats.samples == a.stats.samples);
  CHECK(b.stats.rays == a.stats.rays);
  CHECK(b.stats.invalid_samples == a.stats.invalid_samples);
  CHECK(same_bits(b.film, a.film));
}

/// "fast (wavefront)", for messages.
template <typename R>
std::string renderer_name() {
  // Appended piece by piece: GCC 12 warns falsely (-Warray-bounds) on a chain of + whose first
  // operand is a temporary, once the calls are inlined.
  std::string name(R::Config::info.name);
  name += " (";
  name += R::ExecutionModel::kName;
  name += ')';
  return name;
}

}  // namespace glint_test
