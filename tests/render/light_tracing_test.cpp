// Light tracing (render/light_tracing_execution.hpp) in whole renders: the same bits whatever
// the threads, tiles and passes; the same image as the path tracer wherever both see all the
// light (a diffuse room under lamps, also through a thin lens, and a diffuse ball seen from inside
// the glass that holds it, which checks the adjoint scaling at refraction); and a point light's
// caustic under a glass ball against the irradiance a deterministic fan of rays through the ball
// gives, worked out in the test with its own ray-sphere and Fresnel arithmetic.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "block_statistics.hpp"
#include "caustic_reference.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/render/light_tracing_execution.hpp"
#include "glint/render/renderer.hpp"
#include "lens_scene.hpp"
#include "renderer_types.hpp"
#include "same_bits.hpp"

using glint::Color;
using glint::Vec2;

namespace light_tracing_test {

// The report's material, one lobe per vertex, fixed depth: light tracing follows the Config's
// policies, and the path tracer compared with it is the same Config's chain.
using Chain = glint::variants::report::with_estimator<glint::PathTracing>;
template <typename C>
using LightTracing = glint::Renderer<C, glint::LightTracingExecution<C>>;
/// The path tracer the light tracer is compared with: Chain's image, with less noise per sample
/// (cosine bounces, emitter sampling with MIS).
using PathReference = Chain::with_diffuse_sampling<glint::CosineHemisphere>::with_light_sampling<
    glint::EmitterSampling<glint::PowerHeuristic>>;

glint::Scene build(const std::string& text, const char* label) {
  return glint::Scene::build(glint::read_scene_text(text, label));
}

// A closed diffuse room lit by a lamp near the ceiling that the camera does not see and a
// small one it does, with diffuse balls (one patterned): everything the camera sees is diffuse
// or a lamp, so light tracing sees all the light the path tracer does.
constexpr const char* kRoom = R"(
image     width=16 height=16 spp=64 max_depth=3
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
sphere    center=-5,-6,-2 radius=4 color=0.9,0.8,0.3
sphere    center=4,-7,4 radius=3 color=0.5,0.5,0.5 shading=checker
)";

// A diffuse ball seen from inside the glass sphere that holds it and the camera: every pixel
// sees the ball, lit through the glass by a room around it and the lamp near its ceiling.
constexpr const char* kInsideGlass = R"(
image     width=16 height=16 spp=256 max_depth=6
camera    position=0,0,10 look_at=0,0,0 up=0,1,0 fov=36
antialias sigma=0.5
sphere    center=0,0,0 radius=12 diffuse=0 transparent=1 ior=1.5
sphere    center=0,0,0 radius=5 color=0.8,0.8,0.8
sphere    center=0,17,0 radius=2 diffuse=0 emission=50,50,50
sphere    center=-100020,0,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=100020,0,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,-100020,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,100020,0 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,-100020 radius=1e5 color=0.7,0.7,0.7
sphere    center=0,0,100020 radius=1e5 color=0.7,0.7,0.7
)";

TEST_CASE("light tracing: the same bits for any threads, tiles and passes, and after a resume",
          "[render][light]") {
  const glint::Scene scene = build(glint_test::kMixedRoom, "mixed");
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.seed = 7;
  const glint::Film film = glint_test::check_same_bits<LightTracing<Chain>>(scene, settings);
  double total = 0.0;
  for (const Color& c : film.pixels())
    total += c.r + c.g + c.b;
  CHECK(total > 0.0);
}

TEST_CASE("light tracing: agrees with the path tracer where the camera sees diffuse surfaces",
          "[render][light][statistical]") {
  glint_test::ComparisonFamily family;
  const std::string room_through_lens = glint_test::through_lens(kRoom, "aperture=6 focus=18");
  for (const auto& [text, name] : {std::pair{std::string(kRoom), "room"},
                                   {std::string(kInsideGlass), "inside glass"},
                                   {room_through_lens, "room through a lens"}}) {
    const glint::Scene scene = build(text, name);
    const glint::RenderSettings settings = glint::RenderSettings::from(scene);
    // The scenes' samples per pixel are light tracing's.
    glint::RenderSettings path_settings = settings;
    path_settings.samples_per_pixel = 64;
    const double lit = glint_test::compare_independent(
        family, std::string(name) + ", light tracing against path tracing",
        glint_test::render_blocks<glint::Renderer<PathReference>>(scene, 100, path_settings),
        glint_test::render_blocks<LightTracing<Chain>>(scene, 200, settings));
    CHECK(lit > 0.01);
  }
  family.check();
}

TEST_CASE("light tracing: refuses what it cannot render, and checkpoints of its sums",
          "[render][light]") {
  const glint::Scene scene = build(kRoom, "room");
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.antialias_sigma = 0.0f;
  CHECK_THROWS_AS(LightTracing<Chain>::render(scene, settings), glint::SettingsError);
  settings = glint::RenderSettings::from(scene);
  CHECK_THROWS_AS(
      LightTracing<glint::variants::no_antialiasing::with_estimator<glint::PathTracing>>::render(
          scene, settings),
      glint::SettingsError);

  const glint::Scene sky = build(R"(
camera     position=0,0,10 look_at=0,0,0 up=0,1,0 fov=50
background color=0.2,0.3,0.5
light      position=0,5,5 intensity=10
sphere     center=0,0,0 radius=2
)",
                                 "sky");
  CHECK_THROWS_AS(LightTracing<Chain>::render(sky, glint::RenderSettings::from(sky)),
                  glint::UnsupportedSceneError);

  // A start from sums without splats is refused; sums with splats go through a checkpoint and
  // back, and the render resumed from them is the uninterrupted one, bit for bit.
  const glint::PixelSums plain(settings.width, settings.height);
  CHECK_THROWS_AS(LightTracing<Chain>::render(scene, settings, {}, glint::RenderStart{&plain, 1}),
                  glint::SettingsError);
  settings.samples_per_pixel = 8;
  glint::RenderControl stop_early;
  stop_early.keep_sums = true;
  stop_early.pass_done = [](const glint::PassReport& report) { return report.passes_done < 3; };
  const glint::RenderResult first = LightTracing<Chain>::render(scene, settings, stop_early);
  REQUIRE(first.passes_done == 3);
  REQUIRE(first.sums.has_splats());
  const glint::Checkpoint back = glint::decode_checkpoint(
      glint::encode_checkpoint(glint::CheckpointKey::of(1, "light", settings), first.passes_done,
                               first.samples_per_pixel, first.sums),
      "ck");
  REQUIRE(back.sums.has_splats());
  CHECK(back.sums.splats().words() == first.sums.splats().words());
  const glint::RenderResult resumed = LightTracing<Chain>::render(
      scene, settings, {}, glint::RenderStart{&back.sums, back.passes_done});
  const glint::RenderResult whole = LightTracing<Chain>::render(scene, settings);
  REQUIRE(resumed.complete());
  CHECK(resumed.film.pixels() == whole.film.pixels());
}

TEST_CASE("light tracing: a point light's caustic under a glass ball matches a fan of rays",
          "[render][light][statistical]") {
  caustic_reference::check_caustic<LightTracing<Chain>>(300, "light tracing");
}

}  // namespace light_tracing_test
