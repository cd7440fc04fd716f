// The scene file reader: every statement and key read to the right value, the defaults, and
// every class of error reported at the right line with a recognisable message.

#include "glint/io/scene_reader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <thread>

#include "peak_memory.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using glint::Color;
using glint::read_scene_text;
using glint::SceneDescription;
using glint::SceneError;
using glint::ShadingKind;
using glint::Vec3;
using namespace std::string_view_literals;

namespace {

// Parses `text` as "test.scene", which must fail at `line` with `substring` in the message.
void expect_error(std::string_view text, int line, const std::string& substring) {
  INFO("scene text:\n" << text);
  try {
    (void)read_scene_text(text, "test.scene");
    FAIL("expected a SceneError");
  } catch (const SceneError& e) {
    CHECK(e.line() == line);
    CHECK(e.source() == "test.scene");
    const std::string prefix =
        line > 0 ? "test.scene:" + std::to_string(line) + ": error: " : "test.scene: error: ";
    CHECK_THAT(e.what(), StartsWith(prefix));
    CHECK_THAT(e.what(), Contains(substring));
  }
}

const char* const kFullExample = R"(# The example of the format's specification, line for line.
image      width=640 height=480 spp=16 max_depth=7
camera     position=1,2,55 look_at=0,0.5,0 up=0,1,0 fov=45 near=2.5   # fov: vertical, degrees
antialias  sigma=0.75
background color=0.1,0.2,0.3
medium     ior=1.33
light      position=-10,20,40 intensity=4000 color=1,0.5,0.25
material   glass transparent=1 ior=1.5
material   red diffuse=0.8 color=0.9,0.2,0.2 mirror=0.1 mirror_color=0.5,0.6,0.7 transparent=0.1 transparent_color=0.2,0.3,0.4 ior=2.4 emission=3,2,1

sphere     center=0,0,0 radius=10 material=glass
sphere     center=5,-1,2 radius=2 diffuse=0.5 color=1,1,0 mirror=0.5 shading=octants   # inline
sphere     center=0,0,-30 radius=1e5 material=red shading=checker
light      position=0,1,0 intensity=0.5
)";

bool same(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

}  // namespace

TEST_CASE("scene reader: every statement and key of the full example", "[scene_reader]") {
  const SceneDescription d = read_scene_text(kFullExample, "example.scene");
  CHECK(d.source == "example.scene");

  CHECK(d.image.width == 640);
  CHECK(d.image.height == 480);
  CHECK(d.image.samples_per_pixel == 16);
  CHECK(d.image.max_depth == 7);
  CHECK(d.image.line == 2);

  CHECK(same(d.camera.position, Vec3(1, 2, 55)));
  CHECK(same(d.camera.look_at, Vec3(0, 0.5f, 0)));
  CHECK(same(d.camera.up, Vec3(0, 1, 0)));
  CHECK(d.camera.fov_degrees == 45.0f);
  CHECK(d.camera.near == 2.5f);
  CHECK(d.camera.line == 3);

  CHECK(d.antialias_sigma == 0.75f);
  CHECK(d.antialias_line == 4);
  CHECK(same(d.background, Color(0.1f, 0.2f, 0.3f)));
  CHECK(d.background_line == 5);
  CHECK(d.medium_ior == 1.33f);
  CHECK(d.medium_line == 6);

  REQUIRE(d.lights.size() == 2);
  CHECK(same(d.lights[0].position, Vec3(-10, 20, 40)));
  CHECK(d.lights[0].intensity == 4000.0f);
  CHECK(same(d.lights[0].color, Color(1, 0.5f, 0.25f)));
  CHECK(d.lights[0].line == 7);
  CHECK(same(d.lights[1].color, Color(1.0f)));  // default colour
  CHECK(d.lights[1].intensity == 0.5f);
  CHECK(d.lights[1].line == 14);

  REQUIRE(d.spheres.size() == 3);
  const auto& glass = d.spheres[0];
  CHECK(same(glass.center, Vec3(0.0f)));
  CHECK(glass.radius == 10.0f);
  CHECK(glass.material.transparent == 1.0f);
  CHECK(glass.material.mirror == 0.0f);
  CHECK(glass.material.diffuse == 0.0f);  // 1 - mirror - transparent
  CHECK(glass.material.ior == 1.5f);
  CHECK(glass.shading == ShadingKind::uniform);
  CHECK(glass.line == 11);

  const auto& inline_sphere = d.spheres[1];
  CHECK(same(inline_sphere.center, Vec3(5, -1, 2)));
  CHECK(inline_sphere.radius == 2.0f);
  CHECK(inline_sphere.material.diffuse == 0.5f);
  CHECK(same(inline_sphere.material.diffuse_color, Color(1, 1, 0)));
  CHECK(inline_sphere.material.mirror == 0.5f);
  CHECK(inline_sphere.shading == ShadingKind::octants);
  CHECK(inline_sphere.line == 12);

  const auto& wall = d.spheres[2];
  CHECK(wall.radius == 1e5f);
  CHECK(wall.shading == ShadingKind::checker);
  const glint::Material& red = wall.material;
  CHECK(red.diffuse == 0.8f);
  CHECK(same(red.diffuse_color, Color(0.9f, 0.2f, 0.2f)));
  CHECK(red.mirror == 0.1f);
  CHECK(same(red.mirror_color, Color(0.5f, 0.6f, 0.7f)));
  CHECK(red.transparent == 0.1f);
  CHECK(same(red.transparent_color, Color(0.2f, 0.3f, 0.4f)));
  CHECK(red.ior == 2.4f);
  CHECK(same(red.emission, Color(3, 2, 1)));
  CHECK(wall.line == 13);
}

TEST_CASE("scene reader: missing statements keep the description's defaults", "[scene_reader]") {
  const SceneDescription defaults;
  for (const char* text : {"", "\n\n", "# only a comment\n", "   \t  \n"}) {
    const SceneDescription d = read_scene_text(text);
    CHECK(d.source == "<scene>");
    CHECK(d.image.width == defaults.image.width);
    CHECK(d.image.height == defaults.image.height);
    CHECK(d.image.samples_per_pixel == defaults.image.samples_per_pixel);
    CHECK(d.image.max_depth == defaults.image.max_depth);
    CHECK(same(d.camera.position, defaults.camera.position));
    CHECK(same(d.camera.look_at, defaults.camera.look_at));
    CHECK(same(d.camera.up, defaults.camera.up));
    CHECK(d.camera.fov_degrees == defaults.camera.fov_degrees);
    CHECK(d.camera.near == defaults.camera.near);
    CHECK(d.antialias_sigma == defaults.antialias_sigma);
    CHECK(same(d.background, defaults.background));
    CHECK(d.medium_ior == defaults.medium_ior);
    CHECK(d.lights.empty());
    CHECK(d.spheres.empty());
  }
  SECTION("a statement with no keys keeps the defaults of its keys") {
    const SceneDescription d = read_scene_text("image\ncamera fov=30\n");
    CHECK(d.image.width == defaults.image.width);
    CHECK(d.image.line == 1);
    CHECK(d.camera.fov_degrees == 30.0f);
    CHECK(same(d.camera.position, defaults.camera.position));
  }
  SECTION("partial image statement") {
    const SceneDescription d = read_scene_text("image height=10\n");
    CHECK(d.image.width == defaults.image.width);
    CHECK(d.image.height == 10);
  }
}

TEST_CASE("scene reader: material defaults", "[scene_reader]") {
  const SceneDescription d = read_scene_text("sphere center=1,2,3 radius=4\n");
  REQUIRE(d.spheres.size() == 1);
  const glint::Material& m = d.spheres[0].material;
  CHECK(m.diffuse == 1.0f);
  CHECK(m.mirror == 0.0f);
  CHECK(m.transparent == 0.0f);
  CHECK(same(m.diffuse_color, Color(1.0f)));
  CHECK(same(m.mirror_color, Color(1.0f)));
  CHECK(same(m.transparent_color, Color(1.0f)));
  CHECK(m.ior == 1.5f);
  CHECK(same(m.emission, Color(0.0f)));
  CHECK(d.spheres[0].shading == ShadingKind::uniform);
  CHECK(same(d.spheres[0].center, Vec3(1, 2, 3)));
  CHECK(d.spheres[0].radius == 4.0f);
}

TEST_CASE("scene reader: diffuse defaults to 1 - mirror - transparent", "[scene_reader]") {
  const auto diffuse_of = [](const std::string& keys) {
    const SceneDescription d = read_scene_text("sphere center=0,0,0 radius=1 " + keys + "\n");
    REQUIRE(d.spheres.size() == 1);
    return d.spheres[0].material.diffuse;
  };
  CHECK(diffuse_of("") == 1.0f);
  CHECK(diffuse_of("mirror=0.25") == 0.75f);
  CHECK(diffuse_of("transparent=0.5") == 0.5f);
  CHECK(diffuse_of("mirror=0.25 transparent=0.5") == 0.25f);
  // Rounding must not turn an exact complement into a tiny negative coefficient.
  CHECK(diffuse_of("mirror=0.7 transparent=0.3") == 0.0f);
  CHECK(diffuse_of("mirror=0.1 transparent=0.9") == 0.0f);
  // An explicit diffuse is kept even when the lobes do not add up to 1 (absorption).
  CHECK(diffuse_of("diffuse=0.2 mirror=0.3") == 0.2f);
  CHECK(diffuse_of("diffuse=0 mirror=0.3") == 0.0f);

  SECTION("the same rule for named materials") {
    const SceneDescription d = read_scene_text(
        "material m mirror=0.4\n"
        "sphere center=0,0,0 radius=1 material=m\n");
    CHECK(d.spheres[0].material.diffuse == 0.6f);
    CHECK(d.spheres[0].material.mirror == 0.4f);
  }
  SECTION("mirror + transparent above 1 leaves no room for diffuse") {
    expect_error("sphere center=0,0,0 radius=1 mirror=0.8 transparent=0.5\n", 1,
                 "mirror + transparent must not exceed 1");
    expect_error("\nmaterial m mirror=0.8 transparent=0.5\n", 2,
                 "mirror + transparent must not exceed 1");
  }
}

TEST_CASE("scene reader: rough and metal mirrors", "[scene_reader]") {
  const auto material_of = [](const std::string& keys) {
    const SceneDescription d = read_scene_text("sphere center=0,0,0 radius=1 " + keys + "\n");
    REQUIRE(d.spheres.size() == 1);
    return d.spheres[0].material;
  };
  const glint::Material gold = material_of("metal=gold mirror_roughness=0.25");
  CHECK(gold.mirror_roughness == 0.25f);
  CHECK(gold.metal_eta == glint::metal_named("gold")->eta);
  CHECK(gold.metal_k == glint::metal_named("gold")->k);
  // A named metal makes the sphere a mirror unless told otherwise.
  CHECK(gold.mirror == 1.0f);
  CHECK(gold.diffuse == 0.0f);
  CHECK(gold.has_mirror_finish());
  const glint::Material coated = material_of("metal=copper mirror=0.4");
  CHECK(coated.mirror == 0.4f);
  CHECK(coated.diffuse == 0.6f);
  const glint::Material glassy = material_of("metal=silver transparent=0.25");
  CHECK(glassy.mirror == 0.75f);
  CHECK(glassy.diffuse == 0.0f);
  const glint::Material own = material_of("mirror=1 metal_eta=0.5,0.6,0.7 metal_k=2,3,4");
  CHECK(own.metal_eta == glint::Vec3(0.5f, 0.6f, 0.7f));
  CHECK(own.metal_k == glint::Vec3(2.0f, 3.0f, 4.0f));
  CHECK(own.mirror_roughness == 0.0f);
  CHECK_FALSE(material_of("mirror=1").has_mirror_finish());
  CHECK(material_of("mirror=0.5 mirror_roughness=0.5").has_mirror_finish());

  SECTION("errors") {
    expect_error("sphere center=0,0,0 radius=1 mirror_roughness=0.3\n", 1,
                 "mirror_roughness roughens the mirror lobe, which this material does not have");
    expect_error("sphere center=0,0,0 radius=1 mirror=1 mirror_roughness=1.5\n", 1,
                 "'mirror_roughness' must be in [0, 1], got '1.5'");
    expect_error("material m metal=brass\n", 1,
                 "unknown metal 'brass' (expected gold, silver, copper, aluminium)");
    expect_error(
        "sphere center=0,0,0 radius=1 metal=gold metal_k=1,1,1\n", 1,
        "give a metal by name (metal=) or by its index (metal_eta= and metal_k=), not both");
    expect_error("sphere center=0,0,0 radius=1 mirror=1 metal_k=1,1,1\n", 1,
                 "metal_eta and metal_k go together");
    expect_error("sphere center=0,0,0 radius=1 mirror=1 metal_eta=0,1,1 metal_k=1,1,1\n", 1,
                 "metal_eta components must be in [0.001, 100]");
    expect_error("sphere center=0,0,0 radius=1 mirror=1 metal_eta=1,1,1 metal_k=1,-1,1\n", 1,
                 "metal_k components must be in [0, 100]");
    expect_error("sphere center=0,0,0 radius=1 mirror=0 metal=gold\n", 1,
                 "a metal reflects through the mirror lobe, which this material does not have");
  }
}

TEST_CASE("scene reader: rough glass", "[scene_reader]") {
  const auto material_of = [](const std::string& keys) {
    const SceneDescription d = read_scene_text("sphere center=0,0,0 radius=1 " + keys + "\n");
    REQUIRE(d.spheres.size() == 1);
    return d.spheres[0].material;
  };
  const glint::Material frosted = material_of("transparent=1 transparent_roughness=0.3 ior=1.5");
  CHECK(frosted.transparent_roughness == 0.3f);
  CHECK(frosted.transparent == 1.0f);
  CHECK(frosted.diffuse == 0.0f);
  CHECK(frosted.mirror_roughness == 0.0f);
  CHECK(frosted.has_rough_interface());
  CHECK_FALSE(frosted.has_mirror_finish());
  // The default is the ideal interface.
  const glint::Material glass = material_of("transparent=1");
  CHECK(glass.transparent_roughness == 0.0f);
  CHECK_FALSE(glass.has_rough_interface());
  // Independent of the mirror lobe's roughness.
  const glint::Material both =
      material_of("mirror=0.5 mirror_roughness=0.2 transparent=0.5 transparent_roughness=0.7");
  CHECK(both.mirror_roughness == 0.2f);
  CHECK(both.transparent_roughness == 0.7f);
  CHECK(material_of("transparent=0.5 transparent_roughness=1").transparent_roughness == 1.0f);
  CHECK(material_of("transparent=1 transparent_roughness=0").transparent_roughness == 0.0f);
  // A named material carries it to the spheres that use it.
  const SceneDescription named = read_scene_text(
      "material frosted transparent=1 transparent_roughness=0.45\n"
      "sphere center=0,0,0 radius=1 material=frosted\n");
  REQUIRE(named.spheres.size() == 1);
  CHECK(named.spheres[0].material.transparent_roughness == 0.45f);

  SECTION("errors") {
    expect_error("sphere center=0,0,0 radius=1 transparent_roughness=0.3\n", 1,
                 "transparent_roughness roughens the transparent lobe, which this material does "
                 "not have (transparent=0)");
    expect_error("\nmaterial m diffuse=1 transparent=0 transparent_roughness=0.1\n", 2,
                 "transparent_roughness roughens the transparent lobe");
    expect_error("sphere center=0,0,0 radius=1 transparent=1 transparent_roughness=1.5\n", 1,
                 "'transparent_roughness' must be in [0, 1], got '1.5'");
    expect_error("sphere center=0,0,0 radius=1 transparent=1 transparent_roughness=-0.1\n", 1,
                 "'transparent_roughness' must be in [0, 1], got '-0.1'");
    expect_error("sphere center=0,0,0 radius=1 transparent=1 transparent_roughness=x\n", 1,
                 "transparent_roughness");
    expect_error(
        "material glass transparent=1\n"
        "sphere center=0,0,0 radius=1 material=glass transparent_roughness=0.3\n",
        2, "sphere has both material=glass and inline key 'transparent_roughness'");
  }
}

TEST_CASE("scene reader: layout rules", "[scene_reader]") {
  SECTION("comments anywhere, blank lines, tabs, several spaces") {
    const SceneDescription d = read_scene_text(
        "# heading\n"
        "\n"
        "\t sphere\tcenter=1,2,3  \t radius=2#no space before the comment\n"
        "sphere center=0,0,0 radius=1 # radius=5 is commented out\n"
        "   # indented comment\n"
        "sphere center=0,0,0 radius=3 #\n");
    REQUIRE(d.spheres.size() == 3);
    CHECK(d.spheres[0].radius == 2.0f);
    CHECK(d.spheres[0].line == 3);
    CHECK(d.spheres[1].radius == 1.0f);
    CHECK(d.spheres[1].line == 4);
    CHECK(d.spheres[2].line == 6);
  }
  SECTION("CRLF line endings") {
    const SceneDescription d = read_scene_text(
        "image width=32 height=16\r\n"
        "\r\n"
        "sphere center=0,0,0 radius=1 shading=octants\r\n"
        "light position=0,5,0 intensity=7 # comment\r\n");
    CHECK(d.image.width == 32);
    CHECK(d.image.height == 16);
    REQUIRE(d.spheres.size() == 1);
    CHECK(d.spheres[0].shading == ShadingKind::octants);
    CHECK(d.spheres[0].line == 3);
    REQUIRE(d.lights.size() == 1);
    CHECK(d.lights[0].intensity == 7.0f);
    expect_error("sphere center=0,0,0\r\nsphere radius=1 centre=0,0,0\r\n", 1,
                 "missing required key 'radius'");
  }
  SECTION("no newline at the end of the last line") {
    const SceneDescription d =
        read_scene_text("sphere center=0,0,0 radius=1\nsphere center=1,1,1 radius=9");
    REQUIRE(d.spheres.size() == 2);
    CHECK(d.spheres[1].radius == 9.0f);
  }
  SECTION("a UTF-8 byte order mark is skipped") {
    const SceneDescription d = read_scene_text("\xEF\xBB\xBFimage width=3\n");
    CHECK(d.image.width == 3);
  }
}

TEST_CASE("scene reader: numbers", "[scene_reader]") {
  const SceneDescription d = read_scene_text(
      "sphere center=+1,-0,.5 radius=5. mirror=1e-1 emission=0,2E1,1e-50\n"
      "image width=+7 height=0009\n");
  REQUIRE(d.spheres.size() == 1);
  CHECK(same(d.spheres[0].center, Vec3(1.0f, 0.0f, 0.5f)));
  CHECK(d.spheres[0].radius == 5.0f);
  CHECK(d.spheres[0].material.mirror == 0.1f);
  // Below float's range is rounding, not an error: it flushes to zero.
  CHECK(same(d.spheres[0].material.emission, Color(0.0f, 20.0f, 0.0f)));
  CHECK(d.image.width == 7);
  CHECK(d.image.height == 9);
}

TEST_CASE("scene reader: syntax errors", "[scene_reader][errors]") {
  SECTION("unknown statement, with the valid ones listed") {
    expect_error("sphere center=0,0,0 radius=1\n\nsphre center=0,0,0 radius=1\n", 3,
                 "unknown statement 'sphre'");
    expect_error("Sphere center=0,0,0 radius=1\n", 1, "expected one of: image, camera");
  }
  SECTION("unknown key, with the valid keys listed") {
    expect_error("sphere center=0,0,0 radius=1 radus=2\n", 1, "unknown key 'radus' for sphere");
    expect_error("sphere center=0,0,0 radius=1 radus=2\n", 1,
                 "valid keys: diffuse, color, mirror, mirror_color, transparent, "
                 "transparent_color, ior, emission, mirror_roughness, metal, metal_eta, metal_k, "
                 "transparent_roughness, center, radius, material, shading");
    expect_error("# c\nimage width=10 samples=4\n", 2,
                 "unknown key 'samples' for image (valid keys: width, height, spp, max_depth)");
    expect_error("camera fov=30 target=0,0,0\n", 1, "valid keys: position, look_at, up, fov, near");
    expect_error("light position=0,0,0 intensity=1 colour=1,1,1\n", 1,
                 "valid keys: position, intensity, color");
    expect_error("antialias width=1\n", 1, "valid keys: sigma");
    expect_error("background colour=1,1,1\n", 1, "valid keys: color");
    expect_error("medium index=1\n", 1, "valid keys: ior");
    expect_error("material m shading=octants\n", 1,
                 "valid keys: diffuse, color, mirror, mirror_color, transparent, "
                 "transparent_color, ior, emission, mirror_roughness, metal, metal_eta, metal_k, "
                 "transparent_roughness)");
  }
  SECTION("a key given twice") {
    expect_error("\n\nsphere center=0,0,0 radius=1 radius=2\n", 3, "key 'radius' given twice");
    expect_error("image width=1 width=1\n", 1, "key 'width' given twice");
  }
  SECTION("a token without '=' or with an empty side") {
    expect_error("sphere center=0,0,0 radius 1\n", 1, "expected key=value, got 'radius'");
    expect_error("sphere center=0,0,0 radius = 1\n", 1, "no spaces are allowed around '='");
    expect_error("sphere center=0,0,0 radius=\n", 1, "missing value for 'radius'");
    expect_error("sphere center=0,0,0 =1 radius=1\n", 1, "missing key before '='");
    expect_error("sphere center=0, 0, 0 radius=1\n", 1, "expected key=value, got '0,'");
  }
  SECTION("bad numbers") {
    expect_error("sphere center=0,0,0 radius=abc\n", 1, "bad number 'abc' for 'radius'");
    expect_error("sphere center=0,0,0 radius=1.2.3\n", 1, "bad number '1.2.3'");
    expect_error("sphere center=0,0,0 radius=1e\n", 1, "bad number '1e'");
    expect_error("sphere center=0,0,0 radius=0x10\n", 1, "bad number '0x10'");
    expect_error("sphere center=0,0,0 radius=1,5\n", 1, "bad number '1,5'");
    expect_error("sphere center=0,0,0 radius=2m\n", 1, "bad number '2m'");
    expect_error("sphere center=0,0,0 radius=+-1\n", 1, "bad number '+-1'");
    expect_error("sphere center=0,0,0 radius=+\n", 1, "bad number '+'");
    expect_error("sphere center=0,a,0 radius=1\n", 1, "bad number 'a' for 'center'");
    expect_error("sphere center=0,,0 radius=1\n", 1, "bad number '' for 'center'");
    expect_error("light position=0,0,0 intensity=1.5.\n", 1, "bad number '1.5.' for 'intensity'");
  }
  SECTION("integers are parsed strictly") {
    expect_error("image width=12.5\n", 1, "'width' must be an integer, got '12.5'");
    expect_error("image height=1e3\n", 1, "'height' must be an integer, got '1e3'");
    expect_error("image spp=12x\n", 1, "'spp' must be an integer, got '12x'");
    expect_error("image max_depth=four\n", 1, "'max_depth' must be an integer");
    expect_error("image width=99999999999\n", 1,
                 "integer '99999999999' for 'width' is out of range");
  }
  SECTION("non-finite numbers") {
    expect_error("sphere center=0,0,0 radius=inf\n", 1,
                 "'radius' must be a finite number, got 'inf'");
    expect_error("sphere center=0,0,0 radius=nan\n", 1,
                 "'radius' must be a finite number, got 'nan'");
    expect_error("sphere center=0,-inf,0 radius=1\n", 1, "'center' must be a finite number");
    expect_error("light position=0,0,0 intensity=1e99\n", 1,
                 "'intensity' must be a finite number, got '1e99' (too large for a 32-bit float)");
    expect_error("camera fov=infinity\n", 1, "'fov' must be a finite number");
    expect_error("background color=NaN,0,0\n", 1, "'color' must be a finite number");
    expect_error("medium ior=1e999\n", 1, "number '1e999' for 'ior' is out of range");
  }
  SECTION("vectors need exactly three components") {
    expect_error("sphere center=1,2 radius=1\n", 1, "'center' needs 3 components x,y,z, got 2");
    expect_error("sphere center=1,2,3,4 radius=1\n", 1, "got 4");
    expect_error("sphere center=1,2,3, radius=1\n", 1, "got 4");
    expect_error("sphere center=7 radius=1\n", 1, "got 1");
    expect_error("camera up=0,1\n", 1, "'up' needs 3 components");
  }
  SECTION("missing required keys") {
    expect_error("light intensity=1\n", 1, "missing required key 'position' for light");
    expect_error("light position=0,0,0\n", 1, "missing required key 'intensity' for light");
    expect_error("\nsphere radius=1\n", 2, "missing required key 'center' for sphere");
    expect_error("sphere center=0,0,0\n", 1, "missing required key 'radius' for sphere");
    expect_error("sphere\n", 1, "missing required key 'center'");
  }
  SECTION("input quoted in messages is escaped and shortened") {
    expect_error("sph\x01re\n", 1, "unknown statement 'sph\\x01re'");
    expect_error("sphere center=0,0,0 radius=\xC3\xA9\n", 1, "bad number '\\xc3\\xa9'");
    const std::string long_token(200, 'x');
    try {
      (void)read_scene_text(long_token + "\n");
      FAIL("expected a SceneError");
    } catch (const SceneError& e) {
      CHECK_THAT(e.what(), Contains("unknown statement '" + std::string(40, 'x') + "...'"));
      CHECK(std::string(e.what()).size() < 200);
    }
  }
  SECTION("NUL bytes and enormous lines") {
    expect_error("sphere center=0,0,0 radius=1\nsph\0ere\n"sv, 2, "NUL byte");
    const std::string huge = "# " + std::string(glint::kMaxSceneLineLength, 'x') + "\n";
    expect_error("\n" + huge, 2, "line is longer than");
  }
}

TEST_CASE("scene reader: semantic errors", "[scene_reader][errors]") {
  SECTION("radius must be positive") {
    expect_error("sphere center=0,0,0 radius=0\n", 1, "sphere radius must be positive, got '0'");
    expect_error("\nsphere center=0,0,0 radius=-2\n", 2, "sphere radius must be positive");
  }
  SECTION("radius and coordinates within the geometry limits, which are accepted") {
    expect_error("sphere center=0,0,0 radius=2e10\n", 1,
                 "sphere radius must be at most 1e+10 (the scene format's limit), got 2e+10");
    expect_error("\nsphere center=0,-3e11,0 radius=1\n", 2,
                 "sphere center coordinates must be within +-1e+11 (the scene format's limit), "
                 "got 3e+11");
    expect_error("camera position=0,0,-1.5e11 look_at=0,0,0\n", 1,
                 "camera position coordinates must be within +-1e+11");
    expect_error("light position=2e11,0,0 intensity=1\n", 1,
                 "light position coordinates must be within +-1e+11");
    const glint::SceneDescription at_limits = read_scene_text(
        "camera position=-1e11,0,1e11 look_at=0,0,0\nlight position=1e11,-1e11,1e11 "
        "intensity=1\nsphere center=1e11,1e11,-1e11 radius=1e10\n");
    CHECK(at_limits.spheres.at(0).radius == glint::limits::max_sphere_radius);
  }
  SECTION("coefficients in [0, 1]") {
    expect_error("sphere center=0,0,0 radius=1 diffuse=1.5\n", 1,
                 "'diffuse' must be in [0, 1], got '1.5'");
    expect_error("sphere center=0,0,0 radius=1 mirror=-0.1\n", 1, "'mirror' must be in [0, 1]");
    expect_error("sphere center=0,0,0 radius=1 transparent=2\n", 1,
                 "'transparent' must be in [0, 1]");
    expect_error("material m diffuse=-1\n", 1, "'diffuse' must be in [0, 1]");
  }
  SECTION("coefficients summing above 1") {
    expect_error("sphere center=0,0,0 radius=1 diffuse=0.6 mirror=0.6\n", 1,
                 "diffuse + mirror + transparent must not exceed 1, got 1.2");
    expect_error("\n\nmaterial m diffuse=0.5 transparent=0.3 mirror=0.3\n", 3,
                 "diffuse + mirror + transparent must not exceed 1");
  }
  SECTION("colours, emission and ior") {
    expect_error("sphere center=0,0,0 radius=1 color=1.5,0,0\n", 1,
                 "color components must be in [0, 1]");
    expect_error("sphere center=0,0,0 radius=1 mirror_color=0,-1,0\n", 1,
                 "mirror_color components must be in [0, 1]");
    expect_error("material m transparent_color=0,0,2\n", 1,
                 "transparent_color components must be in [0, 1]");
    expect_error("sphere center=0,0,0 radius=1 emission=0,0,-1\n", 1,
                 "emission must be finite and non-negative");
    expect_error("sphere center=0,0,0 radius=1 ior=0\n", 1, "ior must be in [0.001, 100]");
    // Emission is radiance, not reflectance: it may exceed 1.
    CHECK(read_scene_text("sphere center=0,0,0 radius=1 emission=50,40,30\n")
              .spheres[0]
              .material.emission.x == 50.0f);
  }
  SECTION("lights") {
    expect_error("light position=0,0,0 intensity=-1\n", 1,
                 "light intensity must be finite and non-negative");
    expect_error("\nlight position=0,0,0 intensity=1 color=1,-1,1\n", 2,
                 "light color must be finite and non-negative");
    // A light's colour is a filter on its intensity, allowed above 1.
    CHECK(read_scene_text("light position=0,0,0 intensity=1 color=2,2,2\n").lights[0].color.x ==
          2.0f);
  }
  SECTION("shading kinds") {
    expect_error(
        "sphere center=0,0,0 radius=1 shading=stripes\n", 1,
        "unknown shading 'stripes' (expected uniform, octants, checker, texture or custom)");
    expect_error("sphere center=0,0,0 radius=1 shading=Octants\n", 1, "unknown shading");
  }
  SECTION("the first error in the file is the one reported") {
    expect_error("sphere center=0,0,0 radius=1\nsphere center=0,0,0 radius=0\nimage width=0\n", 2,
                 "radius");
    expect_error("image width=0\nsphere center=0,0,0 radius=0\n", 1, "image size");
  }
}

TEST_CASE("scene reader: named materials", "[scene_reader][errors]") {
  SECTION("a sphere copies the named material and keeps its own shading") {
    const SceneDescription d = read_scene_text(
        "material gold-2_b mirror=0.9 mirror_color=1,0.8,0.3 diffuse=0.1\n"
        "sphere center=0,0,0 radius=1 material=gold-2_b shading=checker\n"
        "sphere center=3,0,0 radius=1 material=gold-2_b\n");
    REQUIRE(d.spheres.size() == 2);
    for (const auto& s : d.spheres) {
      CHECK(s.material.mirror == 0.9f);
      CHECK(s.material.diffuse == 0.1f);
      CHECK(same(s.material.mirror_color, Color(1, 0.8f, 0.3f)));
    }
    CHECK(d.spheres[0].shading == ShadingKind::checker);
    CHECK(d.spheres[1].shading == ShadingKind::uniform);
  }
  SECTION("names") {
    CHECK_NOTHROW(read_scene_text("material _x\nmaterial X9\nmaterial a-b\nmaterial diffuse\n"));
    expect_error("material\n", 1, "material needs a name");
    expect_error("material mirror=1\n", 1, "material needs a name");
    expect_error("material 9lives\n", 1, "invalid material name '9lives'");
    expect_error("material gl@ss\n", 1, "invalid material name 'gl@ss'");
  }
  SECTION("undefined, or defined only after use") {
    expect_error("material glass transparent=1\nsphere center=0,0,0 radius=1 material=glas\n", 2,
                 "undefined material 'glas'");
    expect_error("sphere center=0,0,0 radius=1 material=glass\nmaterial glass transparent=1\n", 1,
                 "undefined material 'glass'");
  }
  SECTION("duplicate names name the first definition") {
    expect_error("\nmaterial glass transparent=1\n\nmaterial glass mirror=1\n", 4,
                 "duplicate material 'glass' (first defined at line 2)");
  }
  SECTION("material= and inline keys are exclusive") {
    expect_error(
        "material glass transparent=1\nsphere center=0,0,0 radius=1 material=glass "
        "mirror=0.5\n",
        2, "sphere has both material=glass and inline key 'mirror'");
  }
  SECTION("errors in a material point at its definition, not at the spheres using it") {
    expect_error("material m diffuse=0.9 mirror=0.9\nsphere center=0,0,0 radius=1 material=m\n", 1,
                 "must not exceed 1");
  }
}

TEST_CASE("scene reader: statements given twice name the first", "[scene_reader][errors]") {
  expect_error("image width=10\n\nimage height=10\n", 3,
               "duplicate 'image' statement (first given at line 1)");
  expect_error("\ncamera fov=10\ncamera fov=10\n", 3,
               "duplicate 'camera' statement (first given at line 2)");
  expect_error("antialias sigma=1\nantialias\n", 2, "duplicate 'antialias' statement");
  expect_error("background\nbackground color=0,0,0\n", 2, "duplicate 'background' statement");
  expect_error("medium ior=1\n#\nmedium ior=1\n", 3,
               "duplicate 'medium' statement (first given at line 1)");
  CHECK_NOTHROW(
      read_scene_text("light position=0,0,0 intensity=1\nlight position=0,0,0 "
                      "intensity=1\n"));
}

TEST_CASE("scene reader: degenerate cameras", "[scene_reader][errors]") {
  expect_error("\ncamera position=1,2,3 look_at=1,2,3\n", 2,
               "camera position and look_at coincide");
  expect_error("camera position=0,10,0 look_at=0,0,0 up=0,1,0\n", 1,
               "camera up vector is parallel to the viewing direction");
  expect_error("camera position=0,10,0 look_at=0,0,0 up=0,-3,0.0000001\n", 1, "parallel");
  expect_error("camera up=0,0,0\n", 1, "camera up vector is zero");
  expect_error("camera fov=0\n", 1, "camera fov must be strictly between 0 and 180 degrees");
  expect_error("camera fov=180\n", 1, "fov must be strictly between");
  expect_error("camera fov=-5\n", 1, "fov must be strictly between");
  expect_error("camera near=-1\n", 1, "camera near must be finite and non-negative");
  expect_error("camera aperture=-0.5\n", 1, "camera aperture must be between 0 and ");
  expect_error("camera aperture=1e30\n", 1, "camera aperture must be between 0 and ");
  expect_error("camera focus=0\n", 1, "camera focus must be positive, got 0");
  expect_error("camera focus=-3\n", 1, "camera focus must be positive, got -3");
  expect_error("camera focus=1e30\n", 1, "camera focus must be positive and at most");
  const glint::SceneDescription lens =
      read_scene_text("camera position=0,0,10 look_at=0,0,0 aperture=0.5 focus=7.5\n");
  CHECK(lens.camera.aperture == 0.5f);
  CHECK(lens.camera.focus_distance == 7.5f);
  // Valid in double, but the float camera basis would be NaN.
  expect_error("camera position=3e38,0,0 look_at=-3e38,0,0\n", 1, "viewing basis");
  expect_error("camera up=0,1e-30,0\n", 1, "viewing basis");
  // Looking straight down works with a suitable up vector.
  CHECK_NOTHROW(read_scene_text("camera position=0,10,0 look_at=0,0,0 up=0,0,-1\n"));
}

TEST_CASE("scene reader: absurd image settings", "[scene_reader][errors]") {
  expect_error("\nimage width=0\n", 2, "image size must be between 1 and 32768");
  expect_error("image width=100000\n", 1, "image size must be between 1 and 32768");
  expect_error("image height=-1\n", 1, "image size");
  expect_error("image width=20000 height=20000\n", 1, "exceeds 67108864 pixels");
  expect_error("image spp=0\n", 1, "spp must be between 1 and");
  expect_error("image max_depth=-1\n", 1, "max_depth must be between 0 and 1024");
  expect_error("image max_depth=5000\n", 1, "max_depth must be between 0 and 1024");
  CHECK(read_scene_text("image width=1 height=1 spp=1 max_depth=0\n").image.max_depth == 0);
  CHECK(read_scene_text("image width=8192 height=8192\n").image.width == 8192);
}

TEST_CASE("scene reader: scene-wide settings out of range", "[scene_reader][errors]") {
  expect_error("\nantialias sigma=-1\n", 2, "antialias sigma must be in [0, 100] pixels, got -1");
  expect_error("background color=0,-1,0\n", 1, "background color must be finite and non-negative");
  expect_error("#\n#\nmedium ior=0\n", 3, "medium ior must be in [0.001, 100], got 0");
  CHECK(read_scene_text("antialias sigma=0\n").antialias_sigma == 0.0f);
  CHECK(read_scene_text("background color=5,5,5\n").background.x == 5.0f);
}

TEST_CASE("validate: descriptions built in code", "[scene_reader][validate]") {
  SceneDescription d;
  CHECK_NOTHROW(glint::validate(d));
  SECTION("an element's line is used, 0 meaning no line") {
    d.image.width = 0;
    try {
      glint::validate(d);
      FAIL("expected a SceneError");
    } catch (const SceneError& e) {
      CHECK(e.line() == 0);
      CHECK_THAT(e.what(), StartsWith("<scene>: error: image size"));
    }
    d.image.line = 12;
    try {
      glint::validate(d);
      FAIL("expected a SceneError");
    } catch (const SceneError& e) {
      CHECK(e.line() == 12);
      CHECK_THAT(e.what(), StartsWith("<scene>:12: error: image size"));
    }
  }
  SECTION("sphere errors carry the sphere's line") {
    glint::SphereDescription s;
    s.radius = -1.0f;
    s.line = 42;
    d.spheres.push_back(s);
    CHECK_THROWS_MATCHES(glint::validate(d), SceneError,
                         Catch::Matchers::Predicate<SceneError>(
                             [](const SceneError& e) { return e.line() == 42; }, "line 42"));
  }
}

TEST_CASE("scene reader: files", "[scene_reader][file]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GLINT_BINARY_DIR) / "scene_reader_test";
  fs::create_directories(dir);

  SECTION("a file that does not exist") {
    const fs::path missing = dir / "missing.scene";
    try {
      (void)glint::read_scene_file(missing);
      FAIL("expected a SceneError");
    } catch (const SceneError& e) {
      CHECK(e.line() == 0);
      CHECK(e.source() == missing.string());
      CHECK_THAT(e.what(), StartsWith(missing.string() + ": error: cannot open file: "));
      CHECK_THAT(e.what(), Contains("No such file"));
    }
  }
  SECTION("a directory") {
    CHECK_THROWS_WITH(glint::read_scene_file(dir), Contains("cannot open file"));
  }
  SECTION("a valid file, and errors naming the path as given") {
    const fs::path path = dir / "two.scene";
    {
      std::ofstream out(path, std::ios::binary);
      out << "# two spheres\r\nsphere center=0,0,0 radius=1\r\nsphere center=0,3,0 radius=2\r\n";
    }
    const SceneDescription d = glint::read_scene_file(path);
    CHECK(d.source == path.string());
    REQUIRE(d.spheres.size() == 2);
    CHECK(d.spheres[1].radius == 2.0f);
    CHECK(d.spheres[1].line == 3);

    {
      std::ofstream out(path, std::ios::binary);
      out << "sphere center=0,0,0 radius=1\n\nlight position=0,0,0\n";
    }
    CHECK_THROWS_WITH(glint::read_scene_file(path),
                      StartsWith(path.string() + ":3: error: missing required key 'intensity'"));
    // Its text alone, as it is: errors of the parse come from read_scene_text.
    CHECK(glint::read_scene_file_text(path) ==
          "sphere center=0,0,0 radius=1\n\nlight position=0,0,0\n");
  }
  SECTION("binary input stops at its first NUL byte, with the line it is on") {
    const fs::path path = dir / "binary.scene";
    {
      // Valid lines across more than one read buffer, then a NUL and much more after it.
      std::ofstream out(path, std::ios::binary);
      for (int i = 0; i < 3000; ++i)
        out << "sphere center=0,0," << i * 3 << " radius=1   # padding padding padding\n";
      out << "sphere center=0,0,0 radius=1" << '\0' << std::string(1 << 20, 'x') << "\n";
    }
    CHECK_THROWS_WITH(glint::read_scene_file(path),
                      StartsWith(path.string() + ":3001: error: line contains a NUL byte"));
    CHECK_THROWS_WITH(glint::read_scene_file_text(path),
                      StartsWith(path.string() + ":3001: error: line contains a NUL byte"));
  }
  SECTION("text without line ends is refused once a line is too long, not after a GiB") {
    // An endless stream of one character through a pipe, in a child: the reader must stop.
    const fs::path fifo = dir / "endless.scene";
    fs::remove(fifo);
    REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
    const glint_test::ChildRun run = glint_test::run_in_child_above_baseline([&] {
      std::signal(SIGPIPE, SIG_IGN);
      std::thread writer([&] {
        const int fd = ::open(fifo.c_str(), O_WRONLY);
        const std::string line = "sphere center=0,0,0 radius=1\n", endless(1 << 16, 'y');
        ssize_t written = ::write(fd, line.data(), line.size());
        while (written > 0)
          written = ::write(fd, endless.data(), endless.size());
        ::close(fd);
      });
      std::string message;
      try {
        glint::read_scene_file_text(fifo);
      } catch (const glint::SceneError& error) {
        message = error.what();
      }
      writer.join();
      return message.starts_with(fifo.string() + ":2: error: line is longer than 65536 characters")
                 ? 0
                 : 3;
    });
    CHECK(run.status == 0);
    CHECK(run.peak_kb < 64 * 1024);
  }
  SECTION("/dev/zero is refused on its first line, not after a GiB") {
    if (fs::exists("/dev/zero"))
      CHECK_THROWS_WITH(glint::read_scene_file("/dev/zero"),
                        StartsWith("/dev/zero:1: error: line contains a NUL byte"));
  }
  SECTION("the complete example of the scene format's reference") {
    // Keeps the documentation honest: the block after the marker must parse as documented.
    std::ifstream in(fs::path(GLINT_SOURCE_DIR) / "docs" / "scene-format.md");
    REQUIRE(in);
    const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t marker = doc.find("<!-- complete example -->");
    REQUIRE(marker != std::string::npos);
    const std::size_t open = doc.find("```\n", marker);
    REQUIRE(open != std::string::npos);
    const std::size_t close = doc.find("\n```", open + 4);
    REQUIRE(close != std::string::npos);
    // As if the file were in docs/images/, where its texture's path leads.
    const SceneDescription d = read_scene_text(
        doc.substr(open + 4, close - open - 3),
        (fs::path(GLINT_SOURCE_DIR) / "docs" / "images" / "example.scene").string());
    CHECK(d.lights.size() >= 1);
    CHECK(d.spheres.size() >= 5);
  }
}

TEST_CASE("scene reader: a million spheres parse in linear time", "[scene_reader][.perf]") {
  std::string text = "material m mirror=0.5\n";
  for (int i = 0; i < 1000000; ++i)
    text += "sphere center=" + std::to_string(i % 1000) + ".25," + std::to_string(i / 1000) +
            ".5,-3.125 radius=0.375 " + (i % 2 ? "material=m" : "diffuse=0.5 color=0.9,0.2,0.2") +
            "\n";
  const auto start = std::chrono::steady_clock::now();
  const SceneDescription d = read_scene_text(text);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(d.spheres.size() == 1000000);
  WARN("parsed " << text.size() / 1e6 << " MB, 1,000,000 spheres in " << seconds << " s");
}
