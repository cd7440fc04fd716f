#pragma once
// Named renderer variants: the one list of them. `report` is the report's renderer; every other
// variant but the three built on `fast` changes exactly one policy from it (an ablation), so
// comparing it with `report` measures that one feature. `fast` combines the policies that give
// the best image per second; `fast_no_emitter_sampling` takes one of them away again,
// `fast_emitters_by_power` chooses light samples' emitters as a room of many lamps should not,
// `light_tracing` replaces its estimator (camera paths) by paths from the lights,
// `bidirectional` by both, joined, and `vcm` by both, joined and merged.
//
// Each variant is a type derived from its Config that carries its name, a line saying what it
// changes and whether it converges to the report's image (as pbrt-v4's types carry Name()).
// The glint-render-NAME executables, the benchmarks, the tests, bench/run-all's tables and the
// README's variant table are all derived from `all`: adding a variant is a struct here plus its
// entry in `all` (then `bench/run-all` or `ctest -L docs` says where the docs need a line).

#include <string_view>
#include <tuple>
#include <type_traits>

#include "glint/config.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// What a named variant says about itself.
struct VariantInfo {
  std::string_view name;         ///< executable glint-render-NAME (with '-' for '_')
  std::string_view description;  ///< what it changes from `report`, in a table's words
  /// It estimates the same image as `report` (it changes only cost and noise); false for
  /// ablations that change what is rendered (no Fresnel, another pixel filter, ...).
  bool same_image_as_report;
};

namespace variants {

inline constexpr bool kSameImage = true;
inline constexpr bool kDifferentImage = false;

struct report : Config<IndependentSampler, TreePathTracing, ExactFresnel, GaussianAntialiasing,
                       BuiltinShading, UniformHemisphere, FixedDepth> {
  static constexpr VariantInfo info{"report", "the report's renderer (baseline)", kSameImage};
};

// The best image per second measured by bench/run-all (bench/results/variants.md), with light
// samples' emitters chosen by their light at the point: less noise on the surfaces a room of
// many lamps lights, for more time per sample (docs/benchmarks.md, "Choosing among many lamps").
struct fast : Config<HybridSobolSampler<6>, PathTracing, ExactFresnel, GaussianAntialiasing,
                     BuiltinShading, CosineHemisphere, RussianRoulette,
                     EmitterSampling<PowerHeuristic>, MicrofacetMaterialModel> {
  static constexpr VariantInfo info{"fast",
                                    "Sobol' for the first 6 requests, one lobe per bounce, cosine "
                                    "bounces, Russian roulette, emitter sampling with MIS, "
                                    "emitters chosen by their light at the point, rough and "
                                    "metal mirrors, rough glass",
                                    kSameImage};
};

struct no_fresnel : report::with_fresnel<NoFresnel> {
  static constexpr VariantInfo info{"no_fresnel", "no Fresnel on glass", kDifferentImage};
};
struct schlick_fresnel : report::with_fresnel<SchlickFresnel> {
  static constexpr VariantInfo info{"schlick_fresnel", "Schlick's approximation for Fresnel",
                                    kDifferentImage};
};
struct no_antialiasing : report::with_antialiasing<NoAntialiasing> {
  static constexpr VariantInfo info{"no_antialiasing", "camera rays through pixel centres",
                                    kDifferentImage};
};
struct box_antialiasing : report::with_antialiasing<BoxAntialiasing> {
  static constexpr VariantInfo info{"box_antialiasing", "box pixel filter instead of Gaussian",
                                    kDifferentImage};
};
struct tent_antialiasing : report::with_antialiasing<TentAntialiasing> {
  static constexpr VariantInfo info{"tent_antialiasing", "tent pixel filter instead of Gaussian",
                                    kDifferentImage};
};
struct cosine_hemisphere : report::with_diffuse_sampling<CosineHemisphere> {
  static constexpr VariantInfo info{"cosine_hemisphere", "cosine-weighted diffuse bounces",
                                    kSameImage};
};
struct stochastic_material : report::with_estimator<PathTracing> {
  static constexpr VariantInfo info{
      "stochastic_material", "one material lobe per bounce, chosen by coefficient", kSameImage};
};
struct russian_roulette : report::with_path_termination<RussianRoulette> {
  static constexpr VariantInfo info{"russian_roulette", "Russian roulette after 3 bounces",
                                    kSameImage};
};
struct uniform_shading : report::with_sphere_shading<UniformShading> {
  static constexpr VariantInfo info{
      "uniform_shading", "one colour per sphere (rejects scenes with other shading kinds)",
      kSameImage};
};
struct stratified_sampler : report::with_sampler<StratifiedSampler> {
  static constexpr VariantInfo info{"stratified_sampler", "jittered stratified samples",
                                    kSameImage};
};
struct sobol_sampler : report::with_sampler<SobolSampler> {
  static constexpr VariantInfo info{"sobol_sampler", "Owen-scrambled Sobol' samples", kSameImage};
};
/// The ablations of `fast`: what light sampling buys where the best other policies are on, what
/// choosing the emitter by its light at the point buys over choosing it by power, and what the
/// rough and metal mirrors cost a scene that has none.
struct fast_no_emitter_sampling : fast::with_light_sampling<PointLightsOnly> {
  static constexpr VariantInfo info{
      "fast_no_emitter_sampling",
      "`fast` with emissive spheres and the background's image found by bounces only", kSameImage};
};
struct fast_emitters_by_power
    : fast::with_light_sampling<EmitterSampling<PowerHeuristic, EmitterChoiceByPower>> {
  static constexpr VariantInfo info{
      "fast_emitters_by_power",
      "`fast` with each light sample's emitter chosen by power, not by its light at the point",
      kSameImage};
};
struct fast_ideal_mirrors : fast::with_material_model<ReportMaterialModel> {
  static constexpr VariantInfo info{
      "fast_ideal_mirrors",
      "`fast` with the report's material only (rejects scenes with rough or metal mirrors or "
      "rough glass)",
      kSameImage};
};
/// The estimator that finds a point light's light through glass: `fast`'s policies, followed
/// from the lights instead of from the camera. It sees no mirror or glass from the camera and
/// no background, so it renders another image than `report` wherever those show.
struct light_tracing : fast::with_estimator<LightTracing> {
  static constexpr VariantInfo info{
      "light_tracing",
      "`fast` followed from the lights: caustics of point lights; no background, nothing seen "
      "through glass or in a mirror",
      kDifferentImage};
};
/// Every light path there is: `fast`'s policies, a camera subpath and a light subpath per sample
/// joined in every way, weighted by the power heuristic. Converges to the image with caustics,
/// which the camera-path variants miss under point lights, so it differs from `report`'s there.
struct bidirectional : fast::with_estimator<BidirectionalPathTracing> {
  static constexpr VariantInfo info{
      "bidirectional",
      "`fast` followed from the camera and the lights, joined with MIS: caustics of point "
      "lights, and what mirrors and glass show",
      kDifferentImage};
};
/// Bidirectional path tracing with vertex merging: `bidirectional` plus the light of every light
/// path of the sample index near each camera vertex, which also renders a point light's caustic
/// seen in a mirror or through glass. Consistent: its merging radius shrinks with the samples.
struct vcm : fast::with_estimator<VertexConnectionMerging> {
  static constexpr VariantInfo info{
      "vcm", "`bidirectional` with vertex merging: also caustics seen in mirrors and through glass",
      kDifferentImage};
};
struct emitter_sampling : report::with_light_sampling<EmitterSampling<PowerHeuristic>> {
  static constexpr VariantInfo info{
      "emitter_sampling",
      "emissive spheres sampled at diffuse hits (each chosen by its light there), MIS with the "
      "power heuristic",
      kSameImage};
};

/// Every named variant, `report` first: the order of every table.
using all = std::tuple<report, fast, no_fresnel, schlick_fresnel, no_antialiasing, box_antialiasing,
                       tent_antialiasing, cosine_hemisphere, stochastic_material, russian_roulette,
                       uniform_shading, stratified_sampler, sobol_sampler, emitter_sampling,
                       fast_no_emitter_sampling, fast_emitters_by_power, fast_ideal_mirrors,
                       light_tracing, bidirectional, vcm>;

/// The variant glint-render renders with where nothing is asked for and the path tracer sees all
/// the scene's light (render/path_tracing_blind_spot.hpp), and glint-render-mpi's.
using default_variant = fast;

/// What glint-render renders with, where nothing is asked for, a scene whose light the path tracer
/// cannot see: a point light shining through glass or by way of a mirror.
using blind_spot_variant = vcm;

/// The variants glint-render holds, among which --estimator chooses: the default variant and the
/// ones that replace its estimator only (the same camera, sampler and material model).
using render_estimators =
    std::tuple<default_variant, blind_spot_variant, bidirectional, light_tracing>;

/// Calls `visit.template operator()<V>()` for each variant V of `all`, in order.
template <typename Visit>
constexpr void for_each(Visit&& visit) {
  [&]<typename... V>(std::type_identity<std::tuple<V...>>) {
    (visit.template operator()<V>(), ...);
  }(std::type_identity<all>{});
}

/// Calls `visit.template operator()<V>()` for the variant named `name`; false if none is.
template <typename Visit>
constexpr bool visit_by_name(std::string_view name, Visit&& visit) {
  bool found = false;
  for_each([&]<typename V>() {
    if (!found && V::info.name == name) {
      found = true;
      visit.template operator()<V>();
    }
  });
  return found;
}

}  // namespace variants

/// A named variant: a RenderConfig that carries its VariantInfo.
template <typename V>
concept NamedVariant = RenderConfig<V> && requires {
  { V::info } -> std::convertible_to<VariantInfo>;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
