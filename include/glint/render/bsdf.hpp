#pragma once
// What every estimator asks of a material at a hit, and nothing more: sample a direction for the
// light to continue in, the value f |cos| for a given direction, and the density of sampling it,
// in both transport directions. The estimators (render/estimators/) see materials only through
// the Bsdf concept, so that a new lobe is a new material model (policy/material_model.hpp) and
// no change to any estimator: direct light at a vertex is f |cos| Li / pdf wherever the material
// has a lobe with a density, whatever that lobe is.
//
// A Bsdf is built per hit and written once over a Float type (math/wide.hpp): one path at width
// 1, a Float's lanes of paths wider, the same bits in every lane.

#include <concepts>
#include <cstdint>
#include <type_traits>

#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/scattering.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The kinds of lobe: one with a density over the directions of its side (diffuse), and the two
/// delta lobes, whose one direction no other sampling can produce (mirror reflection,
/// transmission through an interface, Fresnel reflection there included).
enum class Lobe : std::uint8_t { diffuse, mirror, transmission };

/// What a path carries: radiance (a camera path, followed from the eye) or importance (a light
/// path, followed from a light). The two see the same material but for refraction: a camera
/// path's radiance goes through an interface unscaled, so a light path, its adjoint, is scaled by
/// (incident index / transmitted index)^2 there, the ratio of the solid angles the interface
/// maps onto each other. (A path that enters and leaves a sphere is scaled by 1 either way.)
enum class Transport : std::uint8_t { radiance, importance };

/// A Lobe per lane: the Lobe itself at width 1, its value in an Int lane wider.
template <typename F>
using LobeFor = std::conditional_t<kLanesOf<F> == 1, Lobe, IntFor<F>>;
template <typename F>
LobeFor<F> lobe_lanes(Lobe lobe) {
  if constexpr (kLanesOf<F> == 1)
    return lobe;
  else
    return splat<IntFor<F>>(std::int32_t(lobe));
}

/// One sampled direction per lane: what pbrt-v4's BSDFSample and Mitsuba 3's BSDFSample3f hold.
/// The weight f·cos/pdf is kept as two factors, weight = tint * factor, so that the estimators
/// fold their own scalars (roulette) into `factor` before the colour.
template <typename F>
struct BasicScatterSample {
  Vec3For<F> direction;  ///< unit direction the light continues in (away from the surface)
  Vec3For<F> tint;       ///< the colour part of the weight
  F factor;              ///< the scalar part of the weight
  /// Density of `direction`: per solid angle for a lobe with a density; for a delta lobe (mirror,
  /// refraction) the discrete probability of having chosen it.
  F pdf;
  MaskFor<F> delta;  ///< a mirror or refraction direction: no other direction has a density
  LobeFor<F> lobe;

  Vec3For<F> weight() const { return tint * factor; }
};
using ScatterSample = BasicScatterSample<float>;

/// A material at a Float's lanes of hits, as the estimators use it. B is built from the hit
/// (BasicSurfaceInteraction), the direction the path arrived along, and the lanes to build; then
///  - scatters(): the lanes where some lobe reflects or transmits light at all;
///  - has_density(): the lanes where some lobe has a density over directions, so that light can
///    be sampled towards the point and subpaths joined there (not only delta lobes);
///  - transmits_with_density(): the lanes where such a lobe also transmits, so that light is
///    sampled and joined on both sides of the surface (B::transmits_with_density_at(surface)
///    says the same of every hit on a sphere, for a vertex rebuilt from its sphere alone);
///  - sample<mode>(draws, lanes): a direction and its weight f |cos| / pdf for a path carrying
///    `mode`, drawn from `draws` (next_1d, next_2d) in the lanes of `lanes` (which scatter);
///  - evaluate<mode>(direction): f |cos| for light leaving in unit `direction` (zero for the delta
///    lobes, which have no value at a given direction);
///  - pdf(direction): the density per unit solid angle with which sample() produces `direction`
///    through its lobes with a density (zero where only a delta lobe could).
/// `Draws` is what the estimator draws from at this width: a Sampler at width 1.
template <typename B, typename F, typename Draws>
concept Bsdf = requires(const B bsdf, const BasicSurfaceInteraction<F>& interaction,
                        const Vec3For<F>& direction, MaskFor<F> lanes, Draws& draws,
                        const SurfaceProperties& surface) {
  B(interaction, direction, lanes);
  { bsdf.scatters() } -> std::same_as<MaskFor<F>>;
  { bsdf.has_density() } -> std::same_as<MaskFor<F>>;
  { bsdf.transmits_with_density() } -> std::same_as<MaskFor<F>>;
  { B::transmits_with_density_at(surface) } -> std::same_as<bool>;
  {
    bsdf.template sample<Transport::radiance>(draws, lanes)
    } -> std::same_as<BasicScatterSample<F>>;
  {
    bsdf.template sample<Transport::importance>(draws, lanes)
    } -> std::same_as<BasicScatterSample<F>>;
  { bsdf.template evaluate<Transport::radiance>(direction) } -> std::same_as<Vec3For<F>>;
  { bsdf.template evaluate<Transport::importance>(direction) } -> std::same_as<Vec3For<F>>;
  { bsdf.pdf(direction) } -> std::same_as<F>;
};

/// A Bsdf whose lobes can also be followed one by one, each weighted by its share of the
/// material, as the report's estimator follows every lobe (TreeEstimator):
///  - has_lobe(lobe): whether the lobe is present;
///  - sample_lobe<mode>(lobe, draws, lanes): a direction of that lobe alone, its weight carrying
///    the lobe's share;
///  - lobe_pdf(lobe, direction): the density of sample_lobe(lobe) producing `direction`.
template <typename B, typename F, typename Draws>
concept LobewiseBsdf = Bsdf<B, F, Draws> &&
    requires(const B bsdf, Lobe lobe, const Vec3For<F>& direction, Draws& draws) {
  { bsdf.has_lobe(lobe) } -> std::same_as<MaskFor<F>>;
  {
    bsdf.template sample_lobe<Transport::radiance>(lobe, draws)
    } -> std::same_as<BasicScatterSample<F>>;
  { bsdf.lobe_pdf(lobe, direction) } -> std::same_as<F>;
};

/// A Bsdf at one hit (width 1) that can leave a record of itself at a vertex of a stored subpath
/// (the bidirectional estimators), to be asked after the hit is gone: record<mode>() gives a
/// trivially copyable B::Record with
///  - has_density(): whether some lobe has a density (joins and merges can use the vertex);
///  - transmits_with_density(): whether such a lobe transmits (light joins it from both sides);
///  - f(facing, wo, wi): f (without the cosine) for light scattered between unit directions wo,
///    towards where the subpath reached the vertex from, and wi, in the subpath's transport mode;
///  - pdf(facing, wo, wi): the density per unit solid angle with which the Bsdf samples wi for a
///    path that arrived from wo (zero where only a delta lobe could).
/// `facing` is the vertex's normal on the side its subpath arrived from, which the vertex keeps;
/// wo is on that side but for a density asked the other way round through a lobe that
/// transmits.
template <typename B, typename Draws>
concept RecordableBsdf = Bsdf<B, float, Draws> &&
    std::is_trivially_copyable_v<typename B::Record> &&
    requires(const B bsdf, const typename B::Record record, const Vec3& direction) {
  { bsdf.template record<Transport::radiance>() } -> std::same_as<typename B::Record>;
  { bsdf.template record<Transport::importance>() } -> std::same_as<typename B::Record>;
  { record.has_density() } -> std::same_as<bool>;
  { record.transmits_with_density() } -> std::same_as<bool>;
  { record.f(direction, direction, direction) } -> std::same_as<Color>;
  { record.pdf(direction, direction, direction) } -> std::same_as<float>;
};

/// The Bsdf of Config C's material model at width F (one path: float).
template <typename C, typename F = float>
using BsdfAt = typename C::material_model::template bsdf<C, F>;

}  // namespace glint::inline GLINT_ISA_NAMESPACE
