#pragma once
// PathTracer<Config>: the radiance along camera rays, generic over a Config. The estimator itself
// is the one C::estimator names (render/estimators/tree.hpp or chain.hpp); both see the
// material through the Bsdf of C::material_model (render/bsdf.hpp) and share the hit set-up
// (render/estimators/path_context.hpp).

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/estimators/chain.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/estimators/tree.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Estimates the radiance arriving along camera rays, with the policies of Config C, by the
/// camera-path estimator C::estimator names.
template <RenderConfig C>
class PathTracer {
 public:
  using SamplerType = typename C::sampler;
  using Estimator = typename C::estimator::template camera_paths<C>;

  PathTracer(const Scene& scene, int max_depth) : estimator_(PathContext<C>(scene, max_depth)) {}

  /// Radiance arriving along `ray` (a camera ray).
  Color radiance(const Ray& ray, SamplerType& sampler, TraceCounters& counters) const {
    return estimator_.radiance(ray, sampler, counters);
  }

 private:
  Estimator estimator_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
