#pragma once
// Named renderer variants. `report` is the renderer of the report; every other variant but
// `fast` changes exactly one policy from it (an ablation), so comparing it with `report`
// measures that one feature. `fast` combines the policies that give the best image per second.

#include <tuple>

#include "glint/config.hpp"

namespace glint::variants {

using report = Config<IndependentSampler, ReportMaterialModel, ExactFresnel, GaussianAntialiasing,
                      BuiltinShading, UniformHemisphere, FixedDepth>;

// Fresnel
using no_fresnel = report::with_fresnel<NoFresnel>;
using schlick_fresnel = report::with_fresnel<SchlickFresnel>;
// Antialiasing
using no_antialiasing = report::with_antialiasing<NoAntialiasing>;
using box_antialiasing = report::with_antialiasing<BoxAntialiasing>;
using tent_antialiasing = report::with_antialiasing<TentAntialiasing>;
// Light transport
using cosine_hemisphere = report::with_diffuse_sampling<CosineHemisphere>;
using stochastic_material = report::with_material_model<StochasticMaterialModel>;
using russian_roulette = report::with_termination<RussianRoulette>;
// Shading
using uniform_shading = report::with_shading<UniformShading>;
// Sampler
using stratified_sampler = report::with_sampler<StratifiedSampler>;
using sobol_sampler = report::with_sampler<SobolSampler>;

// The best image per second measured by bench/run-all (bench/results/variants.md): one lobe
// per bounce, cosine-weighted bounces, Russian roulette, and Sobol' samples for the first six
// requests of a path (pure Sobol' costs more than it gains deep in the path).
using fast = Config<HybridSobolSampler<6>, StochasticMaterialModel, ExactFresnel,
                    GaussianAntialiasing, BuiltinShading, CosineHemisphere, RussianRoulette>;

/// Every named variant, for tests that must hold for all of them.
using all = std::tuple<report, no_fresnel, schlick_fresnel, no_antialiasing, box_antialiasing,
                       tent_antialiasing, cosine_hemisphere, stochastic_material, russian_roulette,
                       uniform_shading, stratified_sampler, sobol_sampler, fast>;

}  // namespace glint::variants
