// Bidirectional path tracing (render/estimators/bidirectional.hpp,
// render/bidirectional_execution.hpp): its weights against an explicit sum over all strategies; the
// same bits whatever the threads, tiles and passes, and after a resume; the same image as the path
// tracer wherever the path tracer sees all the light (lamps, glass and mirrors seen by the camera,
// a background, pixel centres), and as light tracing where it does (a point light's caustics
// through glass and off mirrors); and a point light's caustic under a glass ball, which the path
// tracer misses, against the fan of rays of tests/render/caustic_reference.hpp.

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "block_statistics.hpp"
#include "caustic_reference.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/bidirectional_execution.hpp"
#include "glint/render/light_tracing_execution.hpp"
#include "glint/render/renderer.hpp"
#include "lens_scene.hpp"
#include "renderer_types.hpp"
#include "same_bits.hpp"

using glint::Color;

namespace bidirectional_test {

// The report's material, one lobe per vertex, fixed depth: the bidirectional estimator follows
// the Config's policies, and the path tracer compared with it is the same Config's chain.
using Chain = glint::variants::report::with_estimator<glint::PathTracing>;
template <typename C>
using Bidirectional = glint::Renderer<C, glint::BidirectionalExecution<C>>;
/// The path tracer the estimator is compared with: Chain's image, with less noise per sample.
template <typename C>
using PathReference = typename C::template with_diffuse_sampling<glint::CosineHemisphere>::
    template with_light_sampling<glint::EmitterSampling<glint::PowerHeuristic>>;
using PixelCentres = Chain::with_antialiasing<glint::NoAntialiasing>;
using PathVertex = glint::PathVertexOf<Chain>;

glint::Scene build(const std::string& text, const char* label) {
  return glint::Scene::build(glint::read_scene_text(text, label));
}

// ---- the weights against an explicit sum -----------------------------------------------------

/// A full path x_0 (on a light) ... x_k (the camera) as densities only: light[i] is the density
/// with which the light side makes x_i, camera[i] the camera side's; delta[i] says x_i scatters
/// through a mirror or refraction.
struct DensityPath {
  std::vector<float> light, camera;
  std::vector<bool> delta;
  bool point_light = false;
};

/// Strategy s's density written out: the product of the light side's densities of x_0 .. x_{s-1}
/// and the camera side's of x_s .. x_k, a density made through a delta read as one (each valid
/// strategy holds every delta once, and they cancel); zero for a strategy that cannot make the
/// path (a join at a delta vertex, the camera path hitting a point light, a join to the camera
/// where light tracing does not count).
double strategy_density(const DensityPath& p, std::size_t s, bool light_tracing_counts) {
  const std::size_t k = p.light.size() - 1;
  if (s == 0 && p.point_light) return 0.0;
  if (s >= 1 && s <= k) {
    if (p.delta[s - 1] || p.delta[s]) return 0.0;
    if (s == k && !light_tracing_counts) return 0.0;
  }
  if (s > k) return 0.0;  // no camera vertex: the pinhole cannot be hit
  double density = 1.0;
  for (std::size_t i = 0; i < s; ++i)
    density *= i > 0 && p.delta[i - 1] ? 1.0 : double(p.light[i]);
  for (std::size_t i = s; i <= k; ++i)
    density *= i < k && p.delta[i + 1] ? 1.0 : double(p.camera[i]);
  return density;
}

/// Merging at x_j's density written out: the light side's densities of x_0 .. x_j, the camera
/// side's of x_j .. x_k, and eta; zero where x_j scatters through a delta (no diffuse lobe meets
/// the light there) or is an end of the path.
double merge_density(const DensityPath& p, std::size_t j, double eta) {
  const std::size_t k = p.light.size() - 1;
  if (j == 0 || j >= k || p.delta[j] || eta == 0.0) return 0.0;
  double density = eta;
  for (std::size_t i = 0; i <= j; ++i)
    density *= i > 0 && p.delta[i - 1] ? 1.0 : double(p.light[i]);
  for (std::size_t i = j; i <= k; ++i)
    density *= i < k && p.delta[i + 1] ? 1.0 : double(p.camera[i]);
  return density;
}

/// Strategy s's subpaths as the estimator holds them at its join: the light subpath x_0 ..
/// x_{s-1} and the camera subpath x_k .. x_s, each vertex's forward density its own side's
/// (zero behind a delta), its reverse density the other side's, the joined vertices' deltas
/// cleared.
void subpaths(const DensityPath& p, std::size_t s, std::vector<PathVertex>& light,
              std::vector<PathVertex>& camera) {
  const std::size_t k = p.light.size() - 1;
  light.clear();
  camera.clear();
  const auto vertex = [&](std::size_t i, bool light_side) {
    PathVertex v;
    v.kind = i == 0 ? (p.point_light ? PathVertex::Kind::delta_light : PathVertex::Kind::area_light)
             : i == k ? PathVertex::Kind::camera
                      : PathVertex::Kind::surface;
    v.delta = p.delta[i];
    const float made_by_light = i > 0 && p.delta[i - 1] ? 0.0f : p.light[i];
    const float made_by_camera = i < k && p.delta[i + 1] ? 0.0f : p.camera[i];
    v.pdf_forward = light_side ? made_by_light : made_by_camera;
    v.pdf_reverse = light_side ? made_by_camera : made_by_light;
    return v;
  };
  for (std::size_t i = 0; i < s; ++i)
    light.push_back(vertex(i, true));
  for (std::size_t i = k + 1; i-- > s;)
    camera.push_back(vertex(i, false));
  if (!light.empty()) light.back().delta = false;
  camera.back().delta = false;
}

TEST_CASE(
    "bidirectional: each strategy's weight, merges included, is its share of an explicit "
    "sum over all",
    "[render][light]") {
  std::mt19937 random(12345);
  std::uniform_real_distribution<float> log_density(-2.0f, 2.0f);
  std::bernoulli_distribution is_delta(0.25), is_point(0.3);
  int checked = 0, merges_checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // Half the paths without merging (bidirectional path tracing), half with.
    const float eta = trial % 2 ? 0.0f : std::exp(2.0f * log_density(random));
    const std::size_t k = 1 + std::size_t(trial % 8);
    DensityPath p;
    p.point_light = is_point(random);
    for (std::size_t i = 0; i <= k; ++i) {
      p.light.push_back(std::exp(log_density(random)));
      p.camera.push_back(std::exp(log_density(random)));
      // The endpoints do not scatter.
      p.delta.push_back(i > 0 && i < k && is_delta(random));
    }
    for (const bool light_tracing_counts : {true, false}) {
      double total = 0.0;
      for (std::size_t s = 0; s <= k + 1; ++s) {
        const double d = strategy_density(p, s, light_tracing_counts);
        total += d * d;
      }
      for (std::size_t j = 0; j <= k; ++j) {
        const double d = merge_density(p, j, eta);
        total += d * d;
      }
      if (total == 0.0) continue;  // no strategy makes the path
      double weights = 0.0;
      std::vector<PathVertex> light, camera;
      for (std::size_t s = 0; s <= k; ++s) {
        const double d = strategy_density(p, s, light_tracing_counts);
        if (d == 0.0) continue;
        subpaths(p, s, light, camera);
        const double weight =
            glint::bidirectional_weight<PathVertex>(light, camera, {light_tracing_counts, eta});
        INFO("path of " << k + 1 << " vertices, strategy s = " << s << ", light tracing "
                        << light_tracing_counts);
        CHECK(weight == Approx(d * d / total).epsilon(1e-4));
        weights += weight;
        ++checked;
      }
      // Merging at x_j: the light subpath up to x_{j-1}, which keeps its own delta (its next
      // vertex, the merged one, is on the path), the camera subpath down to x_j, whose reverse
      // density is the light side's.
      for (std::size_t j = 1; j < k; ++j) {
        const double d = merge_density(p, j, eta);
        if (d == 0.0) continue;
        subpaths(p, j, light, camera);
        light.back().delta = p.delta[j - 1];
        const double weight =
            glint::merge_weight<PathVertex>(light, camera, {light_tracing_counts, eta});
        INFO("path of " << k + 1 << " vertices, merge at " << j << ", light tracing "
                        << light_tracing_counts);
        CHECK(weight == Approx(d * d / total).epsilon(1e-4));
        // The same weight from the vertices next to the merge and the strategy tails, as merging
        // computes it.
        const glint::StrategyRules rules{light_tracing_counts, eta};
        glint::detail::strategy_tails<PathVertex>(light, true, rules);
        glint::detail::strategy_tails<PathVertex>(camera, false, rules);
        const double from_factors = glint::detail::merge_weight_from_factors(
            glint::detail::held_densities<PathVertex>(light, camera),
            glint::detail::merge_camera_factors<PathVertex>(camera, rules),
            glint::detail::merge_light_factor<PathVertex>(light, rules), light.back().delta, rules);
        CHECK(from_factors == Approx(d * d / total).epsilon(1e-4));
        weights += weight;
        ++merges_checked;
      }
      CHECK(weights == Approx(1.0).epsilon(1e-4));
    }
  }
  CHECK(checked > 10000);
  CHECK(merges_checked > 3000);
}

// ---- whole renders -------------------------------------------------------------------------

TEST_CASE("bidirectional: the same bits for any threads, tiles and passes, and after a resume",
          "[render][light]") {
  const glint::Scene scene = build(glint_test::kMixedRoomWithBackground, "mixed");
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.seed = 7;
  (void)glint_test::check_same_bits<Bidirectional<Chain>>(scene, settings);
}

// A closed room lit by a lamp the camera does not see and a small one it sees, with a glass
// ball, a mirror ball and a ball both diffuse and mirror: the camera sees lamps, diffuse
// surfaces and both deltas, and every light is a sphere, so the path tracer sees all the light.
constexpr const char* kLampRoom = R"(
image     width=16 height=16 spp=32 max_depth=5
camera    position=0,0,30 look_at=0,-4,0 up=0,1,0 fov=50
antialias sigma=0.5
sphere    center=-100016,0,0 radius=1e5 color=0.8,0.3,0.3
sphere    center=100016,0,0 radius=1e5 color=0.3,0.3,0.8
sphere    center=0,-100010,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,100016,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,-100016 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,100040 radius=1e5 color=0.5,0.5,0.5
sphere    center=0,13,-6 radius=2.5 diffuse=0 emission=20,18,14
sphere    center=7,-7,-4 radius=1 diffuse=0 emission=10,10,20
sphere    center=-5,-6,-2 radius=4 diffuse=0 transparent=1 ior=1.5
sphere    center=4,-7,4 radius=3 diffuse=0 mirror=1 color=0.9,0.9,0.9
sphere    center=6,2,-8 radius=3 diffuse=0.5 mirror=0.4 color=0.9,0.8,0.3 shading=checker
)";

// An open scene under a sky: the background lights it and is seen, directly and through glass.
constexpr const char* kSky = R"(
image      width=16 height=16 spp=32 max_depth=4
camera     position=0,4,20 look_at=0,0,0 up=0,1,0 fov=50
antialias  sigma=0.5
background color=0.4,0.5,0.7
sphere     center=0,-100003,0 radius=1e5 color=0.6,0.6,0.6
sphere     center=-3,0,0 radius=3 diffuse=0 transparent=1 ior=1.4
sphere     center=4,-1,-2 radius=2 color=0.8,0.4,0.2
sphere     center=2,6,-3 radius=1 diffuse=0 emission=8,8,8
)";

TEST_CASE("bidirectional: agrees with the path tracer wherever the path tracer sees all the light",
          "[render][light][statistical]") {
  glint_test::ComparisonFamily family;
  const auto compare = [&]<typename C>(const char* text, const char* name) {
    const glint::Scene scene = build(text, name);
    const glint::RenderSettings settings = glint::RenderSettings::from(scene);
    const double lit = glint_test::compare_independent(
        family, std::string(name) + ", bidirectional against path tracing",
        glint_test::render_blocks<glint::Renderer<PathReference<C>>>(scene, 100, settings),
        glint_test::render_blocks<Bidirectional<C>>(scene, 200, settings));
    CHECK(lit > 0.01);
  };
  compare.operator()<Chain>(kLampRoom, "lamp room");
  const std::string lamp_room_through_lens =
      glint_test::through_lens(kLampRoom, "aperture=6 focus=18");
  compare.operator()<Chain>(lamp_room_through_lens.c_str(), "lamp room through a lens");
  // Through pixel centres no join to the camera lands on a pixel: light tracing has no weight,
  // and the other strategies carry all of it.
  compare.operator()<PixelCentres>(kLampRoom, "lamp room through pixel centres");
  compare.operator()<Chain>(kSky, "sky");
  family.check();
}

// A floor and a back wall, which is all the camera sees, lit by a point light and a small lamp
// through and off a glass ball, a mirror ball and a ball both diffuse and mirror, all out of
// view: caustics of a point light through glass and off a mirror, which only light paths find,
// and their light scattered on between the floor and the wall. Light tracing sees all of it.
constexpr const char* kCaustics = R"(
image     width=16 height=16 spp=64 max_depth=4
camera    position=0,2,6 look_at=0,0,-2 up=0,1,0 fov=40
antialias sigma=0.5
light     position=0,9,-1 intensity=150
sphere    center=0,-100000,0 radius=1e5 color=0.6,0.6,0.6
sphere    center=0,0,-100006 radius=1e5 color=0.5,0.6,0.7
sphere    center=0,4,-1 radius=1 diffuse=0 transparent=1 ior=1.5
sphere    center=-3,5,-3 radius=1 diffuse=0 mirror=1
sphere    center=3,5,-3 radius=1 diffuse=0.4 mirror=0.5 color=0.9,0.7,0.3
sphere    center=3,6,-4 radius=0.3 diffuse=0 emission=30,30,30
)";

TEST_CASE("bidirectional: agrees with light tracing where light tracing sees all the light",
          "[render][light][statistical]") {
  const glint::Scene scene = build(kCaustics, "caustics");
  const glint::RenderSettings settings = glint::RenderSettings::from(scene);
  glint_test::ComparisonFamily family;
  const double lit = glint_test::compare_independent(
      family, "caustics, bidirectional against light tracing",
      glint_test::render_blocks<glint::Renderer<Chain, glint::LightTracingExecution<Chain>>>(
          scene, 100, settings),
      glint_test::render_blocks<Bidirectional<Chain>>(scene, 200, settings));
  CHECK(lit > 0.01);
  family.check();
}

TEST_CASE("bidirectional: a point light's caustic under a glass ball matches a fan of rays",
          "[render][light][statistical]") {
  caustic_reference::check_caustic<Bidirectional<Chain>>(400, "bidirectional");
}

}  // namespace bidirectional_test
