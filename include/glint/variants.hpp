#pragma once
// Named renderer variants. `report` is the renderer of the report; each ablation changes one
// policy from it.

#include <tuple>

#include "glint/config.hpp"

namespace glint::variants {

using report = Config<IndependentSampler, ReportMaterialModel, ExactFresnel, GaussianAntialiasing,
                      BuiltinShading, UniformHemisphere, FixedDepth>;

using no_fresnel = report::with_fresnel<NoFresnel>;
using no_antialiasing = report::with_antialiasing<NoAntialiasing>;

/// Every named variant, for tests that must hold for all of them.
using all = std::tuple<report, no_fresnel, no_antialiasing>;

}  // namespace glint::variants
