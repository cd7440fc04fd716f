#pragma once
// Estimator policies: which paths a render follows to estimate the image. Each names the
// execution model that renders with it (how a thread turns a tile's samples into pixel sums,
// render/scalar_execution.hpp and render/light_tracing_execution.hpp), and an estimator of
// camera paths names the class that follows one (render/estimators/). All are class templates
// over the Config, declared here so that the policies do not pull in the renderer.
//
// What each estimator reads of the Config: every one its sampler, Fresnel, pixel filter, sphere
// shading, diffuse sampling and path termination; the camera-path estimators also the light
// sampling (light tracing reaches the lights from the lights themselves).

#include <string_view>

#include "glint/instruction_set.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

template <typename C>
class TreeEstimator;  // render/estimators/tree.hpp
template <typename C>
class ChainEstimator;  // render/estimators/chain.hpp
template <typename C>
class ScalarExecution;  // render/scalar_execution.hpp
template <typename C>
class LightTracingExecution;  // render/light_tracing_execution.hpp
template <typename C, bool Merging = false>
class BidirectionalExecution;  // render/bidirectional_execution.hpp
template <typename C>
class VertexMergingExecution;  // render/bidirectional_execution.hpp

/// The report's renderer: camera paths that, at every hit, follow each lobe with a non-zero
/// coefficient, weighted by its coefficient. Diffuse gets direct light plus one random bounce;
/// mirror and refraction rays are all traced, so a path branches into a tree (exponential in
/// depth for materials that mix mirror and transparency).
struct TreePathTracing {
  static constexpr std::string_view name = "path tracing, every lobe";
  template <typename C>
  using camera_paths = TreeEstimator<C>;
  template <typename C>
  using execution = ScalarExecution<C>;
};

/// Camera paths that follow one lobe per bounce, chosen with probability proportional to its
/// coefficient and weighted so that the expectation is the report's: linear cost per path. The
/// one estimator with the wavefront renderer too (render/wavefront/).
struct PathTracing {
  static constexpr std::string_view name = "path tracing";
  template <typename C>
  using camera_paths = ChainEstimator<C>;
  template <typename C>
  using execution = ScalarExecution<C>;
};

/// Paths from the lights, each diffuse vertex connected to the camera and its light splatted
/// onto the pixels that see it (render/estimators/light_tracer.hpp): a point light's caustic
/// through glass, which no camera path finds; nothing seen through a mirror or glass. Needs a
/// pixel filter with an area and a black background.
struct LightTracing {
  static constexpr std::string_view name = "light tracing";
  template <typename C>
  using execution = LightTracingExecution<C>;
};

/// A camera subpath and a light subpath per sample, joined in every way the report's material
/// allows and weighted by the power heuristic (render/estimators/bidirectional.hpp): the caustics
/// of light tracing, the direct light of next-event estimation and what the camera sees through
/// mirrors and glass, each from the strategy that samples it best. Any background.
struct BidirectionalPathTracing {
  static constexpr std::string_view name = "bidirectional path tracing";
  template <typename C>
  using execution = BidirectionalExecution<C>;
};

/// Bidirectional path tracing with vertex merging (Georgiev et al. 2012): the light subpaths of
/// each sample index traced first for the whole image, and every camera vertex merging with the
/// light of the light vertices near it (photon mapping with a shrinking radius), besides every
/// join, all under one power heuristic. Merging finds what no join can: a point light's caustic
/// seen in a mirror or through glass. Consistent (its bias vanishes as the samples grow) rather
/// than unbiased. Any background.
struct VertexConnectionMerging {
  static constexpr std::string_view name = "vertex connection and merging";
  template <typename C>
  using execution = VertexMergingExecution<C>;
};

static_assert(Estimator<TreePathTracing> && Estimator<PathTracing> && Estimator<LightTracing> &&
              Estimator<BidirectionalPathTracing> && Estimator<VertexConnectionMerging>);

/// Whether estimator policy E follows camera paths (a PathTracer renders them, one at a time or
/// in a wavefront), rather than paths from the lights.
template <typename E>
inline constexpr bool kFollowsCameraPaths = requires {
  typename E::template camera_paths<void>;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
