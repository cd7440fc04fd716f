#pragma once
// Material model policies: how the renderer follows the lobes of the report's material.

#include "glint/policy/concepts.hpp"

namespace glint {

/// The report's renderer: at every hit, each lobe with a non-zero coefficient contributes,
/// weighted by its coefficient. Diffuse gets direct light plus one random bounce; mirror and
/// refraction rays are all traced, so a path branches into a tree (exponential in depth for
/// materials that mix mirror and transparency).
struct ReportMaterialModel {
  static constexpr bool traces_every_lobe = true;
};

/// One lobe per bounce, chosen with probability proportional to its coefficient and weighted
/// so that the expectation is the report's: linear cost per path.
struct StochasticMaterialModel {
  static constexpr bool traces_every_lobe = false;
};

static_assert(MaterialModel<ReportMaterialModel> && MaterialModel<StochasticMaterialModel>);

}  // namespace glint
