#pragma once
// Material models: which materials the spheres of a scene can have, as a Bsdf at each hit
// (render/bsdf.hpp). The estimators ask a hit's Bsdf for samples, values and densities and never
// name a material, so a model with more lobes renders under every estimator unchanged. Each
// model names its Bsdf, a class template over the Config and the width, declared here so that the
// policies do not pull in the renderer.

#include <string_view>

#include "glint/instruction_set.hpp"
#include "glint/policy/concepts.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

template <typename C, typename F = float>
class ReportMaterial;  // render/materials/report_material.hpp
template <typename C, typename F = float>
class MicrofacetMaterial;  // render/materials/microfacet_material.hpp

/// The report's material: a diffuse lobe coloured by the sphere's shading, a mirror and a
/// transmission lobe with Fresnel reflection and the inclusion tree's outside index, mixed by the
/// sphere's coefficients. Reads the Config's Fresnel, sphere shading and diffuse sampling.
struct ReportMaterialModel {
  static constexpr std::string_view name = "the report's material";
  template <typename C, typename F>
  using bsdf = ReportMaterial<C, F>;
  /// The report's lobes only: no rough or metal mirror, no rough interface.
  static bool supports(const Material& material) {
    return !material.has_mirror_finish() && !material.has_rough_interface();
  }
};

/// The report's material with a mirror lobe that may be rough (a Trowbridge-Reitz microfacet
/// lobe) and reflect as a metal (a conductor's Fresnel reflectance), and a transparent lobe whose
/// interface may be rough (frosted glass): every material of the scene format. Spheres without
/// either render as under ReportMaterialModel, to the bit. Its rough lobe is not one of the
/// report's tree estimator's lobes, which takes ReportMaterialModel only.
struct MicrofacetMaterialModel {
  static constexpr std::string_view name = "microfacet mirrors, metals and glass";
  template <typename C, typename F>
  using bsdf = MicrofacetMaterial<C, F>;
  static bool supports(const Material&) { return true; }
};

static_assert(MaterialModel<ReportMaterialModel> && MaterialModel<MicrofacetMaterialModel>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
