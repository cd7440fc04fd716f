// The report's material as a Bsdf (render/materials/report_material.hpp): its samples against
// values worked out by hand (Lambertian weights and densities, the mirror direction, Snell's law,
// normal-incidence Fresnel reflectance), the agreement of sample pdfs with pdf(direction), the
// lobe choice of the one-lobe-per-bounce sampling, and the distribution of its samples against
// its pdf by a chi-square test over the sphere of directions (with the delta lobes' mass as one
// more cell).

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "direction_cells.hpp"
#include "glint/config.hpp"
#include "glint/render/materials/report_material.hpp"
#include "statistics.hpp"
#include "top_of_sphere.hpp"

using glint::Color;
using glint::Lobe;
using glint::Material;
using glint::ScatterSample;
using glint::Vec3;

using glint::test::cell_masses;
using glint::test::cell_of;
using glint::test::kCells;

namespace {

template <typename DiffuseSampling, typename Fresnel = glint::NoFresnel>
using TestConfig =
    glint::Config<glint::IndependentSampler, glint::TreePathTracing, Fresnel, glint::NoAntialiasing,
                  glint::UniformShading, DiffuseSampling, glint::FixedDepth>;

constexpr double kPi = M_PI;

using glint::test::TopOfSphere;

glint::IndependentSampler seeded_sampler(std::uint32_t index) {
  glint::IndependentSampler sampler;
  sampler.start({1u, 2u, index, 1u, 7u});
  return sampler;
}

Material diffuse_material(float diffuse, Color color) {
  Material m;
  m.diffuse = diffuse;
  m.diffuse_color = color;
  return m;
}

/// Chi-square of `n` directions drawn by `draw(sampler)` (a ScatterSample) against density `pdf`:
/// the directions sampled with a density counted by cell, the delta samples in one more cell
/// whose expected mass is what the density leaves of one.
template <typename Draw, typename Density>
glint::test::ChiSquare sampling_against(Draw&& draw, Density&& pdf, int n, std::uint32_t seed) {
  auto sampler = seeded_sampler(seed);
  return glint::test::sampling_against_density([&] { return draw(sampler); }, pdf, n);
}

}  // namespace

TEST_CASE("Cosine-sampled diffuse lobe: weight = albedo, pdf = cos/pi", "[scattering]") {
  const Color color(0.8f, 0.5f, 0.2f);
  const TopOfSphere hit(diffuse_material(0.9f, color), glm::normalize(Vec3(0.3f, 0.1f, -1.0f)));
  const glint::ReportMaterial<TestConfig<glint::CosineHemisphere>> material(hit.interaction,
                                                                            hit.ray.direction);
  const Color albedo = 0.9f * color;
  CHECK(material.albedo().x == Approx(albedo.x));
  auto sampler = seeded_sampler(0);
  for (int i = 0; i < 1000; ++i) {
    for (const bool one_lobe : {false, true}) {
      const ScatterSample s =
          one_lobe ? material.sample(sampler) : material.sample_lobe(Lobe::diffuse, sampler);
      const double cosine = s.direction.z;  // the normal is +z
      REQUIRE(cosine >= 0.0);
      CHECK_FALSE(s.delta);
      CHECK(s.lobe == Lobe::diffuse);
      CHECK(glm::length(s.direction) == Approx(1.0f).margin(1e-5));
      for (int c = 0; c < 3; ++c)
        CHECK(s.weight()[c] == Approx(albedo[c]).epsilon(1e-5));
      CHECK(s.pdf == Approx(cosine / kPi).margin(1e-6));
      // The sample's density is what pdf(direction) says, for either way of sampling.
      const float expected_pdf =
          one_lobe ? material.pdf(s.direction) : material.lobe_pdf(Lobe::diffuse, s.direction);
      CHECK(s.pdf == Approx(expected_pdf).margin(1e-6));
      // f·cos / pdf = weight.
      const Color f_cos = material.evaluate(s.direction);
      for (int c = 0; c < 3; ++c)
        CHECK(f_cos[c] == Approx(albedo[c] * cosine / kPi).margin(1e-6));
    }
  }
}

TEST_CASE("Uniformly sampled diffuse lobe: weight = 2 cos albedo, pdf = 1/(2 pi)", "[scattering]") {
  const TopOfSphere hit(diffuse_material(0.5f, Color(1.0f)), Vec3(0.0f, 0.0f, -1.0f));
  const glint::ReportMaterial<TestConfig<glint::UniformHemisphere>> material(hit.interaction,
                                                                             hit.ray.direction);
  auto sampler = seeded_sampler(1);
  for (int i = 0; i < 1000; ++i) {
    const ScatterSample s = material.sample_lobe(Lobe::diffuse, sampler);
    const double cosine = s.direction.z;
    CHECK(s.weight().x == Approx(0.5 * 2.0 * cosine).margin(1e-5));
    CHECK(s.pdf == Approx(1.0 / (2.0 * kPi)));
    CHECK(s.pdf == Approx(material.lobe_pdf(Lobe::diffuse, s.direction)));
  }
}

TEST_CASE("No value and no density below the surface or for delta lobes", "[scattering]") {
  const TopOfSphere hit(diffuse_material(1.0f, Color(1.0f)), Vec3(0.0f, 0.0f, -1.0f));
  const glint::ReportMaterial<TestConfig<glint::CosineHemisphere>> material(hit.interaction,
                                                                            hit.ray.direction);
  const Vec3 below = glm::normalize(Vec3(0.2f, 0.0f, -1.0f));
  CHECK(material.evaluate(below) == Color(0.0f));
  CHECK(material.pdf(below) == 0.0f);
  const Vec3 above = glm::normalize(Vec3(0.2f, 0.0f, 1.0f));
  CHECK(material.lobe_pdf(Lobe::mirror, above) == 0.0f);
  CHECK(material.lobe_pdf(Lobe::transmission, above) == 0.0f);
}

TEST_CASE("Mirror lobe: the reflected direction, flagged delta", "[scattering]") {
  Material m = diffuse_material(0.5f, Color(1.0f));
  m.mirror = 0.3f;
  m.mirror_color = Color(0.9f, 0.8f, 0.7f);
  m.transparent = 0.2f;
  const Vec3 incoming = glm::normalize(Vec3(1.0f, 0.0f, -1.0f));
  const TopOfSphere hit(m, incoming);
  const glint::ReportMaterial<TestConfig<glint::CosineHemisphere>> material(hit.interaction,
                                                                            hit.ray.direction);
  auto sampler = seeded_sampler(2);
  const ScatterSample s = material.sample_lobe(Lobe::mirror, sampler);
  CHECK(s.delta);
  CHECK(s.lobe == Lobe::mirror);
  CHECK(s.direction.x == Approx(incoming.x));
  CHECK(s.direction.y == Approx(0.0f).margin(1e-6));
  CHECK(s.direction.z == Approx(-incoming.z));
  CHECK(s.pdf == 1.0f);
  // Alone, the lobe weighs its coefficient times its colour.
  CHECK(s.weight().x == Approx(0.3f * 0.9f));
  CHECK(s.weight().z == Approx(0.3f * 0.7f));
}

TEST_CASE("One lobe per bounce: chosen by coefficient, weighted by total / probability",
          "[scattering]") {
  Material m = diffuse_material(0.5f, Color(1.0f));
  m.mirror = 0.3f;
  m.mirror_color = Color(0.9f, 0.8f, 0.7f);
  m.transparent = 0.15f;
  m.transparent_color = Color(0.6f);
  const TopOfSphere hit(m, glm::normalize(Vec3(0.5f, 0.0f, -1.0f)));
  const glint::ReportMaterial<TestConfig<glint::CosineHemisphere>> material(hit.interaction,
                                                                            hit.ray.direction);
  const float total = 0.95f;
  CHECK(material.lobe_probability(Lobe::diffuse) + material.lobe_probability(Lobe::mirror) +
            material.lobe_probability(Lobe::transmission) ==
        Approx(1.0f));
  CHECK(material.lobe_probability(Lobe::mirror) == Approx(0.3f / total));

  const int n = 20000;
  int counts[3] = {0, 0, 0};
  auto sampler = seeded_sampler(3);
  for (int i = 0; i < n; ++i) {
    const ScatterSample s = material.sample(sampler);
    ++counts[static_cast<int>(s.lobe)];
    CHECK(s.delta == (s.lobe != Lobe::diffuse));
    CHECK(s.pdf > 0.0f);
    if (s.lobe == Lobe::mirror) {
      CHECK(s.weight().x == Approx(total * 0.9f));
      CHECK(s.pdf == Approx(0.3f / total));
    } else if (s.lobe == Lobe::transmission) {
      CHECK(s.weight().x == Approx(total * 0.6f));
      CHECK(s.pdf == Approx(0.15f / total));  // not fully transparent: no Fresnel choice
    } else {
      // The diffuse weight is albedo / probability = diffuse * colour * total / diffuse.
      CHECK(s.weight().x == Approx(total).epsilon(1e-5));
      CHECK(s.pdf == Approx(material.pdf(s.direction)).margin(1e-6));
    }
  }
  // Each lobe's frequency within 5 standard deviations of its probability.
  for (const Lobe lobe : {Lobe::diffuse, Lobe::mirror, Lobe::transmission}) {
    const double p = material.lobe_probability(lobe);
    const double sigma = std::sqrt(p * (1.0 - p) / n);
    CHECK(std::fabs(counts[static_cast<int>(lobe)] / double(n) - p) < 5.0 * sigma);
  }
}

TEST_CASE("Transmission lobe: Snell's law, and Fresnel reflection with probability F",
          "[scattering]") {
  Material glass;
  glass.diffuse = 0.0f;
  glass.transparent = 1.0f;
  glass.ior = 1.5f;
  SECTION("refraction at 45 degrees, no Fresnel") {
    const Vec3 incoming = glm::normalize(Vec3(1.0f, 0.0f, -1.0f));
    const TopOfSphere hit(glass, incoming);
    const glint::ReportMaterial<TestConfig<glint::CosineHemisphere>> material(hit.interaction,
                                                                              hit.ray.direction);
    auto sampler = seeded_sampler(4);
    const ScatterSample s = material.sample_lobe(Lobe::transmission, sampler);
    CHECK(s.delta);
    CHECK(s.pdf == 1.0f);
    const double sin_transmitted = std::sin(kPi / 4.0) / 1.5;
    CHECK(s.direction.x == Approx(sin_transmitted));
    CHECK(s.direction.z == Approx(-std::sqrt(1.0 - sin_transmitted * sin_transmitted)));
    CHECK(s.weight().x == Approx(1.0f));
  }
  SECTION("normal incidence, exact Fresnel: reflected with F = ((n-1)/(n+1))^2") {
    const Vec3 incoming(0.0f, 0.0f, -1.0f);
    const TopOfSphere hit(glass, incoming);
    const glint::ReportMaterial<TestConfig<glint::CosineHemisphere, glint::ExactFresnel>> material(
        hit.interaction, hit.ray.direction);
    const double f = (0.5 / 2.5) * (0.5 / 2.5);
    const int n = 20000;
    int reflected = 0;
    auto sampler = seeded_sampler(5);
    for (int i = 0; i < n; ++i) {
      const ScatterSample s = material.sample_lobe(Lobe::transmission, sampler);
      CHECK(s.delta);
      CHECK(s.weight().x == 1.0f);  // F / F or (1 - F) / (1 - F)
      if (s.direction.z > 0.0f) {
        ++reflected;
        CHECK(s.pdf == Approx(f));
      } else {
        CHECK(s.direction.z == Approx(-1.0f));
        CHECK(s.pdf == Approx(1.0 - f));
      }
    }
    const double sigma = std::sqrt(f * (1.0 - f) / n);
    CHECK(std::fabs(reflected / double(n) - f) < 5.0 * sigma);
  }
  SECTION("total internal reflection from inside") {
    // Leaving glass at 60 degrees: sin 60 * 1.5 > 1.
    const Vec3 incoming = glm::normalize(Vec3(std::sqrt(3.0f), 0.0f, 1.0f));
    const TopOfSphere hit(glass, incoming);
    REQUIRE(hit.interaction.at.from_inside);
    const glint::ReportMaterial<TestConfig<glint::CosineHemisphere>> material(hit.interaction,
                                                                              hit.ray.direction);
    auto sampler = seeded_sampler(6);
    const ScatterSample s = material.sample_lobe(Lobe::transmission, sampler);
    CHECK(s.delta);
    CHECK(s.pdf == 1.0f);
    CHECK(s.direction.x == Approx(incoming.x));
    CHECK(s.direction.z == Approx(-incoming.z));
  }
}

TEST_CASE("The Bsdf's samples are distributed as its pdf says, in both transport modes",
          "[scattering][statistical]") {
  // Each case: a material and the direction a path arrives along; the outward normal is +z.
  Material mixed = diffuse_material(0.4f, Color(0.8f, 0.6f, 0.4f));
  mixed.mirror = 0.3f;
  mixed.transparent = 0.3f;
  mixed.ior = 1.5f;
  Material frosted = diffuse_material(0.5f, Color(0.9f));
  frosted.transparent = 0.5f;
  frosted.ior = 1.33f;
  struct Case {
    const char* name;
    Material material;
    Vec3 incoming;
  };
  const Case cases[] = {
      {"diffuse, oblique", diffuse_material(0.9f, Color(0.8f, 0.5f, 0.2f)),
       glm::normalize(Vec3(0.6f, 0.2f, -1.0f))},
      {"diffuse, mirror and glass mixed, 45 degrees", mixed,
       glm::normalize(Vec3(1.0f, 0.0f, -1.0f))},
      {"diffuse and glass, from inside", frosted, glm::normalize(Vec3(0.3f, -0.4f, 1.0f))},
  };
  const int n = 100000;
  std::uint32_t seed = 100;
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const TopOfSphere hit(c.material, c.incoming);
    auto check = [&](const auto& bsdf) {
      auto pdf = [&](const Vec3& direction) { return bsdf.pdf(direction); };
      const auto radiance = sampling_against(
          [&](auto& sampler) { return bsdf.template sample<glint::Transport::radiance>(sampler); },
          pdf, n, seed++);
      CAPTURE(radiance.statistic, radiance.degrees_of_freedom);
      CHECK_FALSE(radiance.rejected());
      const auto importance = sampling_against(
          [&](auto& sampler) {
            return bsdf.template sample<glint::Transport::importance>(sampler);
          },
          pdf, n, seed++);
      CAPTURE(importance.statistic, importance.degrees_of_freedom);
      CHECK_FALSE(importance.rejected());
      // Each sample with a density has the pdf and the weight f |cos| / pdf that evaluate and
      // pdf give for its direction.
      auto sampler = seeded_sampler(seed++);
      for (int i = 0; i < 2000; ++i) {
        const ScatterSample s = bsdf.template sample<glint::Transport::radiance>(sampler);
        if (s.delta) continue;
        const float pdf_there = bsdf.pdf(s.direction);
        REQUIRE(pdf_there > 0.0f);
        CHECK(s.pdf == Approx(pdf_there).epsilon(1e-5));
        const Color expected = bsdf.evaluate(s.direction) / pdf_there;
        for (int k = 0; k < 3; ++k)
          CHECK(s.weight()[k] == Approx(expected[k]).epsilon(1e-4));
      }
    };
    check(glint::ReportMaterial<TestConfig<glint::CosineHemisphere, glint::ExactFresnel>>(
        hit.interaction, hit.ray.direction));
    check(glint::ReportMaterial<TestConfig<glint::UniformHemisphere, glint::SchlickFresnel>>(
        hit.interaction, hit.ray.direction));
  }
}

TEST_CASE("The sampling test catches a density 5% off in shape", "[scattering][statistical]") {
  // Cosine-distributed samples against a density that moves 5% of the mass from the cosine lobe
  // to the uniform hemisphere: the test must reject it, or it could not see a wrong pdf.
  const TopOfSphere hit(diffuse_material(1.0f, Color(1.0f)), Vec3(0.0f, 0.0f, -1.0f));
  const glint::ReportMaterial<TestConfig<glint::CosineHemisphere>> bsdf(hit.interaction,
                                                                        hit.ray.direction);
  auto draw = [&](auto& sampler) {
    return bsdf.template sample<glint::Transport::radiance>(sampler);
  };
  const int n = 400000;
  const auto right = sampling_against(
      draw, [&](const Vec3& d) { return bsdf.pdf(d); }, n, 7);
  CAPTURE(right.statistic, right.degrees_of_freedom);
  CHECK_FALSE(right.rejected());
  const auto wrong = sampling_against(
      draw,
      [&](const Vec3& d) {
        return d.z > 0.0f ? 0.95f * bsdf.pdf(d) + 0.05f / (2.0f * float(kPi)) : 0.0f;
      },
      n, 7);
  CAPTURE(wrong.statistic, wrong.degrees_of_freedom);
  CHECK(wrong.rejected());
}
