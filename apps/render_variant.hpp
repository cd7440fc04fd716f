#pragma once
// What glint-render and glint-render-mpi share that depends on the variant they render with: its
// type and the renderer a run uses. The rest of what they share is render_command.hpp's, compiled
// once in the glint-cli library; this header alone names the variant, so only the programs'
// own translation units instantiate it. Each program includes it once (one translation unit
// each), and with it the CPU check (cpu_check.hpp), which runs before main.

#include <span>
#include <string_view>
#include <type_traits>

#include "cpu_check.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/variants.hpp"
#include "glint_renderers.hpp"  // the renderers, compiled once in glint-renderers
#include "render_command.hpp"

// GLINT_VARIANT names the type of glint::variants the program renders with (e.g.
// -DGLINT_VARIANT=report), chosen when it is compiled.
#ifndef GLINT_VARIANT
#define GLINT_VARIANT default_variant
#endif

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

using Variant = glint::variants::GLINT_VARIANT;
static_assert(glint::NamedVariant<Variant>, "GLINT_VARIANT must name a variant of variants.hpp");

/// Whether this program's variant has the wavefront renderer (Program::has_wavefront).
inline constexpr bool kVariantHasWavefront = glint::WavefrontConfig<Variant>;

/// Whether its renderer splats (light tracing): its sums carry a splat layer.
inline constexpr bool kVariantSplats =
    glint::kExecutionSplats<typename glint::Renderer<Variant>::ExecutionModel>;

/// What the program does, as the first line of its help says it (Program::description).
inline constexpr std::string_view kVariantDescription =
    glint::kFollowsCameraPaths<typename Variant::estimator>
        ? "Renders SCENE (a glint scene file) with the path tracer and writes an image."
    : std::is_same_v<typename Variant::estimator, glint::BidirectionalPathTracing>
        ? "Renders SCENE (a glint scene file) by bidirectional path tracing (paths from the "
          "camera and from the lights, joined in every way) and writes an image."
    : std::is_same_v<typename Variant::estimator, glint::VertexConnectionMerging>
        ? "Renders SCENE (a glint scene file) by vertex connection and merging (paths from the "
          "camera and from the lights, joined in every way and merged where they meet) and "
          "writes an image."
        : "Renders SCENE (a glint scene file) by light tracing (paths from the lights, connected "
          "to the camera) and writes an image.";

/// The paths its wavefront renderer shades at once (Program::wavefront_lanes).
inline constexpr int kVariantWavefrontLanes = [] {
  if constexpr (glint::WavefrontConfig<Variant>)
    return glint::default_shading_width<Variant>();
  else
    return 1;
}();

/// The instruction set this translation unit was compiled for, as a program that holds no other
/// lists it (Program::simds).
inline constexpr glint::Simd kCompiledSimds[] = {glint::kCompiledSimd};

/// The instruction sets whose renderers this program holds (Program::simds): every one where it
/// is compiled once per set (GLINT_RENDER_SIMD_SETS, apps/CMakeLists.txt), else its own.
#if defined(GLINT_RENDER_SIMD_SETS)
inline constexpr glint::Simd kProgramSimds[] = {glint::Simd::scalar, glint::Simd::avx2,
                                                glint::Simd::avx512};
#else
inline constexpr std::span<const glint::Simd> kProgramSimds = kCompiledSimds;
#endif

/// The renderer of variant V for `model`: `render.template operator()<R>()` with R
/// WavefrontRenderer<V> or Renderer<V>, returning what it returns. A variant without the
/// wavefront renderer always gets Renderer<V> (--scalar changes nothing there).
template <glint::NamedVariant V, typename Render>
decltype(auto) with_renderer(ExecutionModel model, Render&& render) {
  if constexpr (glint::WavefrontConfig<V>)
    if (model == ExecutionModel::wavefront)
      return render.template operator()<glint::WavefrontRenderer<V>>();
  return render.template operator()<glint::Renderer<V>>();
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
