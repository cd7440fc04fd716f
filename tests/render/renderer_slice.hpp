#pragma once
// What renderer_slice_N.cpp compiles: precompiled_render<R> for the renderers R of slice N of
// AllRenderers (renderer_types.hpp). Only those files include this header, so that no test
// file compiles a renderer they provide.

#include <cstddef>
#include <tuple>
#include <utility>
#include <vector>

#include "renderer_types.hpp"

namespace glint_test {

template <Precompiled R>
glint::RenderResult precompiled_render(const glint::Scene& scene,
                                       const glint::RenderSettings& settings,
                                       const glint::RenderControl& control,
                                       const glint::RenderStart& from) {
  return R::render(scene, settings, control, from);
}

using RenderFunction = glint::RenderResult (*)(const glint::Scene&, const glint::RenderSettings&,
                                               const glint::RenderControl&,
                                               const glint::RenderStart&);

/// The precompiled_render of each renderer of slice `Slice`. Its explicit instantiation in the
/// slice's file is what makes the compiler emit them there, for the test files to link with.
template <std::size_t Slice>
std::vector<RenderFunction> slice_renderers() {
  static_assert(Slice < kRendererSlices, "renderer_types.hpp's kRendererSlices is too small");
  std::vector<RenderFunction> functions;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (
        [&] {
          if constexpr (I % kRendererSlices == Slice)
            functions.push_back(&precompiled_render<std::tuple_element_t<I, AllRenderers>>);
        }(),
        ...);
  }
  (std::make_index_sequence<std::tuple_size_v<AllRenderers>>{});
  return functions;
}

}  // namespace glint_test
