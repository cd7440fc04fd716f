// The scene writer: exact text for known input, shortest floats that read back bit for bit,
// and a full round trip through io/scene_reader.hpp.

#include "glint/io/scene_writer.hpp"

#include <bit>
#include <catch2/catch.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

#include "glint/io/scene_reader.hpp"
#include "glint/math/random.hpp"

namespace {

std::string shortest(float v) {
  std::string out;
  glint::detail::append_float(out, v, "number");
  return out;
}

bool reads_back(float v) {
  const std::string text = shortest(v);
  float parsed = 0.0f;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), parsed);
  return r.ec == std::errc{} && r.ptr == text.data() + text.size() &&
         std::bit_cast<std::uint32_t>(parsed) == std::bit_cast<std::uint32_t>(v);
}

/// A description that sets every field to a value away from its default, with floats chosen
/// to need all their digits.
glint::SceneDescription every_field_scene() {
  using glint::Color;
  using glint::Vec3;
  glint::SceneDescription scene;
  scene.image.width = 640;
  scene.image.height = 480;
  scene.image.samples_per_pixel = 37;
  scene.image.max_depth = 5;
  scene.camera.position = Vec3(0.1f, -2.5e-3f, 55.000004f);
  scene.camera.look_at = Vec3(1.0f / 3.0f, 2.0f / 3.0f, -7.0f);
  scene.camera.up = Vec3(0.0f, 1.0f, 1e-3f);
  scene.camera.fov_degrees = 47.123456f;
  scene.camera.near = 0.25f;
  scene.camera.aperture = 0.0625f;
  scene.camera.focus_distance = 31.4159f;
  scene.antialias_sigma = 0.333333343f;
  scene.background = Color(0.01f, 0.02f, 0.03f);
  scene.medium_ior = 1.333f;
  glint::PointLight light;
  light.position = Vec3(-10.0f, 20.0f, 40.0f);
  light.intensity = 4000.5f;
  light.color = Color(1.0f, 0.9f, 0.8f);
  scene.lights.push_back(light);
  light.position = Vec3(3.0e-7f, 1e5f, -1e-30f);
  light.intensity = 0.0f;
  light.color = Color(0.0f, 0.5f, 1.0f);
  scene.lights.push_back(light);

  glint::SphereDescription sphere;
  sphere.center = Vec3(99960.0f, 0.0f, 0.0f);  // a wall
  sphere.radius = 1e5f;
  sphere.material.diffuse_color = Color(0.75f, 0.25f, 0.25f);
  scene.spheres.push_back(sphere);

  sphere = {};  // every material key set, none implied
  sphere.center = Vec3(1.1f, -2.2f, 3.3f);
  sphere.radius = 0.7f;
  sphere.material.diffuse = 0.1f;
  sphere.material.diffuse_color = Color(0.9f, 0.2f, 0.2f);
  sphere.material.mirror = 0.2f;
  sphere.material.mirror_color = Color(0.5f, 0.6f, 0.7f);
  sphere.material.transparent = 0.3f;
  sphere.material.transparent_color = Color(0.8f, 0.9f, 1.0f);
  sphere.material.ior = 1.7654321f;
  sphere.material.emission = Color(10.0f, 20.5f, 0.125f);
  sphere.shading = glint::ShadingKind::octants;
  scene.spheres.push_back(sphere);

  sphere = {};  // a rough metal of one's own
  sphere.center = Vec3(7.0f, 1.0f, -3.0f);
  sphere.radius = 1.5f;
  sphere.material.diffuse = 0.25f;
  sphere.material.mirror = 0.75f;
  sphere.material.mirror_roughness = 0.3333333f;
  sphere.material.metal_eta = Color(0.2f, 0.9243f, 1.1f);
  sphere.material.metal_k = Color(3.9f, 2.45f, 0.0f);
  scene.spheres.push_back(sphere);

  sphere = {};  // frosted glass beside a rough mirror lobe
  sphere.center = Vec3(-9.0f, 2.0f, 4.0f);
  sphere.radius = 2.5f;
  sphere.material.diffuse = 0.0f;
  sphere.material.mirror = 0.2f;
  sphere.material.mirror_roughness = 0.1f;
  sphere.material.transparent = 0.8f;
  sphere.material.transparent_roughness = 0.31622776f;
  sphere.material.ior = 1.45f;
  scene.spheres.push_back(sphere);

  sphere = {};  // pure glass: diffuse left to the default
  sphere.center = Vec3(-5.0f, 0.0f, 12.5f);
  sphere.radius = 3.0f;
  sphere.material.diffuse = 0.0f;
  sphere.material.transparent = 1.0f;
  sphere.material.ior = 1.5f;
  sphere.shading = glint::ShadingKind::checker;
  scene.spheres.push_back(sphere);

  sphere = {};  // a coefficient of -0 must survive as -0
  sphere.center = Vec3(-0.0f, 8.0f, -8.0f);
  sphere.radius = 1.0f;
  sphere.material.mirror = -0.0f;
  sphere.material.transparent_roughness = -0.0f;
  sphere.material.diffuse = 0.5f;
  scene.spheres.push_back(sphere);

  sphere = {};  // an emitter with an explicit diffuse the writer cannot leave implied
  sphere.center = Vec3(0.0f, 30.0f, 0.0f);
  sphere.radius = 2.0f;
  sphere.material.diffuse = 0.3f;
  sphere.material.mirror = 0.7f;
  sphere.material.emission = Color(12.0f);
  scene.spheres.push_back(sphere);

  sphere = {};  // a diffuse remainder small enough to look like rounding, at the limits of
                // the scene format's coordinates
  sphere.center = Vec3(1e-30f, -glint::limits::max_coordinate, 3.4e-38f);
  sphere.radius = std::numeric_limits<float>::denorm_min();
  sphere.material.diffuse = 0x1p-21f;
  sphere.material.mirror = 1.0f - 0x1p-21f;
  scene.spheres.push_back(sphere);
  return scene;
}

std::uint32_t bits(float v) {
  return std::bit_cast<std::uint32_t>(v);
}

void require_same(const glint::Vec3& a, const glint::Vec3& b) {
  REQUIRE(bits(a.x) == bits(b.x));
  REQUIRE(bits(a.y) == bits(b.y));
  REQUIRE(bits(a.z) == bits(b.z));
}

/// Field by field, bit for bit; line numbers and the source label belong to the file.
void require_same_scene(const glint::SceneDescription& a, const glint::SceneDescription& b) {
  REQUIRE(a.image.width == b.image.width);
  REQUIRE(a.image.height == b.image.height);
  REQUIRE(a.image.samples_per_pixel == b.image.samples_per_pixel);
  REQUIRE(a.image.max_depth == b.image.max_depth);
  require_same(a.camera.position, b.camera.position);
  require_same(a.camera.look_at, b.camera.look_at);
  require_same(a.camera.up, b.camera.up);
  REQUIRE(bits(a.camera.fov_degrees) == bits(b.camera.fov_degrees));
  REQUIRE(bits(a.camera.near) == bits(b.camera.near));
  REQUIRE(bits(a.camera.aperture) == bits(b.camera.aperture));
  REQUIRE(bits(a.camera.focus_distance) == bits(b.camera.focus_distance));
  REQUIRE(bits(a.antialias_sigma) == bits(b.antialias_sigma));
  require_same(a.background, b.background);
  REQUIRE(bits(a.medium_ior) == bits(b.medium_ior));
  REQUIRE(a.lights.size() == b.lights.size());
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    INFO("light " << i);
    require_same(a.lights[i].position, b.lights[i].position);
    REQUIRE(bits(a.lights[i].intensity) == bits(b.lights[i].intensity));
    require_same(a.lights[i].color, b.lights[i].color);
  }
  REQUIRE(a.spheres.size() == b.spheres.size());
  for (std::size_t i = 0; i < a.spheres.size(); ++i) {
    INFO("sphere " << i);
    const glint::SphereDescription& x = a.spheres[i];
    const glint::SphereDescription& y = b.spheres[i];
    require_same(x.center, y.center);
    REQUIRE(bits(x.radius) == bits(y.radius));
    REQUIRE(x.shading == y.shading);
    REQUIRE(bits(x.material.diffuse) == bits(y.material.diffuse));
    require_same(x.material.diffuse_color, y.material.diffuse_color);
    REQUIRE(bits(x.material.mirror) == bits(y.material.mirror));
    require_same(x.material.mirror_color, y.material.mirror_color);
    REQUIRE(bits(x.material.transparent) == bits(y.material.transparent));
    require_same(x.material.transparent_color, y.material.transparent_color);
    REQUIRE(bits(x.material.ior) == bits(y.material.ior));
    require_same(x.material.emission, y.material.emission);
    REQUIRE(bits(x.material.mirror_roughness) == bits(y.material.mirror_roughness));
    REQUIRE(bits(x.material.transparent_roughness) == bits(y.material.transparent_roughness));
    require_same(x.material.metal_eta, y.material.metal_eta);
    require_same(x.material.metal_k, y.material.metal_k);
  }
}

}  // namespace

TEST_CASE("scene writer: floats are printed in the shortest form that reads back exactly",
          "[io][writer]") {
  CHECK(shortest(0.1f) == "0.1");
  CHECK(shortest(0.5f) == "0.5");
  CHECK(shortest(-3.0f) == "-3");
  CHECK(shortest(-0.0f) == "-0");
  CHECK(shortest(1e5f) == "100000");  // a wall radius stays readable
  CHECK(shortest(99960.0f) == "99960");
  CHECK(shortest(1e-5f) == "0.00001");
  CHECK(shortest(1e30f) == "1e+30");  // plain notation would take 31 digits
  CHECK(shortest(1.0f / 3.0f) == "0.33333334");

  const float specials[] = {0.0f,
                            -0.0f,
                            1.0f,
                            std::numeric_limits<float>::min(),
                            std::numeric_limits<float>::denorm_min(),
                            -std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::epsilon(),
                            16777217.0f,
                            0.30000001f,
                            123456.789f};
  for (const float v : specials) {
    INFO(shortest(v));
    CHECK(reads_back(v));
  }
  // Random bit patterns cover every exponent; NaNs and infinities are skipped.
  glint::Pcg32 rng(7, 3);
  int tested = 0;
  for (int i = 0; i < 200000; ++i) {
    const float v = std::bit_cast<float>(rng.next_u32());
    if (!std::isfinite(v)) continue;
    ++tested;
    if (!reads_back(v)) FAIL("does not read back: " << shortest(v));
  }
  CHECK(tested > 190000);
}

TEST_CASE("scene writer: statements and keys use the format's names", "[io][writer]") {
  glint::SceneDescription scene;
  glint::PointLight light;
  light.position = glint::Vec3(-10.0f, 20.0f, 40.0f);
  light.intensity = 4000.0f;
  scene.lights.push_back(light);
  glint::SphereDescription glass;
  glass.radius = 10.0f;
  glass.material.diffuse = 0.0f;
  glass.material.transparent = 1.0f;
  scene.spheres.push_back(glass);
  glint::SphereDescription mixed;
  mixed.center = glint::Vec3(5.0f, 0.0f, 0.0f);
  mixed.radius = 2.0f;
  mixed.material.diffuse = 0.5f;
  mixed.material.mirror = 0.5f;
  mixed.shading = glint::ShadingKind::octants;
  scene.spheres.push_back(mixed);

  CHECK(glint::format_scene(scene) ==
        "image width=800 height=800 spp=1000 max_depth=12\n"
        "camera position=0,0,55 look_at=0,0,0 up=0,1,0 fov=60 near=0\n"
        "antialias sigma=0.5\n"
        "background color=0,0,0\n"
        "medium ior=1\n"
        "light position=-10,20,40 intensity=4000 color=1,1,1\n"
        "sphere center=0,0,0 radius=10 transparent=1\n"
        "sphere center=5,0,0 radius=2 mirror=0.5 shading=octants\n");
}

TEST_CASE("scene writer: material keys are left out only where the default restores them",
          "[io][writer]") {
  const auto line_of = [](const glint::Material& material) {
    glint::SceneDescription scene;
    glint::SphereDescription sphere;
    sphere.material = material;
    scene.spheres.push_back(sphere);
    const std::string text = glint::format_scene(scene);
    const auto start = text.find("sphere ");
    return text.substr(start, text.size() - start - 1);
  };
  glint::Material m;
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1");
  m.diffuse = 0.0f;
  m.mirror = 1.0f;
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1 mirror=1");
  // 1 - 0.1 - 0.3 and 1 - (0.1 + 0.3) differ in the last bit in float, so a reader's
  // default could differ from the stored value: the writer keeps the key.
  m = {};
  m.diffuse = 0.6f;
  m.mirror = 0.1f;
  m.transparent = 0.3f;
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1 diffuse=0.6 mirror=0.1 transparent=0.3");
  // Less than the implied amount is always written.
  m = {};
  m.diffuse = 0.25f;
  m.diffuse_color = glint::Color(0.5f, 0.25f, 0.125f);
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1 diffuse=0.25 color=0.5,0.25,0.125");
  // A remainder this small could be taken for rounding and read back as 0.
  m = {};
  m.diffuse = 0x1p-21f;
  m.mirror = 1.0f - 0x1p-21f;
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1 diffuse=0.00000047683716 mirror=0.9999995");
  m = {};
  m.mirror = -0.0f;  // -0 is not the default's bits
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1 mirror=-0");
  m = {};
  m.ior = 1.5f;
  m.emission = glint::Color(0.0f, 2.0f, 0.0f);
  m.mirror_color = glint::Color(0.5f);
  m.transparent_color = glint::Color(0.25f);
  CHECK(line_of(m) ==
        "sphere center=0,0,0 radius=1 mirror_color=0.5,0.5,0.5 "
        "transparent_color=0.25,0.25,0.25 emission=0,2,0");
  // A rough interface is written; the ideal one (the default) is not.
  m = {};
  m.diffuse = 0.0f;
  m.transparent = 1.0f;
  m.transparent_roughness = 0.3f;
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1 transparent=1 transparent_roughness=0.3");
  m.transparent_roughness = 0.0f;
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1 transparent=1");
  m.transparent_roughness = -0.0f;
  CHECK(line_of(m) == "sphere center=0,0,0 radius=1 transparent=1 transparent_roughness=-0");
}

TEST_CASE("scene writer: non-finite numbers are refused with the key named", "[io][writer]") {
  glint::SceneDescription scene;
  glint::SphereDescription sphere;
  sphere.radius = std::numeric_limits<float>::infinity();
  scene.spheres.push_back(sphere);
  CHECK_THROWS_AS(glint::format_scene(scene), glint::SceneWriteError);
  CHECK_THROWS_WITH(glint::format_scene(scene), Catch::Contains("radius"));
  scene.spheres.clear();
  scene.camera.fov_degrees = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_WITH(glint::format_scene(scene), Catch::Contains("fov"));
}

TEST_CASE("scene writer: write_scene streams exactly the text of format_scene", "[io][writer]") {
  glint::SceneDescription scene = every_field_scene();
  // Enough spheres to pass the writer's 64 KiB chunk several times.
  glint::Pcg32 rng(1, 1);
  for (int i = 0; i < 5000; ++i) {
    glint::SphereDescription sphere;
    sphere.center = glint::Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 100.0f;
    sphere.radius = 0.5f + rng.next_float();
    scene.spheres.push_back(sphere);
  }
  std::ostringstream out;
  glint::write_scene(out, scene);
  REQUIRE(out.good());
  const std::string text = glint::format_scene(scene);
  CHECK(text.size() > 4 * 65536);
  CHECK(out.str() == text);
}

TEST_CASE("scene writer: reading the text back gives the same description bit for bit",
          "[io][writer][reader]") {
  const glint::SceneDescription scene = every_field_scene();
  const std::string text = glint::format_scene(scene);
  INFO(text);
  const glint::SceneDescription read = glint::read_scene_text(text, "round-trip.scene");
  require_same_scene(scene, read);
  CHECK(glint::format_scene(read) == text);
}
