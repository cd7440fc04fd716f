#pragma once
// WavefrontRenderer<Config>: renders like Renderer<Config> (the same interface, passes,
// checkpoints and statistics) but advances a batch of paths per thread stage by stage, with
// batched scene queries. Only for chain configurations (one lobe per bounce).
//
// Interim: the execution model is being written; until it lands this is the scalar renderer
// under the new name, so that the command-line and benchmark side can be built against the
// final interface.

#include <concepts>

#include "glint/config.hpp"
#include "glint/policy/material_model.hpp"
#include "glint/render/renderer.hpp"

namespace glint {

/// Whether variant C can be rendered by WavefrontRenderer: it follows one lobe per bounce.
template <typename C>
concept WavefrontConfig =
    RenderConfig<C> && std::same_as<typename C::material_model, StochasticMaterialModel>;

template <WavefrontConfig C>
using WavefrontRenderer = Renderer<C>;

}  // namespace glint
