#pragma once
// What glint-render and glint-render-mpi share that depends on the variant they render with: its
// type and the renderer a run uses. The rest of what they share is render_command.hpp's, compiled
// once in the glint-cli library; this header alone names the variant, so only the programs'
// own translation units instantiate it. Each program includes it once (one translation unit
// each), and with it the CPU check (cpu_check.hpp), which runs before main.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "cpu_check.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/renderer.hpp"
#include "glint/render/wavefront/wavefront_renderer.hpp"
#include "glint/variants.hpp"
#include "glint_renderers.hpp"  // the renderers, compiled once in glint-renderers
#include "render_command.hpp"

// GLINT_VARIANT names the type of glint::variants a variant's own program renders with (e.g.
// -DGLINT_VARIANT=report), chosen when it is compiled. Without it, the program is glint-render,
// which holds the estimators of glint::variants::render_estimators (ProgramVariants), or
// glint-render-mpi, which renders with the default variant.
#ifdef GLINT_VARIANT
#define GLINT_PROGRAM_HOLDS_ESTIMATORS 0
#else
#define GLINT_VARIANT default_variant
#define GLINT_PROGRAM_HOLDS_ESTIMATORS 1
#endif

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

using Variant = glint::variants::GLINT_VARIANT;
static_assert(glint::NamedVariant<Variant>, "GLINT_VARIANT must name a variant of variants.hpp");

/// Whether variant V has the wavefront renderer (Program::has_wavefront).
template <glint::NamedVariant V>
inline constexpr bool kHasWavefront = glint::WavefrontConfig<V>;

/// Whether V's renderer splats (light paths): its sums carry a splat layer.
template <glint::NamedVariant V>
inline constexpr bool kSplats =
    glint::kExecutionSplats<typename glint::Renderer<V>::ExecutionModel>;

/// The paths V's wavefront renderer shades at once (Program::wavefront_lanes); 1 without one.
template <glint::NamedVariant V>
inline constexpr int kWavefrontLanes = [] {
  if constexpr (glint::WavefrontConfig<V>)
    return glint::default_shading_width<V>();
  else
    return 1;
}();

inline constexpr bool kVariantHasWavefront = kHasWavefront<Variant>;
inline constexpr bool kVariantSplats = kSplats<Variant>;
inline constexpr int kVariantWavefrontLanes = kWavefrontLanes<Variant>;

namespace detail {
template <typename V, typename List>
inline constexpr bool kListed = false;
template <typename V, typename... L>
inline constexpr bool kListed<V, std::tuple<L...>> = (std::is_same_v<V, L> || ...);

/// The variants of `List` that the build compiled renderers for (glint::compiled::Variants).
template <typename... V>
auto compiled_of(std::tuple<V...>*) -> decltype(std::tuple_cat(
    std::conditional_t<kListed<V, glint::compiled::Variants>, std::tuple<V>, std::tuple<>>{}...));
}  // namespace detail

/// Whether this program chooses among several variants (glint-render: --estimator).
inline constexpr bool kHoldsEstimators = GLINT_PROGRAM_HOLDS_ESTIMATORS;

/// The variants this program renders with: glint-render's estimators the build compiled, the
/// default variant first; a variant's own program (and glint-render-mpi) its one variant.
using ProgramVariants =
    std::conditional_t<kHoldsEstimators,
                       decltype(detail::compiled_of(
                           static_cast<glint::variants::render_estimators*>(nullptr))),
                       std::tuple<Variant>>;
static_assert(std::is_same_v<std::tuple_element_t<0, ProgramVariants>, Variant>,
              "the default variant comes first: it renders where nothing else is asked for");

/// The first line of the help text.
inline constexpr std::string_view kVariantDescription = [] {
  if constexpr (kHoldsEstimators && (std::tuple_size_v < ProgramVariants >> 1))
    return "Renders SCENE (a glint scene file) and writes an image: with the path tracer, or by "
           "vertex connection and merging where a point light shines through glass or by way of "
           "a mirror, which no path from the camera can follow (--estimator chooses).";
  else if constexpr (kFollowsCameraPaths<typename Variant::estimator>)
    return "Renders SCENE (a glint scene file) with the path tracer and writes an image.";
  else if constexpr (std::is_same_v<typename Variant::estimator, BidirectionalPathTracing>)
    return "Renders SCENE (a glint scene file) by bidirectional path tracing (paths from the "
           "camera and from the lights, joined in every way) and writes an image.";
  else if constexpr (std::is_same_v<typename Variant::estimator, VertexConnectionMerging>)
    return "Renders SCENE (a glint scene file) by vertex connection and merging (paths from the "
           "camera and from the lights, joined in every way and merged where they meet) and "
           "writes an image.";
  else
    return "Renders SCENE (a glint scene file) by light tracing (paths from the lights, "
           "connected to the camera) and writes an image.";
}();

/// The names --estimator takes: the program's variants' names, '_' written '-' (the names of
/// their own programs, glint-render-NAME).
inline const std::vector<std::string>& estimator_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    [&]<typename... V>(std::type_identity<std::tuple<V...>>) {
      (list.push_back(dashed_variant_name(V::info.name)), ...);
    }(std::type_identity<ProgramVariants>{});
    return list;
  }();
  return names;
}

/// Calls `visit.template operator()<V>()` for the variant at `index` of ProgramVariants and
/// returns what it returns.
template <typename Visit>
int with_program_variant(std::size_t index, Visit&& visit) {
  int status = 0;
  std::size_t at = 0;
  [&]<typename... V>(std::type_identity<std::tuple<V...>>) {
    ((at++ == index ? (status = visit.template operator()<V>(), 0) : 0), ...);
  }(std::type_identity<ProgramVariants>{});
  return status;
}

/// The index in ProgramVariants of glint::variants::blind_spot_variant, where the program holds
/// it.
inline constexpr std::optional<std::size_t> kBlindSpotIndex =
    []<typename... V>(std::type_identity<std::tuple<V...>>) -> std::optional<std::size_t> {
  constexpr bool is[] = {std::is_same_v<V, glint::variants::blind_spot_variant>...};
  for (std::size_t i = 0; i < sizeof...(V); ++i)
    if (is[i]) return i;
  return std::nullopt;
}(std::type_identity<ProgramVariants>{});

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
