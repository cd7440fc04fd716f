#pragma once
// The renderers the render tests run: every named variant with the scalar execution
// (Renderer<V>), and every chain variant also with the wavefront one (WavefrontRenderer<V>), so
// that a physical check written once holds for both execution models.

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

/// "fast (wavefront)", for messages.
template <typename R>
std::string renderer_name() {
  return std::string(R::Config::info.name) + " (" + R::ExecutionModel::kName + ")";
}

}  // namespace glint_test
