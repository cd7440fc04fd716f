// Rough glass (render/materials/rough_interface.hpp through MicrofacetMaterial): the value of
// both transport modes against Walter et al.'s BSDF written out in double
// (tests/support/microfacet_reference.hpp), the adjoint relation between the modes, sampling
// against the pdf by chi-square on both sides of the surface, weights against f |cos| / pdf, the
// bidirectional record against the Bsdf (densities asked the other way round included), the
// directional albedo against the integral of f |cos| over the sphere (at most one, near one for a
// nearly smooth interface), and the interfaces that stay ideal.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "../support/microfacet_reference.hpp"
#include "direction_cells.hpp"
#include "glint/config.hpp"
#include "glint/render/materials/microfacet_material.hpp"
#include "statistics.hpp"
#include "top_of_sphere.hpp"

namespace rough_interface_test {

using glint::Color;
using glint::Material;
using glint::ScatterSample;
using glint::Transport;
using glint::Vec3;

using Config =
    glint::Config<glint::IndependentSampler, glint::PathTracing, glint::ExactFresnel,
                  glint::NoAntialiasing, glint::UniformShading, glint::CosineHemisphere,
                  glint::FixedDepth, glint::PointLightsOnly, glint::MicrofacetMaterialModel>;
using Bsdf = glint::MicrofacetMaterial<Config, float>;
using IdealBsdf = glint::ReportMaterial<Config, float>;

constexpr float kOutside = 1.0f;  // TopOfSphere's outside index

/// A hit on the top of the unit sphere (outside +z, index 1; inside index `ior`) reached along
/// `incoming`: from outside where incoming.z < 0, from inside where it is > 0.
using Hit = glint::test::TopOfSphereWith<Bsdf>;

Material frosted(float roughness, float transparent = 1.0f, Color tint = Color(1.0f)) {
  Material m;
  m.diffuse = 0.0f;
  m.transparent = transparent;
  m.transparent_color = tint;
  m.transparent_roughness = roughness;
  m.ior = 1.5f;
  return m;
}

glint::IndependentSampler sampler_for(std::uint32_t index) {
  glint::IndependentSampler sampler;
  sampler.start({7u, 2u, index, 1u, 5u});
  return sampler;
}

glint_test::Direction as_direction(const Vec3& v) {
  return {v.x, v.y, v.z};
}
Vec3 as_vec3(const glint_test::Direction& d) {
  return Vec3(float(d.x), float(d.y), float(d.z));
}

/// A direction at angle theta from +z towards +x, turned by phi about z.
Vec3 direction(double theta, double phi = 0.0) {
  return Vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
              float(std::cos(theta)));
}

/// A direction drawn uniformly over the sphere up to `edge` in |cos theta|, at least 0.08 away
/// from the surface's plane (at grazing angles single precision leaves the textbook's values).
Vec3 random_direction(std::mt19937& random, double edge) {
  std::uniform_real_distribution<double> cosine(-edge, edge), turn(0.0, 2.0 * std::numbers::pi);
  double c = cosine(random);
  if (std::abs(c) < 0.08) c = c < 0.0 ? -0.08 : 0.08;
  return direction(std::acos(c), turn(random));
}

/// The index on the side of unit direction `w`.
float index_of(const Vec3& w, const Material& m) {
  return w.z > 0.0f ? kOutside : m.ior;
}

/// The integral of g over the whole sphere of directions.
template <typename G>
double sphere_integral(G&& g, int n) {
  return glint_test::hemisphere_integral(g, n) +
         glint_test::hemisphere_integral(
             [&](const glint_test::Direction& d) {
               return g(glint_test::Direction{d.x, d.y, -d.z});
             },
             n);
}

TEST_CASE("rough glass: f in both transport modes against Walter et al.'s BSDF in double",
          "[microfacet][rough_glass]") {
  std::mt19937 random(5);
  struct Case {
    Material material;
    bool fresnel;
  };
  for (const Case& c : {Case{frosted(0.3f), true}, Case{frosted(0.7f), true},
                        Case{frosted(0.5f, 0.6f, Color(0.9f, 0.7f, 0.5f)), false}})
    for (int k = 0; k < 3000; ++k) {
      const Vec3 wo = random_direction(random, 0.97), wi = random_direction(random, 0.97);
      const Hit hit(c.material, -wo);
      const Bsdf bsdf = hit.bsdf(-wo);
      const double alpha =
          double(c.material.transparent_roughness) * double(c.material.transparent_roughness);
      const double eta_o = index_of(wo, c.material), eta_i = index_of(wi, c.material);
      // Radiance: light from wi leaves along wo; importance: from wo along wi. glint's
      // radiance goes through an interface unscaled: the physical value times (eta_i/eta_o)^2.
      const double physical_in = glint_test::textbook_rough_dielectric(
          alpha, kOutside, c.material.ior, as_direction(wi), as_direction(wo), c.fresnel);
      const double physical_out = glint_test::textbook_rough_dielectric(
          alpha, kOutside, c.material.ior, as_direction(wo), as_direction(wi), c.fresnel);
      const double scale = c.material.transparent;
      const double radiance = scale * physical_in * (eta_i / eta_o) * (eta_i / eta_o);
      const double importance = scale * physical_out * (eta_o / eta_i) * (eta_o / eta_i);
      const double cos_i = std::abs(double(wi.z));
      INFO("wo " << wo.x << "," << wo.y << "," << wo.z << "; wi " << wi.x << "," << wi.y << ","
                 << wi.z << "; roughness " << c.material.transparent_roughness);
      const Color f_radiance = bsdf.evaluate<Transport::radiance>(wi) / float(cos_i);
      const Color f_importance = bsdf.evaluate<Transport::importance>(wi) / float(cos_i);
      const double tint = c.material.transparent_color.y;
      CHECK(double(f_radiance.y) == Approx(radiance * tint).epsilon(2e-3).margin(1e-6));
      CHECK(double(f_importance.y) == Approx(importance * tint).epsilon(2e-3).margin(1e-6));
    }
}

TEST_CASE("rough glass: importance from wo to wi is radiance from wi to wo (the adjoint)",
          "[microfacet][rough_glass]") {
  std::mt19937 random(9);
  for (const Material& material : {frosted(0.4f), frosted(0.8f, 0.7f)})
    for (int k = 0; k < 2000; ++k) {
      const Vec3 wo = random_direction(random, 0.95), wi = random_direction(random, 0.95);
      const Hit from_wo(material, -wo), from_wi(material, -wi);
      const float importance =
          from_wo.bsdf(-wo).evaluate<Transport::importance>(wi).x / std::abs(wi.z);
      const float radiance = from_wi.bsdf(-wi).evaluate<Transport::radiance>(wo).x / std::abs(wo.z);
      INFO("wo " << wo.x << "," << wo.y << "," << wo.z << "; wi " << wi.x << "," << wi.y << ","
                 << wi.z);
      CHECK(importance == Approx(radiance).epsilon(1e-3).margin(5e-4));
    }
}

/// Chi-square of `n` samples of `bsdf` in `mode` against its pdf over the whole sphere, the
/// samples that carry nothing (a facet that sends the light to the wrong side) in one more cell.
/// The cells' pole is off the lobes, and each cell's mass is integrated on a 64 x 64 grid: the
/// density of refraction rises steeply towards the edge of the directions a facet can reach.
template <Transport mode>
glint::test::ChiSquare sampling_against_pdf(const Bsdf& bsdf, int n, std::uint32_t seed) {
  auto sampler = sampler_for(seed);
  return glint::test::sampling_against_density<64>([&] { return bsdf.sample<mode>(sampler); },
                                                   [&](const Vec3& d) { return bsdf.pdf(d); }, n,
                                                   glint::test::CellPole::y);
}

/// Frosted glass, frosted glass under a diffuse coat, and a rough mirror over rough glass.
std::vector<Material> mixtures() {
  Material coated = frosted(0.6f, 0.7f);
  coated.diffuse = 0.3f;
  Material mirrored = frosted(0.5f, 0.5f);
  mirrored.mirror = 0.5f;
  mirrored.mirror_roughness = 0.4f;
  return {frosted(0.4f), frosted(0.9f), coated, mirrored};
}

TEST_CASE("rough glass: samples follow the pdf on both sides, from both sides",
          "[microfacet][rough_glass][scattering]") {
  std::uint32_t seed = 100;
  for (const Material& material : mixtures())
    for (const double theta : {0.2, 1.0, 1.4})
      for (const bool from_inside : {false, true}) {
        const Vec3 incoming = from_inside ? direction(theta) : -direction(theta);
        const Hit hit(material, incoming);
        const Bsdf bsdf = hit.bsdf(incoming);
        INFO("roughness " << material.transparent_roughness << ", diffuse " << material.diffuse
                          << ", mirror " << material.mirror << ", theta " << theta
                          << (from_inside ? ", from inside" : ", from outside"));
        const glint::test::ChiSquare radiance =
            sampling_against_pdf<Transport::radiance>(bsdf, 200000, ++seed);
        INFO("chi-square " << radiance.statistic << " with " << radiance.degrees_of_freedom
                           << " degrees of freedom");
        CHECK_FALSE(radiance.rejected());
        const glint::test::ChiSquare importance =
            sampling_against_pdf<Transport::importance>(bsdf, 200000, ++seed);
        CHECK_FALSE(importance.rejected());
      }
}

TEST_CASE(
    "rough glass: a sample's weight is f |cos| / pdf; the record agrees with the Bsdf, densities "
    "asked the other way round included",
    "[microfacet][rough_glass][scattering]") {
  for (const Material& material : mixtures())
    for (const double theta : {0.3, 1.2})
      for (const bool from_inside : {false, true}) {
        const Vec3 incoming = from_inside ? direction(theta) : -direction(theta);
        const Vec3 wo = -incoming;
        const Hit hit(material, incoming);
        const Bsdf bsdf = hit.bsdf(incoming);
        const Vec3 facing = hit.interaction.at.facing_normal;
        const Bsdf::Record radiance_record = bsdf.record<Transport::radiance>();
        const Bsdf::Record importance_record = bsdf.record<Transport::importance>();
        CHECK(radiance_record.transmits_with_density());
        auto sampler = sampler_for(std::uint32_t(theta * 10) + (from_inside ? 50u : 0u));
        for (int i = 0; i < 1500; ++i) {
          const ScatterSample s = bsdf.sample<Transport::importance>(sampler);
          if (s.delta) {
            CHECK(s.weight() == Color(0.0f));
            continue;
          }
          const Vec3 wi = s.direction;
          const float pdf = bsdf.pdf(wi);
          const Color f_cos = bsdf.evaluate<Transport::importance>(wi);
          INFO("direction " << wi.x << "," << wi.y << "," << wi.z);
          CHECK(s.pdf == Approx(pdf).epsilon(1e-5));
          if (material.diffuse == 0.0f && material.mirror == 0.0f) {
            CHECK(s.weight().x * pdf == Approx(f_cos.x).epsilon(2e-4));
          }
          const float cos_i = std::abs(wi.z);
          CHECK(importance_record.f(facing, wo, wi).x * cos_i == Approx(f_cos.x).epsilon(1e-5));
          CHECK(radiance_record.f(facing, wo, wi).x * cos_i ==
                Approx(bsdf.evaluate<Transport::radiance>(wi).x).epsilon(1e-5));
          CHECK(radiance_record.pdf(facing, wo, wi) == Approx(pdf).epsilon(1e-5));
          // The other way round: the density of sampling wo for a path arriving from wi, which
          // is the Bsdf's at the hit reached along -wi.
          const Hit reverse(material, -wi);
          CHECK(radiance_record.pdf(facing, wi, wo) ==
                Approx(reverse.bsdf(-wi).pdf(wo)).epsilon(1e-4));
        }
      }
}

TEST_CASE(
    "rough glass: the directional albedo by sampling matches the integral of f |cos|, at most "
    "one, near one where nearly smooth",
    "[microfacet][rough_glass][scattering]") {
  for (const float roughness : {0.2f, 0.5f, 1.0f})
    for (const double theta : {0.0, 0.8, 1.3})
      for (const bool from_inside : {false, true}) {
        const Material material = frosted(roughness);
        const Vec3 incoming = from_inside ? direction(theta) : -direction(theta);
        const Vec3 wo = -incoming;
        const Hit hit(material, incoming);
        const Bsdf bsdf = hit.bsdf(incoming);
        const double integral = sphere_integral(
            [&](const glint_test::Direction& wi) {
              return double(bsdf.evaluate<Transport::radiance>(as_vec3(wi)).x);
            },
            1200);
        // The physical albedo of light arriving along -wo, which radiance's equals.
        const double alpha = double(roughness) * roughness;
        const double textbook = sphere_integral(
            [&](const glint_test::Direction& wi) {
              return glint_test::textbook_rough_dielectric(alpha, kOutside, material.ior,
                                                           as_direction(wo), wi, true) *
                     std::abs(wi.z);
            },
            1200);
        auto sampler = sampler_for(900u + std::uint32_t(roughness * 10 + theta * 3));
        constexpr int kSamples = 200000;
        double sum = 0.0, squares = 0.0;
        for (int i = 0; i < kSamples; ++i) {
          const double w = bsdf.sample<Transport::radiance>(sampler).weight().x;
          sum += w;
          squares += w * w;
        }
        const double mean = sum / kSamples;
        const double error = std::sqrt((squares / kSamples - mean * mean) / kSamples);
        INFO("roughness " << roughness << ", theta " << theta
                          << (from_inside ? " from inside" : " from outside") << ": sampled "
                          << mean << " +- " << error << ", integral " << integral << ", textbook "
                          << textbook);
        CHECK(integral == Approx(textbook).epsilon(5e-3));
        CHECK(std::abs(mean - integral) < 5.0 * error + 3e-3);
        CHECK(integral <= 1.0 + 3e-3);
        if (roughness == 0.2f && theta == 0.0) CHECK(integral > 0.97);
      }
}

TEST_CASE(
    "rough glass: an interface smoother than the narrowest lobe, or between equal indices, "
    "is the ideal one",
    "[microfacet][rough_glass][scattering]") {
  const Vec3 incoming = -direction(0.6);
  Material index_matched = frosted(0.5f);
  index_matched.ior = kOutside;
  for (const Material& material : {frosted(0.0f), frosted(0.03f), index_matched}) {
    const Hit hit(material, incoming);
    const Bsdf bsdf = hit.bsdf(incoming);
    CHECK_FALSE(bsdf.has_density());
    CHECK_FALSE(bsdf.transmits_with_density());
    const IdealBsdf ideal(hit.interaction, incoming);
    auto sampler = sampler_for(3u), ideal_sampler = sampler_for(3u);
    for (int i = 0; i < 100; ++i) {
      const ScatterSample s = bsdf.sample(sampler);
      const ScatterSample t = ideal.sample(ideal_sampler);
      CHECK(s.delta);
      CHECK(s.direction == t.direction);
      CHECK(s.weight() == t.weight());
    }
  }
}

}  // namespace rough_interface_test
