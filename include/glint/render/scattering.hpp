#pragma once
// How light scatters at a hit: the side of the surface a ray arrives on, the mirror and Snell
// directions, and the report's material as a component that samples, evaluates and gives the
// density of its lobes. The estimators (render/estimators/) decide which lobes to follow; this
// component only answers for one lobe, or for one lobe chosen by coefficient.

#include <cmath>
#include <cstdint>
#include <optional>

#include "glint/config.hpp"
#include "glint/math/sampling.hpp"
#include "glint/scene/scene.hpp"

namespace glint {

namespace detail {

/// The side of a surface a ray arrives on.
struct Interface {
  Vec3 facing_normal;  ///< unit normal on the side the ray came from
  float cos_incident;  ///< cosine between the reversed ray and facing_normal, in [0, 1]
  bool from_inside;
};

inline Interface interface_at(const Ray& ray, const Vec3& outward_normal) {
  const float cos_out = glm::dot(ray.direction, outward_normal);
  const bool from_inside = cos_out > 0.0f;
  return {from_inside ? -outward_normal : outward_normal, std::fabs(cos_out), from_inside};
}

inline Vec3 reflect(const Vec3& direction, const Interface& at) {
  return direction + (2.0f * at.cos_incident) * at.facing_normal;
}

/// The refracted direction by Snell's law (eta = incident index / transmitted index); none on
/// total internal reflection.
inline std::optional<Vec3> refract(const Vec3& direction, const Interface& at, float eta) {
  const float sin2_transmitted = eta * eta * (1.0f - at.cos_incident * at.cos_incident);
  if (sin2_transmitted >= 1.0f) return std::nullopt;
  const float cos_transmitted = std::sqrt(1.0f - sin2_transmitted);
  return glm::normalize(eta * direction +
                        (eta * at.cos_incident - cos_transmitted) * at.facing_normal);
}

}  // namespace detail

/// Where a ray met the scene, with everything shading needs there: the geometry, the sphere's
/// properties and the side the ray came from.
struct SurfaceInteraction {
  SurfaceHit hit;
  const SurfaceProperties* surface;  ///< owned by the scene, which outlives every path
  detail::Interface at;

  const Material& material() const { return surface->material; }
};

/// The three lobes of the report's material.
enum class Lobe : std::uint8_t { diffuse, mirror, transmission };

/// One sampled lobe direction: what pbrt-v4's BSDFSample and Mitsuba 3's BSDFSample3f hold.
///
/// The weight f·cos/pdf is kept as two factors, weight = tint * factor: the estimators fold
/// their own scalars (roulette, throughput) into `factor` before the colour, and that order of
/// the multiplications is the one every image was made with (changing it changes the last bits
/// of pixels).
struct ScatterSample {
  Vec3 direction;  ///< unit direction the light continues in (away from the surface)
  Color tint;      ///< the colour part of the weight
  float factor;    ///< the scalar part of the weight
  /// Density of `direction`: per solid angle for the diffuse lobe; for a delta lobe (mirror,
  /// refraction) the discrete probability of having chosen it.
  float pdf;
  bool delta;  ///< a mirror or refraction direction: no other direction has a density
  Lobe lobe;

  Color weight() const { return tint * factor; }
};

/// The report's material at one hit: a diffuse lobe (coloured by the sphere's shading, directions
/// drawn by C::diffuse_sampling), a mirror lobe and a transmission lobe (refraction, with
/// Fresnel reflection by C::fresnel for fully transparent spheres and total internal reflection).
/// Each lobe's weight is its coefficient times its colour. Built per hit; it holds references to
/// the interaction and to the arriving ray's direction, so it must not outlive either.
template <RenderConfig C>
class ReportMaterial {
 public:
  using SamplerType = typename C::sampler;

  /// `incoming` is the direction of the arriving ray, read in place: mirror and refraction
  /// directions computed from a copy of it round differently once inlined (the compiler fuses
  /// multiply-adds according to where operands come from), which changes images.
  ReportMaterial(const SurfaceInteraction& interaction, const Vec3& incoming)
      : interaction_(interaction),
        incoming_(incoming),
        m_(interaction.material()),
        albedo_(m_.diffuse > 0.0f ? diffuse_albedo() : Color(0.0f)),
        total_(m_.diffuse + m_.mirror + m_.transparent) {}

  /// Whether the surface reflects at all (some lobe has a positive coefficient).
  bool scatters() const { return total_ > 0.0f; }
  bool has_lobe(Lobe lobe) const { return coefficient(lobe) > 0.0f; }
  /// The diffuse coefficient times the sphere's colour at the hit (zero without a diffuse lobe).
  const Color& albedo() const { return albedo_; }

  /// Samples lobe `lobe` alone; its weight carries the lobe's coefficient (for the estimator
  /// that follows every lobe). Diffuse draws one next_2d; transmission one next_1d when Fresnel
  /// applies; the mirror draws nothing.
  ScatterSample sample_lobe(Lobe lobe, SamplerType& sampler) const {
    switch (lobe) {
      case Lobe::diffuse: {
        ScatterSample s = sample_diffuse(sampler);
        s.factor = s.factor * kInvPi;
        return s;
      }
      case Lobe::mirror:
        return {mirror_direction(), m_.mirror_color, m_.mirror, 1.0f, true, Lobe::mirror};
      case Lobe::transmission:
      default: {
        ScatterSample s = sample_transmission(sampler);
        s.tint = m_.transparent_color;
        s.factor = m_.transparent;
        return s;
      }
    }
  }

  /// Chooses one lobe with probability coefficient / total (one next_1d), then samples it; the
  /// weight is divided by that probability and the pdf multiplied by it, so the expectation is
  /// that of following every lobe. Requires scatters().
  ScatterSample sample(SamplerType& sampler) const {
    const float u = sampler.next_1d() * total_;
    if (u < m_.diffuse) {
      ScatterSample s = sample_diffuse(sampler);
      s.factor = s.factor * kInvPi * total_ / m_.diffuse;
      s.pdf *= m_.diffuse / total_;
      return s;
    }
    if (u < m_.diffuse + m_.mirror)
      return {mirror_direction(), m_.mirror_color, total_, m_.mirror / total_, true, Lobe::mirror};
    ScatterSample s = sample_transmission(sampler);
    s.tint = m_.transparent_color;
    s.factor = total_;
    s.pdf *= m_.transparent / total_;
    return s;
  }

  /// f·cos for the direction `direction` leaving the surface: the diffuse lobe only, since a
  /// delta lobe has no value at a given direction.
  Color evaluate(const Vec3& direction) const {
    const float cosine = glm::dot(direction, interaction_.at.facing_normal);
    if (!(cosine > 0.0f)) return Color(0.0f);
    return albedo_ * (kInvPi * cosine);
  }

  /// Density of sample_lobe(lobe) producing `direction` (zero for delta lobes).
  float lobe_pdf(Lobe lobe, const Vec3& direction) const {
    if (lobe != Lobe::diffuse) return 0.0f;
    return C::diffuse_sampling::pdf(glm::dot(direction, interaction_.at.facing_normal));
  }

  /// Density of sample() producing `direction` (zero unless diffuse; requires scatters()).
  float pdf(const Vec3& direction) const {
    return m_.diffuse / total_ * lobe_pdf(Lobe::diffuse, direction);
  }

  /// The probability that sample() chooses `lobe` (requires scatters()).
  float lobe_probability(Lobe lobe) const { return coefficient(lobe) / total_; }

 private:
  float coefficient(Lobe lobe) const {
    switch (lobe) {
      case Lobe::diffuse:
        return m_.diffuse;
      case Lobe::mirror:
        return m_.mirror;
      case Lobe::transmission:
      default:
        return m_.transparent;
    }
  }

  Color diffuse_albedo() const {
    return m_.diffuse * C::sphere_shading::color(interaction_.surface->shading, m_.diffuse_color,
                                                 interaction_.hit.local_direction);
  }

  /// A diffuse direction with tint = albedo and factor = cos/pdf (without the 1/pi of the
  /// Lambertian f, which the callers multiply in at their place in the product).
  ScatterSample sample_diffuse(SamplerType& sampler) const {
    const DirectionSample sample = C::diffuse_sampling::sample(sampler.next_2d());
    const Vec3 direction =
        Frame::around(interaction_.at.facing_normal).to_world(sample.local_direction);
    return {direction,     albedo_,
            sample.weight, C::diffuse_sampling::pdf(sample.local_direction.z),
            false,         Lobe::diffuse};
  }

  Vec3 mirror_direction() const { return detail::reflect(incoming_, interaction_.at); }

  /// The direction light continues in through a transparent surface: refracted, or reflected
  /// on total internal reflection or (fully transparent spheres with Fresnel) with
  /// probability F. The pdf is the probability of the branch taken; tint and factor are left
  /// for the caller.
  ScatterSample sample_transmission(SamplerType& sampler) const {
    const auto transmitted = [](const Vec3& direction, float pdf) {
      return ScatterSample{direction, Color(0.0f), 0.0f, pdf, true, Lobe::transmission};
    };
    const detail::Interface& at = interaction_.at;
    const SurfaceProperties& surface = *interaction_.surface;
    const float ior_inside = m_.ior;
    const float eta_incident = at.from_inside ? ior_inside : surface.ior_outside;
    const float eta_transmitted = at.from_inside ? surface.ior_outside : ior_inside;
    const std::optional<Vec3> refracted =
        detail::refract(incoming_, at, eta_incident / eta_transmitted);
    // Refraction or total internal reflection without a Fresnel choice: probability 1.
    if (!refracted) return transmitted(detail::reflect(incoming_, at), 1.0f);
    if constexpr (C::fresnel::enabled) {
      if (surface.fully_transparent) {
        const float reflectance =
            C::fresnel::reflectance(at.cos_incident, eta_incident, eta_transmitted);
        if (sampler.next_1d() < reflectance)
          return transmitted(detail::reflect(incoming_, at), reflectance);
        return transmitted(*refracted, 1.0f - reflectance);
      }
    }
    return transmitted(*refracted, 1.0f);
  }

  const SurfaceInteraction& interaction_;
  const Vec3& incoming_;
  const Material& m_;
  Color albedo_;
  float total_;
};

}  // namespace glint
