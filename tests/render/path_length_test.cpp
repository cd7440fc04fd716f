// max_depth means one thing for every light and every estimator (docs/scene-format.md): light
// reaches the camera after at most max_depth + 1 scattering vertices. Inside a closed diffuse
// sphere of albedo rho every wall point is alike, so each vertex of a path adds one power of rho
// and the radiance after at most n = max_depth + 1 vertices is a geometric series:
//   a point light of intensity I at the centre of a sphere of radius R, first seen after one
//   vertex:       L = rho I / (pi R^2) (1 + rho + ... + rho^(n-1)),
//   an emissive wall of radiance Le, seen after none:
//                 L = Le (1 + rho + ... + rho^n).
// Both are held, for every compiled variant (every estimator, each with its default execution),
// at max_depth 0 (direct light only), 1 and 5 (where Russian roulette plays).

#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>

#include "block_statistics.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"

namespace path_length_test {

constexpr double kRho = 0.5, kIntensity = 400.0, kRadius = 10.0, kEmission = 2.0;

glint::Scene build(const std::string& text, const std::string& name) {
  return glint::Scene::build(glint::read_scene_text(text, name));
}

/// 1 + rho + ... + rho^(terms - 1).
double geometric(int terms) {
  return (1.0 - std::pow(kRho, terms)) / (1.0 - kRho);
}

TEST_CASE(
    "max_depth: every estimator shows a point light and an emissive wall after at most "
    "max_depth + 1 scattering vertices",
    "[render][light][statistical]") {
  const glint::Scene lit = build(R"(
camera    position=0,0,3 look_at=0,0,-10 up=0,1,0 fov=90
antialias sigma=0.5
light     position=0,0,0 intensity=400
sphere    center=0,0,0 radius=10 color=1,1,1 diffuse=0.5
)",
                                 "lit sphere");
  const glint::Scene glowing = build(R"(
camera    position=0,0,3 look_at=0,0,-10 up=0,1,0 fov=90
antialias sigma=0.5
sphere    center=0,0,0 radius=10 color=1,1,1 diffuse=0.5 emission=2,2,2
)",
                                     "glowing sphere");
  glint_test::ComparisonFamily family;
  int variants = 0;
  glint_test::for_each_compiled_variant([&]<typename V>() {
    ++variants;
    for (const int depth : {0, 1, 5}) {
      const int vertices = depth + 1;
      // Three channels, each the same radiance.
      const double expected_lit =
          3.0 * kRho * kIntensity / (M_PI * kRadius * kRadius) * geometric(vertices);
      const double expected_glowing = 3.0 * kEmission * geometric(vertices + 1);
      for (const auto& [scene, expected] :
           {std::pair<const glint::Scene*, double>{&lit, expected_lit},
            {&glowing, expected_glowing}}) {
        REQUIRE(glint::is_supported<V>(*scene));
        glint::RenderSettings settings = glint::RenderSettings::from(*scene);
        settings.samples_per_pixel = 4;
        settings.max_depth = depth;
        const glint_test::BlockSamples blocks = glint_test::render_blocks<glint::Renderer<V>>(
            *scene, 700 + std::uint64_t(depth), settings);
        for (std::size_t b = 0; b <= glint_test::kBlocks; ++b) {
          std::vector<double> error;
          for (const double v : blocks.per_seed[b])
            error.push_back(v - expected);
          const glint_test::MeanEstimate e = glint_test::estimate_mean(error);
          std::ostringstream line;
          line << V::info.name << ", " << scene->source() << ", max depth " << depth << ", "
               << glint_test::block_name(b) << ": expected " << expected << ", off by " << e.mean
               << " +- " << e.standard_error;
          family.add(line.str(),
                     glint_test::zero_mean_p_value(e, glint_test::kRelativeRounding * expected));
        }
      }
    }
  });
  CHECK(variants > 0);
  family.check();
}

}  // namespace path_length_test
