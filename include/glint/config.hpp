#pragma once
// A renderer configuration: one policy per rendering feature, each checked against its concept
// (policy/concepts.hpp). Naming rule: the member alias is the concept's name in snake_case
// (`Antialiasing` -> `antialiasing`), and `with_<alias><P>` is the same configuration with that
// one policy replaced, which is how an ablation is written.

#include <type_traits>

#include "glint/instruction_set.hpp"
#include "glint/policy/antialiasing.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/diffuse_sampling.hpp"
#include "glint/policy/estimator.hpp"
#include "glint/policy/fresnel.hpp"
#include "glint/policy/light_sampling.hpp"
#include "glint/policy/material_model.hpp"
#include "glint/policy/path_termination.hpp"
#include "glint/policy/sampler.hpp"
#include "glint/policy/sphere_shading.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// - SamplerPolicy: where sample values come from (independent, stratified, Sobol').
/// - EstimatorPolicy: which paths estimate the image: camera paths that follow every lobe of
///   the report's material at a hit (a tree of rays) or one chosen at random (a chain), or
///   paths from the lights connected to the camera.
/// - FresnelPolicy: reflectance of fully transparent spheres (none, Schlick, exact).
/// - AntialiasingPolicy: where in the pixel a camera ray goes (centre, Gaussian, box, tent).
/// - SphereShadingPolicy: which shading kinds (uniform, octants, checker, custom) the build
///   supports and how each colours a point.
/// - DiffuseSamplingPolicy: how a diffuse bounce direction is drawn (uniform, cosine).
/// - PathTerminationPolicy: when a path ends (at the maximum depth, or by Russian roulette).
/// - LightSamplingPolicy: whether diffuse hits also sample emissive spheres, and how that is
///   weighted against bounces that hit them (multiple importance sampling).
/// - MaterialModelPolicy: which materials the spheres can have, as the Bsdf every estimator
///   samples and evaluates at a hit (the report's material).
template <Sampler SamplerPolicy, Estimator EstimatorPolicy, Fresnel FresnelPolicy,
          Antialiasing AntialiasingPolicy, SphereShading SphereShadingPolicy,
          DiffuseSampling DiffuseSamplingPolicy = UniformHemisphere,
          PathTermination PathTerminationPolicy = FixedDepth,
          LightSampling LightSamplingPolicy = PointLightsOnly,
          MaterialModel MaterialModelPolicy = ReportMaterialModel>
struct Config {
  using sampler = SamplerPolicy;
  using estimator = EstimatorPolicy;
  using fresnel = FresnelPolicy;
  using antialiasing = AntialiasingPolicy;
  using sphere_shading = SphereShadingPolicy;
  using diffuse_sampling = DiffuseSamplingPolicy;
  using path_termination = PathTerminationPolicy;
  using light_sampling = LightSamplingPolicy;
  using material_model = MaterialModelPolicy;

  template <Sampler P>
  using with_sampler = Config<P, estimator, fresnel, antialiasing, sphere_shading, diffuse_sampling,
                              path_termination, light_sampling, material_model>;
  template <Estimator P>
  using with_estimator = Config<sampler, P, fresnel, antialiasing, sphere_shading, diffuse_sampling,
                                path_termination, light_sampling, material_model>;
  template <Fresnel P>
  using with_fresnel = Config<sampler, estimator, P, antialiasing, sphere_shading, diffuse_sampling,
                              path_termination, light_sampling, material_model>;
  template <Antialiasing P>
  using with_antialiasing = Config<sampler, estimator, fresnel, P, sphere_shading, diffuse_sampling,
                                   path_termination, light_sampling, material_model>;
  template <SphereShading P>
  using with_sphere_shading = Config<sampler, estimator, fresnel, antialiasing, P, diffuse_sampling,
                                     path_termination, light_sampling, material_model>;
  template <DiffuseSampling P>
  using with_diffuse_sampling = Config<sampler, estimator, fresnel, antialiasing, sphere_shading, P,
                                       path_termination, light_sampling, material_model>;
  template <PathTermination P>
  using with_path_termination = Config<sampler, estimator, fresnel, antialiasing, sphere_shading,
                                       diffuse_sampling, P, light_sampling, material_model>;
  template <LightSampling P>
  using with_light_sampling = Config<sampler, estimator, fresnel, antialiasing, sphere_shading,
                                     diffuse_sampling, path_termination, P, material_model>;
  template <MaterialModel P>
  using with_material_model = Config<sampler, estimator, fresnel, antialiasing, sphere_shading,
                                     diffuse_sampling, path_termination, light_sampling, P>;
};

namespace detail {
// Deduction accepts a class derived from a Config, which is what a named variant is.
template <typename S, typename M, typename F, typename A, typename H, typename D, typename T,
          typename L, typename B>
std::true_type derives_from_config(const Config<S, M, F, A, H, D, T, L, B>*);
std::false_type derives_from_config(...);
}  // namespace detail

/// A Config, or a class derived from one (a named variant, see variants.hpp).
template <typename C>
concept RenderConfig = decltype(detail::derives_from_config(std::declval<const C*>()))::value;

}  // namespace glint::inline GLINT_ISA_NAMESPACE
