#pragma once
// WavefrontRenderer<Config>: Renderer<Config> (the same interface, passes, checkpoints, tiles
// and statistics) with the wavefront execution model (wavefront_execution.hpp), which advances
// a batch of paths per thread stage by stage with batched scene queries. For chain
// configurations only (WavefrontConfig).

#include "glint/config.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_execution.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

template <RenderConfig C>
using WavefrontRenderer = Renderer<C, WavefrontExecution<C>>;

}  // namespace glint::inline GLINT_ISA_NAMESPACE
