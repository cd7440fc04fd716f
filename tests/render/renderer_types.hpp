#pragma once
// The renderers the render tests run: every named variant with the scalar execution
// (Renderer<V>), and every chain variant also with the wavefront one (WavefrontRenderer<V>), so
// that a physical check written once holds for both execution models.
//
// Each of them is compiled once, in renderer_slice_*.cpp, rather than in every test file that
// renders with it: the tests call render_by<R>, which for these renderers only declares what
// those files define. (Compiled in each of a dozen files, they were most of the build of the
// render tests, and under the sanitizers most of CI's time.)

#include <cstddef>
#include <string>
#include <tuple>
#include <type_traits>

#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/variants.hpp"

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

template <typename... V>
auto renderers_of(std::tuple<V...>*)
    -> decltype(std::tuple_cat(std::tuple<glint::Renderer<V>...>{},
                               typename WavefrontOf<V>::type{}...));

/// Renderer<V> for every V of variants::all, then WavefrontRenderer<V> for the chain ones.
using AllRenderers = decltype(renderers_of(static_cast<glint::variants::all*>(nullptr)));
static_assert(std::tuple_size_v<AllRenderers> > std::tuple_size_v<glint::variants::all>);

template <typename R, typename List>
inline constexpr bool kIsOneOf = false;
template <typename R, typename... Rs>
inline constexpr bool kIsOneOf<R, std::tuple<Rs...>> = (std::is_same_v<R, Rs> || ...);

/// Renderers the renderer_slice_*.cpp files compile.
template <typename R>
concept Precompiled = kIsOneOf<R, AllRenderers>;

/// The test programs' build splits AllRenderers into this many files (renderer_slice_0.cpp
/// and on): renderer i is compiled by slice i % kRendererSlices. A slice file missing is an
/// undefined symbol when the tests link.
inline constexpr std::size_t kRendererSlices = 4;

/// R::render(scene, settings, control, from), defined for each Precompiled R by its slice.
template <Precompiled R>
glint::RenderResult precompiled_render(const glint::Scene& scene,
                                       const glint::RenderSettings& settings,
                                       const glint::RenderControl& control,
                                       const glint::RenderStart& from);

/// R::render(scene, settings, control, from) for any renderer R: compiled by a slice file for
/// the Precompiled ones, here for the others (a test's own variant).
template <typename R>
glint::RenderResult render_by(const glint::Scene& scene, const glint::RenderSettings& settings,
                              const glint::RenderControl& control = {},
                              const glint::RenderStart& from = {}) {
  if constexpr (Precompiled<R>)
    return precompiled_render<R>(scene, settings, control, from);
  else
    return R::render(scene, settings, control, from);
}

/// render_by with only a progress callback, as R::render(scene, settings, progress).
template <typename R>
glint::RenderResult render_by(const glint::Scene& scene, const glint::RenderSettings& settings,
                              const glint::ProgressCallback& progress) {
  return render_by<R>(scene, settings, glint::RenderControl{progress, {}, nullptr});
}

/// "fast (wavefront)", for messages.
template <typename R>
std::string renderer_name() {
  return std::string(R::Config::info.name) + " (" + R::ExecutionModel::kName + ")";
}

}  // namespace glint_test
