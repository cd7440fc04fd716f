#pragma once
// Material model policies: how the renderer follows the lobes of the report's material. Each
// names its estimator, a class template over the Config; the estimators are defined in
// render/estimators/ (declared here so that the policies do not pull in the renderer).

#include "glint/instruction_set.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

template <typename C>
class TreeEstimator;  // render/estimators/tree.hpp
template <typename C>
class ChainEstimator;  // render/estimators/chain.hpp

/// The report's renderer: at every hit, each lobe with a non-zero coefficient contributes,
/// weighted by its coefficient. Diffuse gets direct light plus one random bounce; mirror and
/// refraction rays are all traced, so a path branches into a tree (exponential in depth for
/// materials that mix mirror and transparency).
struct ReportMaterialModel {
  template <typename C>
  using estimator = TreeEstimator<C>;
};

/// One lobe per bounce, chosen with probability proportional to its coefficient and weighted
/// so that the expectation is the report's: linear cost per path.
struct StochasticMaterialModel {
  template <typename C>
  using estimator = ChainEstimator<C>;
};

static_assert(MaterialModel<ReportMaterialModel> && MaterialModel<StochasticMaterialModel>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
