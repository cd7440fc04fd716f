// Rough and metal mirrors (render/materials/microfacet.hpp, microfacet_material.hpp): the
// Trowbridge-Reitz distribution against its normalisations (the projected normals integrate to
// one, the visible normals' projected area is the direction's cosine), the conductor's Fresnel
// reflectance against the closed forms at normal and grazing incidence and against a dielectric's
// where k = 0, the material's sampling against its pdf by chi-square, its weights against f cos /
// pdf, its directional albedo against a numerical integral of f cos (below one: single
// scattering loses the light the microfacets shadow), reciprocity, the record the bidirectional
// estimators keep against the Bsdf, and the lobes too narrow for single precision as the ideal
// mirror.

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
#include "glint/scene/metals.hpp"
#include "statistics.hpp"
#include "top_of_sphere.hpp"

namespace microfacet_test {

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
static_assert(glint::RecordableBsdf<Bsdf, Config::sampler>);
// The report's tree follows lobes by name; a rough lobe is not one of them.
static_assert(!glint::LobewiseBsdf<Bsdf, float, Config::sampler>);

constexpr double kPi = std::numbers::pi;

/// The top of a unit sphere reached along `incoming`, with its Bsdf.
using TopHit = glint::test::TopOfSphereWith<Bsdf>;

Material rough_mirror(float roughness, Color tint = Color(1.0f)) {
  Material m;
  m.diffuse = 0.0f;
  m.mirror = 1.0f;
  m.mirror_color = tint;
  m.mirror_roughness = roughness;
  return m;
}

Material metal(const char* name, float roughness, float mirror = 1.0f) {
  Material m = rough_mirror(roughness);
  const glint::Metal known = *glint::metal_named(name);
  m.metal_eta = known.eta;
  m.metal_k = known.k;
  m.mirror = mirror;
  m.diffuse = 1.0f - mirror;
  m.diffuse_color = Color(0.2f, 0.5f, 0.8f);
  return m;
}

/// The direction at angle theta from +z towards +x (travelling away from the surface).
Vec3 at_angle(double theta) {
  return Vec3(float(std::sin(theta)), 0.0f, float(std::cos(theta)));
}

glint::IndependentSampler sampler_for(std::uint32_t index) {
  glint::IndependentSampler sampler;
  sampler.start({3u, 5u, index, 1u, 11u});
  return sampler;
}

/// The reference's direction as glint's.
Vec3 as_vec3(const glint_test::Direction& d) {
  return Vec3(float(d.x), float(d.y), float(d.z));
}

TEST_CASE("Trowbridge-Reitz: projected normals integrate to one", "[microfacet]") {
  for (const float alpha : {0.02f, 0.1f, 0.3f, 0.7f, 1.0f}) {
    const glint::TrowbridgeReitz<float> d{alpha};
    // 2 pi times the integral over theta of D cos sin, finely enough for the narrowest lobe.
    constexpr int kSteps = 400000;
    const double step = 0.5 * kPi / kSteps;
    double sum = 0.0;
    for (int i = 0; i < kSteps; ++i) {
      const double theta = (i + 0.5) * step;
      sum += double(d.normal_density(at_angle(theta))) * std::cos(theta) * std::sin(theta);
    }
    INFO("alpha " << alpha);
    CHECK(2.0 * kPi * sum * step == Approx(1.0).epsilon(1e-3));
  }
}

TEST_CASE("Trowbridge-Reitz: the visible normals' projected area is the direction's cosine",
          "[microfacet]") {
  // Integral of G1(w) max(0, w.m) D(m) over the normals m = w.z: masking and distribution agree.
  for (const float alpha : {0.2f, 0.6f, 1.0f})
    for (const double theta : {0.0, 0.7, 1.3}) {
      const glint::TrowbridgeReitz<float> d{alpha};
      const Vec3 w = at_angle(theta);
      const double area = glint_test::hemisphere_integral(
          [&](const glint_test::Direction& normal) {
            const Vec3 m = as_vec3(normal);
            return double(d.masking(w)) * std::max(0.0, double(glm::dot(w, m))) *
                   double(d.normal_density(m));
          },
          1200);
      INFO("alpha " << alpha << ", theta " << theta);
      CHECK(area == Approx(double(w.z)).epsilon(2e-3));
    }
}

TEST_CASE("conductor reflectance: the closed forms at normal and grazing incidence",
          "[microfacet][fresnel]") {
  for (const auto& [eta, k] : std::vector<std::pair<float, float>>{
           {0.2f, 3.9f}, {1.66f, 9.2f}, {0.05f, 0.5f}, {2.5f, 0.0f}, {1.0f, 1.0f}}) {
    const double n = eta, kk = k;
    const double normal = ((n - 1) * (n - 1) + kk * kk) / ((n + 1) * (n + 1) + kk * kk);
    INFO("eta " << eta << ", k " << k);
    CHECK(glint::detail::conductor_reflectance(1.0f, eta, k) == Approx(normal).epsilon(1e-5));
    CHECK(glint::detail::conductor_reflectance(0.0f, eta, k) == Approx(1.0).epsilon(1e-6));
    for (int i = 0; i <= 20; ++i) {
      const float c = float(i) / 20.0f;
      const float r = glint::detail::conductor_reflectance(c, eta, k);
      CHECK(r >= 0.0f);
      CHECK(r <= 1.0f + 1e-6f);
    }
  }
  // The named metals head-on, as docs/scene-format.md lists them.
  const struct {
    const char* name;
    Color reflectance;
  } listed[] = {{"gold", Color(0.97f, 0.80f, 0.32f)},
                {"silver", Color(0.97f, 0.96f, 0.91f)},
                {"copper", Color(0.95f, 0.62f, 0.51f)},
                {"aluminium", Color(0.93f, 0.92f, 0.92f)}};
  for (const auto& metal : listed) {
    const glint::Metal known = *glint::metal_named(metal.name);
    const Color r = glint::conductor_reflectance(1.0f, known.eta, known.k);
    INFO(metal.name);
    for (int c = 0; c < 3; ++c)
      CHECK(r[c] == Approx(metal.reflectance[c]).margin(0.005));
  }
  // Gold reflects red most and blue least; silver is nearly white.
  const glint::Metal gold = *glint::metal_named("gold");
  const Color g = glint::conductor_reflectance(1.0f, gold.eta, gold.k);
  CHECK(g.x > g.y);
  CHECK(g.y > g.z);
  const glint::Metal silver = *glint::metal_named("silver");
  const Color s = glint::conductor_reflectance(1.0f, silver.eta, silver.k);
  CHECK(std::min({s.x, s.y, s.z}) > 0.9f);
}

TEST_CASE("conductor reflectance with k = 0 is a dielectric's", "[microfacet][fresnel]") {
  for (const float eta : {1.2f, 1.5f, 2.4f})
    for (int i = 0; i <= 50; ++i) {
      const float c = float(i) / 50.0f;
      INFO("eta " << eta << ", cos " << c);
      CHECK(glint::detail::conductor_reflectance(c, eta, 0.0f) ==
            Approx(glint::ExactFresnel::reflectance(c, 1.0f, eta)).margin(2e-6).epsilon(1e-4));
    }
}

/// Chi-square of `n` samples of `bsdf` in `mode` against its pdf, the delta samples (and the
/// rough samples reflected below the surface, which carry nothing) in one more cell.
template <Transport mode>
glint::test::ChiSquare sampling_against_pdf(const Bsdf& bsdf, int n, std::uint32_t seed) {
  auto sampler = sampler_for(seed);
  return glint::test::sampling_against_density([&] { return bsdf.sample<mode>(sampler); },
                                               [&](const Vec3& d) { return bsdf.pdf(d); }, n);
}

TEST_CASE("rough mirrors and metals: samples follow the pdf", "[microfacet][scattering]") {
  std::uint32_t seed = 0;
  for (const Material& material :
       {rough_mirror(0.6f), rough_mirror(1.0f), metal("gold", 0.8f), metal("copper", 0.7f, 0.6f)})
    for (const double theta : {0.2, 1.0, 1.4}) {
      const Vec3 incoming = -at_angle(theta);
      const TopHit hit(material, incoming);
      const Bsdf bsdf = hit.bsdf(incoming);
      INFO("roughness " << material.mirror_roughness << ", mirror " << material.mirror << ", theta "
                        << theta);
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

TEST_CASE("a rough mirror's sample weight is f cos / pdf, and the record agrees with the Bsdf",
          "[microfacet][scattering]") {
  for (const Material& material : {rough_mirror(0.4f, Color(0.9f, 0.8f, 0.7f)),
                                   metal("aluminium", 0.5f), metal("gold", 0.3f, 0.5f)})
    for (const double theta : {0.1, 0.9, 1.45}) {
      const Vec3 incoming = -at_angle(theta);
      const TopHit hit(material, incoming);
      const Bsdf bsdf = hit.bsdf(incoming);
      const Bsdf::Record record = bsdf.record<Transport::radiance>();
      const Vec3 facing(0.0f, 0.0f, 1.0f);
      auto sampler = sampler_for(std::uint32_t(theta * 100));
      for (int i = 0; i < 2000; ++i) {
        const ScatterSample s = bsdf.sample(sampler);
        if (s.delta) {
          CHECK(s.weight() == Color(0.0f));
          continue;
        }
        const Color f_cos = bsdf.evaluate(s.direction);
        const float pdf = bsdf.pdf(s.direction);
        INFO("theta " << theta << ", direction " << s.direction.x << "," << s.direction.y << ","
                      << s.direction.z);
        CHECK(s.pdf == Approx(pdf).epsilon(1e-5));
        if (material.diffuse == 0.0f) {
          // One lobe: its weight is the whole f cos / pdf.
          CHECK(s.weight().x * pdf == Approx(f_cos.x).epsilon(2e-4));
          CHECK(s.weight().z * pdf == Approx(f_cos.z).epsilon(2e-4));
        }
        const Color f = record.f(facing, -incoming, s.direction) * s.direction.z;
        CHECK(f.x == Approx(f_cos.x).epsilon(1e-5));
        CHECK(f.y == Approx(f_cos.y).epsilon(1e-5));
        CHECK(record.pdf(facing, -incoming, s.direction) == Approx(pdf).epsilon(1e-5));
      }
    }
}

TEST_CASE("a rough mirror's directional albedo: sampling against the integral of f cos, below one",
          "[microfacet][scattering]") {
  for (const float roughness : {0.3f, 0.6f, 1.0f})
    for (const double theta : {0.0, 0.8, 1.3}) {
      const Vec3 incoming = -at_angle(theta);
      const TopHit hit(rough_mirror(roughness), incoming);
      const Bsdf bsdf = hit.bsdf(incoming);
      const double integral = glint_test::hemisphere_integral(
          [&](const glint_test::Direction& wi) { return double(bsdf.evaluate(as_vec3(wi)).x); },
          1500);
      const double textbook = glint_test::textbook_ggx_albedo(double(roughness) * roughness, theta);
      auto sampler = sampler_for(7u + std::uint32_t(roughness * 10));
      constexpr int kSamples = 200000;
      double sum = 0.0, squares = 0.0;
      for (int i = 0; i < kSamples; ++i) {
        const double w = bsdf.sample(sampler).weight().x;
        sum += w;
        squares += w * w;
      }
      const double mean = sum / kSamples;
      const double error = std::sqrt((squares / kSamples - mean * mean) / kSamples);
      INFO("roughness " << roughness << ", theta " << theta << ": sampled " << mean << " +- "
                        << error << ", integral " << integral << ", textbook " << textbook);
      CHECK(integral == Approx(textbook).epsilon(1e-4));
      CHECK(std::abs(mean - integral) < 5.0 * error + 2e-3);
      CHECK(integral < 1.0);
      // Smoother lobes lose less: at roughness 0.3 and normal incidence nearly nothing.
      if (roughness == 0.3f && theta == 0.0) CHECK(integral > 0.98);
    }
}

TEST_CASE("rough metal reflection is reciprocal", "[microfacet][scattering]") {
  std::mt19937 random(12);
  std::uniform_real_distribution<float> angle(0.02f, 1.5f), turn(0.0f, 6.28f);
  const auto direction = [&] {
    const float theta = angle(random), phi = turn(random);
    return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  for (const Material& material : {metal("gold", 0.5f), metal("silver", 0.9f, 0.7f)})
    for (int i = 0; i < 500; ++i) {
      const Vec3 wo = direction(), wi = direction();
      const TopHit hit_wo(material, -wo), hit_wi(material, -wi);
      const Bsdf from_wo = hit_wo.bsdf(-wo);
      const Bsdf from_wi = hit_wi.bsdf(-wi);
      const Color f_oi = from_wo.evaluate(wi) / wi.z;
      const Color f_io = from_wi.evaluate(wo) / wo.z;
      INFO("wo " << wo.x << "," << wo.y << "," << wo.z << "; wi " << wi.x << "," << wi.y << ","
                 << wi.z);
      CHECK(f_oi.x == Approx(f_io.x).epsilon(1e-4));
      CHECK(f_oi.z == Approx(f_io.z).epsilon(1e-4));
      const Bsdf::Record record = from_wo.record<Transport::importance>();
      const Vec3 facing(0.0f, 0.0f, 1.0f);
      CHECK(record.f(facing, wo, wi).y == Approx(record.f(facing, wi, wo).y).epsilon(1e-4));
    }
}

TEST_CASE(
    "a mirror smoother than the narrowest microfacet lobe is the ideal mirror; a smooth "
    "metal tints it by its reflectance",
    "[microfacet][scattering]") {
  const Vec3 incoming = -at_angle(0.6);
  for (const float roughness : {0.0f, 0.03f}) {
    const TopHit hit(rough_mirror(roughness), incoming);
    const Bsdf bsdf = hit.bsdf(incoming);
    auto sampler = sampler_for(3u);
    const ScatterSample s = bsdf.sample(sampler);
    CHECK(s.delta);
    CHECK_FALSE(bsdf.has_density());
    CHECK(glm::length(s.direction - Vec3(incoming.x, incoming.y, -incoming.z)) < 1e-6f);
    CHECK(s.weight() == Color(1.0f));
  }
  const Material gold = metal("gold", 0.0f);
  const TopHit hit(gold, incoming);
  const Bsdf bsdf = hit.bsdf(incoming);
  auto sampler = sampler_for(4u);
  const ScatterSample s = bsdf.sample(sampler);
  CHECK(s.delta);
  const Color expected =
      glint::conductor_reflectance(float(std::cos(0.6)), gold.metal_eta, gold.metal_k);
  CHECK(s.weight().x == Approx(expected.x).epsilon(1e-5));
  CHECK(s.weight().z == Approx(expected.z).epsilon(1e-5));
}

}  // namespace microfacet_test
