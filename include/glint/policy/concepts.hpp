#pragma once
// The policy concepts. Each rendering feature is a policy type chosen at compile time; these
// concepts are the contract a type must meet, so that a wrong type fails with one error naming
// the concept rather than pages of template instantiation.

#include <concepts>
#include <cstdint>
#include <string_view>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"
#include "glint/math/wide.hpp"
#include "glint/scene/material.hpp"
#include "glint/scene/sphere_texture.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Identifies one sample of one pixel, or (W > 1) one in each of W lanes; samplers derive all
/// their randomness from it, so the image does not depend on which thread renders which pixel.
/// The count and the seed are the render's, the same in every lane, so that what depends on the
/// seed alone is hashed once for all lanes.
template <int W>
struct PixelSamples {
  UInt<W> x{};
  UInt<W> y{};
  UInt<W> index{};                      ///< sample number within the pixel, 0 .. count-1
  std::uint32_t samples_per_pixel = 1;  ///< lets stratified samplers plan their strata
  std::uint64_t seed = 0;
};
using PixelSample = PixelSamples<1>;

/// Where sample values come from: a stream of values in [0,1), dimension by dimension.
template <typename S>
concept Sampler = std::default_initializable<S> && std::copyable<S> &&
    requires(S sampler, const PixelSample& pixel_sample) {
  sampler.start(pixel_sample);
  { sampler.next_1d() } -> std::same_as<float>;
  { sampler.next_2d() } -> std::same_as<Vec2>;
};

/// A sampler with a form that draws for W paths at once, one per lane: S::template Wide<W>,
/// which loads and stores lane i from and to a sampler and draws for the lanes of a mask (the
/// others keep their state), each lane drawing exactly what its sampler would.
template <typename S, int W>
concept WideSampler = Sampler<S> &&
    requires(typename S::template Wide<W> lanes, const S& from, S& to, Mask<W> mask) {
  lanes.set_lane(0, from);
  lanes.get_lane(0, to);
  { lanes.next_1d(mask) } -> std::same_as<Float<W>>;
  { lanes.next_2d(mask) } -> std::same_as<Vec2For<Float<W>>>;
};

/// A WideSampler whose Wide form also starts the lanes of a mask at once, each as S::start
/// would with that lane's PixelSample.
template <typename S, int W>
concept WideSamplerStart = WideSampler<S, W> &&
    requires(typename S::template Wide<W> lanes, Mask<W> mask, const PixelSamples<W>& s) {
  lanes.start(mask, s);
};

/// A diffuse bounce direction in the local frame (z = normal) and its weight cos(theta)/pdf,
/// for one path (F = float) or for a Float's lanes of paths.
template <typename F>
struct BasicDirectionSample {
  Vec3For<F> local_direction;
  F weight;
};
using DirectionSample = BasicDirectionSample<float>;

/// How the diffuse bounce direction is drawn.
template <typename D>
concept DiffuseSampling = requires(Vec2 u) {
  { D::sample(u) } -> std::same_as<DirectionSample>;
  { D::pdf(float{}) } -> std::same_as<float>;  // density for a given cos(theta)
};

/// Which paths estimate the image (camera paths, paths from the lights, ...): the policy names
/// its execution model, a class template over the Config: `E::template execution<C>`. (The
/// check forms it for `void` without instantiating it, so executions and estimators leave C
/// unconstrained in their declaration and check it in their body.)
template <typename E>
concept Estimator = requires {
  { E::name } -> std::convertible_to<std::string_view>;
  typename E::template execution<void>;
};

/// Which materials spheres can have: the policy names the Bsdf (render/bsdf.hpp) of a hit, a class
/// template over the Config and the width: `P::template bsdf<C, F>` (the check forms it for
/// `void` without instantiating it, as Estimator does), and says which scene materials it
/// renders (`supports`), so that a variant refuses a scene it would render wrongly.
template <typename P>
concept MaterialModel = requires(const Material& material) {
  { P::name } -> std::convertible_to<std::string_view>;
  typename P::template bsdf<void, float>;
  { P::supports(material) } -> std::same_as<bool>;
};

/// Fresnel reflectance of a dielectric interface, used for fully transparent spheres.
/// cos_incident is measured on the incident side; eta_* are the refractive indices.
template <typename F>
concept Fresnel = requires(float cos_incident, float eta_incident, float eta_transmitted) {
  { F::enabled } -> std::convertible_to<bool>;
  { F::reflectance(cos_incident, eta_incident, eta_transmitted) } -> std::same_as<float>;
};

/// Where in the pixel a primary ray goes: an offset from the pixel centre, in pixels; the
/// density of those offsets (the pixel filter), and the half-width of the square beyond which
/// it is zero (0: all rays through the centre, a filter with no density).
template <typename A>
concept Antialiasing = requires(Vec2 u, float sigma) {
  { A::enabled } -> std::convertible_to<bool>;
  { A::offset(u, sigma) } -> std::same_as<Vec2>;
  { A::density(u, sigma) } -> std::same_as<float>;
  { A::footprint(sigma) } -> std::same_as<float>;
};

/// Where on a sphere shading asks for the diffuse colour.
struct ShadingPoint {
  Vec3 direction;  ///< the unit direction from the sphere's centre
  /// The sphere's image (ShadingKind::texture), placed; null for the other kinds.
  const SphereTexture* texture = nullptr;
};

/// A sphere's diffuse colour at a point, given the sphere's base colour and where the point is.
/// `supports` lists the closed set of kinds a build handles; scenes using another kind are
/// rejected when loaded.
template <typename H>
concept SphereShading = requires(ShadingKind kind, Color base, const ShadingPoint& at) {
  { H::supports(kind) } -> std::same_as<bool>;
  { H::color(kind, base, at) } -> std::same_as<Color>;
};

/// When a path stops: at the maximum depth only, or earlier by Russian roulette.
template <typename T>
concept PathTermination = requires(int depth, float throughput) {
  { T::uses_roulette } -> std::convertible_to<bool>;
  // Probability of continuing after `depth` bounces for a path carrying `throughput`.
  { T::continue_probability(depth, throughput) } -> std::same_as<float>;
};

/// A multiple importance sampling heuristic: the weight of a sample made with density `pdf`
/// when another strategy would have made it with density `other_pdf` (both per solid angle).
template <typename H>
concept MisHeuristic = requires(float pdf, float other_pdf) {
  { H::weight(pdf, other_pdf) } -> std::same_as<float>;
};

/// How emissive spheres are found: only by bounces, or also by sampling them from diffuse hits,
/// with the weights that split each direction's light between the two strategies.
template <typename L>
concept LightSampling = requires(float pdf, float other_pdf) {
  { L::samples_emitters } -> std::convertible_to<bool>;
  { L::light_weight(pdf, other_pdf) } -> std::same_as<float>;   // a light sample's weight
  { L::bounce_weight(pdf, other_pdf) } -> std::same_as<float>;  // a bounce's, on an emitter
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
