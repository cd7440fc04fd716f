#pragma once
// A renderer configuration: one policy per feature, all checked against their concepts. A
// variant is an alias of Config; an ablation swaps one policy with the with_* aliases.

#include "glint/policy/antialiasing.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/diffuse_sampling.hpp"
#include "glint/policy/fresnel.hpp"
#include "glint/policy/material_model.hpp"
#include "glint/policy/sampler.hpp"
#include "glint/policy/shading.hpp"
#include "glint/policy/termination.hpp"

namespace glint {

template <Sampler S, MaterialModel M, FresnelModel F, AntiAliasing A, SphereShading H,
          DiffuseSampling D = UniformHemisphere, PathTermination T = FixedDepth>
struct Config {
  using sampler = S;
  using material_model = M;
  using fresnel = F;
  using antialiasing = A;
  using shading = H;
  using diffuse_sampling = D;
  using termination = T;

  template <Sampler S2>
  using with_sampler = Config<S2, M, F, A, H, D, T>;
  template <MaterialModel M2>
  using with_material_model = Config<S, M2, F, A, H, D, T>;
  template <FresnelModel F2>
  using with_fresnel = Config<S, M, F2, A, H, D, T>;
  template <AntiAliasing A2>
  using with_antialiasing = Config<S, M, F, A2, H, D, T>;
  template <SphereShading H2>
  using with_shading = Config<S, M, F, A, H2, D, T>;
  template <DiffuseSampling D2>
  using with_diffuse_sampling = Config<S, M, F, A, H, D2, T>;
  template <PathTermination T2>
  using with_termination = Config<S, M, F, A, H, D, T2>;
};

namespace detail {
template <typename T>
struct is_config : std::false_type {};
template <typename S, typename M, typename F, typename A, typename H, typename D, typename T>
struct is_config<Config<S, M, F, A, H, D, T>> : std::true_type {};
}  // namespace detail

/// Any instantiation of Config (whose parameters the Config template has already checked).
template <typename C>
concept RenderConfig = detail::is_config<C>::value;

}  // namespace glint
