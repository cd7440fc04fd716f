// path_tracing_blind_spot: a scene is given to light paths exactly when a point light that emits
// and a sphere that reflects or transmits specularly are both in it, and the lines it names are
// those of the file.

#include "glint/render/path_tracing_blind_spot.hpp"

#include <catch2/catch.hpp>
#include <optional>
#include <string>

#include "glint/io/scene_reader.hpp"

namespace {

std::optional<glint::PathTracingBlindSpot> blind_spot(const std::string& text) {
  return glint::path_tracing_blind_spot(glint::Scene::build(glint::read_scene_text(text)));
}

}  // namespace

TEST_CASE("a point light and glass: the path tracer is blind to the caustic", "[blind_spot]") {
  const auto spot = blind_spot(
      "camera position=0,0,30 look_at=0,0,0\n"
      "sphere center=0,-1000,0 radius=990 color=0.8,0.8,0.8\n"
      "light position=0,20,0 intensity=100\n"
      "sphere center=5,0,0 radius=2 color=0.5,0.5,0.5\n"
      "sphere center=0,0,0 radius=3 transparent=1 ior=1.5\n");
  REQUIRE(spot);
  CHECK(spot->light_line == 3);
  CHECK(spot->sphere_line == 5);
}

TEST_CASE("a point light and a partial mirror: blind to what the mirror sends", "[blind_spot]") {
  const auto spot = blind_spot(
      "light position=0,20,0 intensity=100 color=0,0,1\n"
      "sphere center=0,0,0 radius=3 diffuse=0.9 mirror=0.1\n");
  REQUIRE(spot);
  CHECK(spot->light_line == 1);
  CHECK(spot->sphere_line == 2);
}

TEST_CASE("what the path tracer sees all of", "[blind_spot]") {
  // Only diffuse spheres under a point light: every light path ends in a shadow ray it takes.
  CHECK_FALSE(
      blind_spot("light position=0,20,0 intensity=100\n"
                 "sphere center=0,0,0 radius=3 color=0.5,0.5,0.5\n"));
  // Glass under an emissive sphere: a bounce can hit the lamp through the glass.
  CHECK_FALSE(
      blind_spot("sphere center=0,20,0 radius=1 emission=10,10,10\n"
                 "sphere center=0,0,0 radius=3 transparent=1\n"
                 "sphere center=0,-1000,0 radius=990 color=0.8,0.8,0.8\n"));
  // A point light that emits nothing (zero intensity, or black) lights no caustic.
  CHECK_FALSE(
      blind_spot("light position=0,20,0 intensity=0\n"
                 "sphere center=0,0,0 radius=3 mirror=1 diffuse=0\n"));
  CHECK_FALSE(
      blind_spot("light position=0,20,0 intensity=5 color=0,0,0\n"
                 "sphere center=0,0,0 radius=3 mirror=1 diffuse=0\n"));
  // A rough mirror has a density: light is sampled towards it as to a diffuse surface.
  CHECK_FALSE(
      blind_spot("light position=0,20,0 intensity=100\n"
                 "sphere center=0,0,0 radius=3 metal=gold mirror_roughness=0.2\n"
                 "sphere center=0,-1000,0 radius=990 color=0.8,0.8,0.8\n"));
  // Rough glass too, from both sides: light is sampled through it from inside the ball.
  CHECK_FALSE(
      blind_spot("light position=0,20,0 intensity=100\n"
                 "sphere center=0,0,0 radius=3 transparent=1 transparent_roughness=0.3\n"
                 "sphere center=0,-1000,0 radius=990 color=0.8,0.8,0.8\n"));
}

TEST_CASE("a point light and glass too smooth to be rough, or between equal indices: blind",
          "[blind_spot]") {
  for (const char* glass : {"transparent_roughness=0.03", "transparent_roughness=0.5 ior=1"}) {
    INFO(glass);
    const auto spot = blind_spot(std::string("light position=0,20,0 intensity=100\n"
                                             "sphere center=0,0,0 radius=3 transparent=1 ") +
                                 glass + "\n");
    REQUIRE(spot);
    CHECK(spot->sphere_line == 2);
  }
}

TEST_CASE("a point light and a mirror too smooth to be a microfacet lobe: blind", "[blind_spot]") {
  for (const char* roughness : {"0", "0.03"}) {
    INFO("mirror_roughness " << roughness);
    const auto spot = blind_spot(std::string("light position=0,20,0 intensity=100\n"
                                             "sphere center=0,0,0 radius=3 metal=silver "
                                             "mirror_roughness=") +
                                 roughness + "\n");
    REQUIRE(spot);
    CHECK(spot->sphere_line == 2);
  }
}

TEST_CASE("the first light that emits is named, not the first light", "[blind_spot]") {
  const auto spot = blind_spot(
      "light position=0,20,0 intensity=0\n"
      "light position=0,30,0 intensity=10\n"
      "sphere center=0,0,0 radius=3 mirror=1 diffuse=0\n");
  REQUIRE(spot);
  CHECK(spot->light_line == 2);
  CHECK(spot->sphere_line == 3);
}
