// Image textures: glint's atan2 against the exact angle; the equirectangular map at known
// directions and back; an image's placement on a sphere (its axis and turn); bilinear filtering
// (exact for one colour, wrapping around in u, ending at the poles in v); the sRGB decoding
// against its formula in double; read_texture on PNG, JPEG, Radiance HDR and PFM files written
// here, and on the files it must refuse; the scene file's texture keys, their errors and their
// round trip through the writer.

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <stb_image_write.h>

#include "../support/scratch_directory.hpp"
#include "glint/error.hpp"
#include "glint/image/texture.hpp"
#include "glint/io/image_writer.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/io/scene_writer.hpp"
#include "glint/io/texture_reader.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/math/equirectangular.hpp"
#include "glint/math/random.hpp"
#include "glint/math/wide.hpp"
#include "glint/scene/scene.hpp"
#include "glint/scene/sphere_texture.hpp"

namespace texture_test {

namespace fs = std::filesystem;
using glint::Color;
using glint::Vec2;
using glint::Vec3;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// An 8-bit RGB PNG of `width` x `height`, row by row from the top.
void write_png_bytes(const fs::path& path, int width, int height,
                     const std::vector<unsigned char>& rgb, int channels = 3) {
  REQUIRE(stbi_write_png(path.c_str(), width, height, channels, rgb.data(), width * channels));
}

/// The message of the ImageReadError that read_texture(path) throws.
std::string refusal(const fs::path& path) {
  try {
    (void)glint::read_texture(path, path.filename().string());
  } catch (const glint::ImageReadError& error) {
    return error.what();
  }
  FAIL("read_texture accepted " << path);
  return {};
}

TEST_CASE("glint's atan2 is within 3e-7 of the exact angle, in every quadrant", "[texture][unit]") {
  glint::Pcg32 rng(3, 7);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    // Magnitudes over many binades, every sign, and the axes now and then.
    const float scale = std::ldexp(1.0f, int(rng.next_u32() % 60) - 30);
    float y = (2.0f * rng.next_float() - 1.0f) * scale;
    float x = (2.0f * rng.next_float() - 1.0f) * scale;
    if (i % 97 == 0) y = 0.0f;
    if (i % 89 == 0) x = 0.0f;
    const double exact = std::atan2(double(y), double(x));
    const float got = glint::atan2(y, x);
    worst = std::max(worst, std::abs(double(got) - exact));
    INFO("atan2(" << y << ", " << x << ") = " << got << ", exactly " << exact);
    REQUIRE(std::abs(double(got) - exact) <= 3e-7);
  }
  INFO("largest error " << worst);
  CHECK(worst > 0.0);
  // The C library's conventions where the angle is a multiple of pi/2.
  CHECK(glint::atan2(0.0f, 1.0f) == 0.0f);
  CHECK(glint::atan2(0.0f, 0.0f) == 0.0f);
  CHECK(glint::atan2(1.0f, 0.0f) == Approx(std::numbers::pi / 2).epsilon(1e-7));
  CHECK(glint::atan2(0.0f, -1.0f) == Approx(std::numbers::pi).epsilon(1e-7));
  CHECK(glint::atan2(-0.0f, -1.0f) == Approx(-std::numbers::pi).epsilon(1e-7));
  CHECK(glint::atan2(-1.0f, 0.0f) == Approx(-std::numbers::pi / 2).epsilon(1e-7));
}

TEST_CASE("atan2 gives every lane of a wide Float the bits of one float", "[texture][unit]") {
  using F = glint::Float<8>;
  glint::Pcg32 rng(5, 1);
  for (int round = 0; round < 1000; ++round) {
    F y{}, x{};
    for (int i = 0; i < 8; ++i) {
      y[i] = 2.0f * rng.next_float() - 1.0f;
      x[i] = i == 3 ? 0.0f : 2.0f * rng.next_float() - 1.0f;
    }
    const F wide = glint::atan2(y, x);
    for (int i = 0; i < 8; ++i)
      REQUIRE(std::bit_cast<std::uint32_t>(wide[i]) ==
              std::bit_cast<std::uint32_t>(glint::atan2(y[i], x[i])));
  }
}

TEST_CASE("the equirectangular map puts known directions where the image has them",
          "[texture][unit]") {
  const auto at = [](Vec3 d) { return glint::equirectangular_uv(d); };
  // +z meets the middle of the image; east (+x) is to its right, west to its left.
  CHECK(at({0, 0, 1}).x == Approx(0.5).margin(1e-7));
  CHECK(at({0, 0, 1}).y == Approx(0.5).margin(1e-7));
  CHECK(at({1, 0, 0}).x == Approx(0.75).margin(1e-7));
  CHECK(at({-1, 0, 0}).x == Approx(0.25).margin(1e-7));
  CHECK(at({0, 0, -1}).x == Approx(1.0).margin(1e-7));  // the seam, where u = 0 meets u = 1
  // The north pole is the top row, the south pole the bottom one; 45 degrees is a quarter.
  CHECK(at({0, 1, 0}).y == Approx(0.0).margin(1e-7));
  CHECK(at({0, -1, 0}).y == Approx(1.0).margin(1e-7));
  const float half = std::sqrt(0.5f);
  CHECK(at({0, half, half}).y == Approx(0.25).margin(1e-7));
  CHECK(at({half, 0, half}).x == Approx(0.625).margin(1e-7));

  // And back: direction(uv(d)) = d.
  glint::Pcg32 rng(9, 9);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 d = glm::normalize(
        Vec3(2 * rng.next_float() - 1, 2 * rng.next_float() - 1, 2 * rng.next_float() - 1));
    const Vec3 back = glint::equirectangular_direction(at(d));
    INFO(d.x << ", " << d.y << ", " << d.z);
    REQUIRE(glm::length(back - d) < 2e-6f);
  }
}

TEST_CASE("an image's placement turns its frame: the axis is its top, the turn spins it",
          "[texture][unit]") {
  const auto image =
      std::make_shared<const glint::Texture>("one", 1, 1, std::vector<Color>{Color(1.0f)});
  const auto near = [](Vec3 a, Vec3 b) { return glm::length(a - b) < 1e-6f; };
  {
    const glint::SphereTexture t(image, {});
    CHECK(near(t.north(), {0, 1, 0}));
    CHECK(near(t.front(), {0, 0, 1}));
    CHECK(near(t.east(), {1, 0, 0}));
  }
  {
    // Turned 90 degrees counterclockwise seen from above: the middle moves from +z to +x.
    const glint::SphereTexture t(image, {{0, 1, 0}, 90.0f});
    CHECK(t.uv({1, 0, 0}).x == Approx(0.5).margin(1e-6));
    CHECK(t.uv({1, 0, 0}).y == Approx(0.5).margin(1e-6));
    CHECK(t.uv({0, 0, 1}).x == Approx(0.25).margin(1e-6));
    // Whole turns, and turns the other way, are the same placement.
    const glint::SphereTexture again(image, {{0, 1, 0}, 90.0f + 720.0f});
    const glint::SphereTexture back(image, {{0, 1, 0}, -270.0f});
    CHECK(near(again.front(), t.front()));
    CHECK(near(back.front(), t.front()));
  }
  {
    // Tipped towards the camera: the top of the image faces +z, its middle -y.
    const glint::SphereTexture t(image, {{0, 0, 5}, 0.0f});
    CHECK(t.uv({0, 0, 1}).y == Approx(0.0).margin(1e-6));
    CHECK(t.uv({0, -1, 0}).x == Approx(0.5).margin(1e-6));
    CHECK(t.uv({0, -1, 0}).y == Approx(0.5).margin(1e-6));
    // Upside down: the top is at -y.
    const glint::SphereTexture down(image, {{0, -1, 0}, 0.0f});
    CHECK(down.uv({0, -1, 0}).y == Approx(0.0).margin(1e-6));
  }
  // Any axis, of any length: a right-handed orthonormal frame around it.
  glint::Pcg32 rng(4, 4);
  for (int i = 0; i < 2000; ++i) {
    const float scale = std::ldexp(1.0f, int(rng.next_u32() % 200) - 100);
    const Vec3 axis =
        scale * Vec3(2 * rng.next_float() - 1, 2 * rng.next_float() - 1, 2 * rng.next_float() - 1);
    const glint::SphereTexture t(image, {axis, 360.0f * rng.next_float()});
    INFO(axis.x << ", " << axis.y << ", " << axis.z);
    REQUIRE(near(t.north(), glm::normalize(axis / scale)));
    REQUIRE(std::abs(glm::dot(t.north(), t.front())) < 1e-6f);
    REQUIRE(std::abs(glm::length(t.front()) - 1.0f) < 1e-6f);
    REQUIRE(near(t.east(), glm::cross(t.north(), t.front())));
  }
}

TEST_CASE("bilinear filtering blends the nearest texel centres, wrapping around in u only",
          "[texture][unit]") {
  const Color a(1.0f, 0.0f, 0.0f), b(0.0f, 0.0f, 1.0f);
  const glint::Texture row("row", 2, 1, {a, b});
  CHECK(row.filtered(0.25f, 0.5f) == a);  // texel centres
  CHECK(row.filtered(0.75f, 0.5f) == b);
  CHECK(row.filtered(0.5f, 0.5f) == 0.5f * (a + b));
  // The seam: u = 0 and u = 1 lie between the last column and the first.
  CHECK(row.filtered(0.0f, 0.5f) == 0.5f * (a + b));
  CHECK(row.filtered(1.0f, 0.5f) == 0.5f * (a + b));
  CHECK(row.filtered(0.125f, 0.5f) == a + 0.25f * (b - a));
  const glint::Texture column("column", 1, 2, {a, b});
  CHECK(column.filtered(0.5f, 0.0f) == a);  // the top row up to the pole
  CHECK(column.filtered(0.5f, 1.0f) == b);
  CHECK(column.filtered(0.5f, 0.5f) == 0.5f * (a + b));

  // One colour is that colour exactly, wherever it is looked up.
  const Color c(0.123f, 0.456f, 0.789f);
  const glint::Texture flat("flat", 7, 5, std::vector<Color>(35, c));
  glint::Pcg32 rng(2, 2);
  for (int i = 0; i < 10000; ++i)
    REQUIRE(flat.filtered(rng.next_float(), rng.next_float()) == c);

  CHECK_THROWS_AS(glint::Texture("bad", 2, 2, std::vector<Color>(3, c)), glint::ImageReadError);
  CHECK_THROWS_WITH(glint::Texture("bad", 2, 1, {c, Color(0.0f, -1.0f, 0.0f)}),
                    Catch::Contains("bad: texel (1, 0) is not a finite, non-negative colour"));
  CHECK_THROWS_WITH(glint::Texture("bad", 1, 1, {Color(INFINITY)}),
                    Catch::Contains("not a finite"));
}

TEST_CASE("sRGB values decode to the linear values of the standard's formula", "[texture][unit]") {
  for (int v = 0; v <= 1000; ++v) {
    const double e = v / 1000.0;
    const double exact = e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
    const float got = glint::srgb_to_linear(float(e));
    INFO("encoded " << e);
    REQUIRE(std::abs(got - exact) <= 2e-6 * exact + 1e-9);
  }
  CHECK(glint::srgb_to_linear(0.0f) == 0.0f);
  CHECK(glint::srgb_to_linear(1.0f) == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("read_texture decodes PNG, JPEG, Radiance HDR and PFM files to linear texels",
          "[texture][unit]") {
  const glint_test::ScratchDirectory dir("texture");
  SECTION("an 8-bit PNG, row by row from the top, alpha ignored") {
    const std::vector<unsigned char> rgba = {10,  20,  30,  255, 128, 0,  255, 7,  //
                                             255, 255, 255, 0,   0,   64, 200, 99};
    write_png_bytes(dir / "a.png", 2, 2, rgba, 4);
    const glint::Texture t = glint::read_texture(dir / "a.png", "a.png");
    REQUIRE(t.width() == 2);
    REQUIRE(t.height() == 2);
    CHECK(t.name() == "a.png");
    const auto linear = [](int v) { return glint::srgb_to_linear(float(v) / 255.0f); };
    CHECK(t.at(0, 0) == Color(linear(10), linear(20), linear(30)));
    CHECK(t.at(1, 0) == Color(linear(128), linear(0), linear(255)));
    CHECK(t.at(0, 1) == Color(1.0f));
    CHECK(t.at(1, 1) == Color(linear(0), linear(64), linear(200)));
    CHECK(t.at(1, 0).r == Approx(0.2158605).epsilon(1e-5));  // the standard's 128
  }
  SECTION("a grey PNG is grey in every channel") {
    write_png_bytes(dir / "grey.png", 1, 1, {100}, 1);
    const glint::Texture t = glint::read_texture(dir / "grey.png", "grey.png");
    const float grey = glint::srgb_to_linear(100.0f / 255.0f);
    CHECK(t.at(0, 0) == Color(grey));
  }
  SECTION("a JPEG of one colour, within what its compression changes") {
    std::vector<unsigned char> rgb(16 * 16 * 3);
    for (std::size_t i = 0; i < rgb.size(); i += 3) {
      rgb[i] = 200;
      rgb[i + 1] = 100;
      rgb[i + 2] = 50;
    }
    REQUIRE(stbi_write_jpg((dir / "c.jpg").c_str(), 16, 16, 3, rgb.data(), 100));
    const glint::Texture t = glint::read_texture(dir / "c.jpg", "c.jpg");
    for (const int channel : {0, 1, 2}) {
      const float expected = glint::srgb_to_linear(float(rgb[std::size_t(channel)]) / 255.0f);
      CHECK(t.at(5, 9)[channel] == Approx(expected).epsilon(0.03));
    }
  }
  SECTION("a Radiance HDR, linear and beyond one") {
    const std::vector<float> rgb = {0.5f, 2.0f, 8.0f, 0.25f, 0.25f, 0.25f};
    REQUIRE(stbi_write_hdr((dir / "h.hdr").c_str(), 2, 1, 3, rgb.data()));
    const glint::Texture t = glint::read_texture(dir / "h.hdr", "h.hdr");
    CHECK(t.at(0, 0) == Color(0.5f, 2.0f, 8.0f));
    CHECK(t.at(1, 0) == Color(0.25f));
  }
  SECTION("a PFM, exactly") {
    glint::Film film(3, 2);
    film.at(0, 0) = Color(0.1f, 20.0f, 3e4f);
    film.at(2, 1) = Color(1e-6f, 0.5f, 0.0f);
    glint::write_pfm(film, dir / "f.pfm");
    const glint::Texture t = glint::read_texture(dir / "f.pfm", "f.pfm");
    CHECK(t.at(0, 0) == film.at(0, 0));
    CHECK(t.at(2, 1) == film.at(2, 1));
    CHECK(t.at(1, 1) == Color(0.0f));
  }
}

TEST_CASE("read_texture refuses what is no image it reads, naming the file and the problem",
          "[texture][unit]") {
  const glint_test::ScratchDirectory dir("texture");
  CHECK_THAT(refusal(dir / "missing.png"), Catch::Contains("cannot read") &&
                                               Catch::Contains("missing.png") &&
                                               Catch::Contains("No such file"));
  CHECK_THAT(refusal(dir.path()), Catch::Contains("it is a directory"));
  write_text(dir / "scene.png", "sphere center=0,0,0 radius=1\n");
  CHECK_THAT(refusal(dir / "scene.png"),
             Catch::Contains("scene.png: not a PNG, JPEG, Radiance HDR, PFM or OpenEXR file"));
  CHECK_THAT(refusal("/dev/zero"), Catch::Contains("not a PNG"));
  // An OpenEXR file, in a program that has not enabled glint's EXR library (this one).
  write_text(dir / "sky.exr", std::string("\x76\x2f\x31\x01\x02\x00\x00\x00", 8) + "more");
  CHECK_THAT(refusal(dir / "sky.exr"),
             Catch::Contains("sky.exr: an OpenEXR file, which this program does not read") &&
                 Catch::Contains("convert it to PFM or Radiance HDR"));
  write_text(dir / "empty.png", "");
  CHECK_THAT(refusal(dir / "empty.png"), Catch::Contains("not a PNG"));

  // A PNG cut short after its header, and one whose header claims a width beyond the limits.
  std::vector<unsigned char> rgb(64 * 64 * 3, 90);
  write_png_bytes(dir / "whole.png", 64, 64, rgb);
  const std::string whole = read_bytes(dir / "whole.png");
  write_text(dir / "cut.png", whole.substr(0, 60));
  CHECK_THAT(refusal(dir / "cut.png"), Catch::Contains("cut.png: cannot decode the image"));
  std::string wide = whole;
  // IHDR's width, big-endian, at bytes 16-19: 40000 pixels.
  wide[16] = 0;
  wide[17] = 0;
  wide[18] = char(40000 >> 8);
  wide[19] = char(40000 & 0xff);
  write_text(dir / "wide.png", wide);
  CHECK_THAT(refusal(dir / "wide.png"),
             Catch::Contains("wide.png: 40000x64 pixels, beyond glint's limits"));

  // A PFM with a texel that is not a number.
  glint::Film film(2, 1);
  film.at(1, 0) = Color(0.0f, NAN, 0.0f);
  glint::write_pfm(film, dir / "nan.pfm");
  CHECK_THAT(refusal(dir / "nan.pfm"), Catch::Contains("texel (1, 0) is not a finite"));
}

// ---------------------------------------------------------------------------------------------
// The scene file

std::string scene_error(const fs::path& scene) {
  try {
    (void)glint::read_scene_file(scene);
  } catch (const glint::SceneError& error) {
    return error.what();
  }
  FAIL("the scene was accepted: " << scene);
  return {};
}

TEST_CASE("texture=FILE reads the image from the scene file's directory, once for all spheres",
          "[texture][unit]") {
  const glint_test::ScratchDirectory dir("texture");
  fs::create_directories(dir / "maps");
  write_png_bytes(dir / "maps" / "ball.png", 2, 1, {255, 0, 0, 0, 0, 255});
  write_text(dir / "scene.txt",
             "sphere center=0,0,0 radius=1 texture=maps/ball.png\n"
             "sphere center=3,0,0 radius=1 texture=maps/ball.png texture_axis=1,0,0 "
             "texture_turn=30 color=0.5,0.5,0.5\n"
             "sphere center=6,0,0 radius=1\n");
  // From another working directory: the path is the scene file's, not the process's.
  const glint::SceneDescription scene = glint::read_scene_file(dir / "scene.txt");
  REQUIRE(scene.spheres.size() == 3);
  const glint::SphereDescription& first = scene.spheres[0];
  CHECK(first.shading == glint::ShadingKind::texture);
  REQUIRE(first.texture);
  CHECK(first.texture->name() == "maps/ball.png");
  CHECK(first.texture->at(0, 0) == Color(1.0f, 0.0f, 0.0f));
  CHECK(scene.spheres[1].texture == first.texture);  // read once
  CHECK(scene.spheres[1].texture_placement.axis == Vec3(1.0f, 0.0f, 0.0f));
  CHECK(scene.spheres[1].texture_placement.turn_degrees == 30.0f);
  CHECK(scene.spheres[2].texture == nullptr);

  // Written back with the name it was read with, and read again from the same directory.
  std::ostringstream text;
  glint::write_scene(text, scene);
  CHECK_THAT(text.str(), Catch::Contains(" texture=maps/ball.png\n") &&
                             Catch::Contains(" texture=maps/ball.png texture_axis=1,0,0 "
                                             "texture_turn=30\n"));
  write_text(dir / "again.txt", text.str());
  const glint::SceneDescription again = glint::read_scene_file(dir / "again.txt");
  CHECK(again.spheres[1].texture->texels() == first.texture->texels());
  CHECK(again.spheres[1].texture_placement.turn_degrees == 30.0f);
  CHECK(again.spheres[1].material.diffuse_color == Color(0.5f));

  // The scene builds, and shading finds each sphere's image by its index.
  const glint::Scene built = glint::Scene::build(scene);
  REQUIRE(built.sphere_texture(0) != nullptr);
  CHECK(&built.sphere_texture(0)->image() == first.texture.get());
  CHECK(built.sphere_texture(1)->north() == Vec3(1.0f, 0.0f, 0.0f));
  CHECK(built.sphere_texture(2) == nullptr);
}

TEST_CASE("the texture keys' mistakes are errors naming the line", "[texture][unit]") {
  const glint_test::ScratchDirectory dir("texture");
  write_png_bytes(dir / "ok.png", 1, 1, {1, 2, 3});
  const auto error_of = [&](const std::string& sphere) {
    write_text(dir / "s.txt", "image width=4 height=4\n" + sphere + "\n");
    return scene_error(dir / "s.txt");
  };
  CHECK_THAT(error_of("sphere center=0,0,0 radius=1 texture=nothing.png"),
             Catch::Contains("s.txt:2: error: texture 'nothing.png': cannot read") &&
                 Catch::Contains("No such file"));
  CHECK_THAT(error_of("sphere center=0,0,0 radius=1 shading=texture"),
             Catch::Contains(":2: error: shading=texture needs an image: texture=FILE"));
  CHECK_THAT(error_of("sphere center=0,0,0 radius=1 shading=checker texture=ok.png"),
             Catch::Contains(":2: error: a texture is shown by shading=texture, not "
                             "shading=checker"));
  CHECK_THAT(error_of("sphere center=0,0,0 radius=1 texture_turn=10"),
             Catch::Contains(":2: error: texture_axis and texture_turn place an image"));
  CHECK_THAT(error_of("sphere center=0,0,0 radius=1 texture=ok.png texture_axis=0,0,0"),
             Catch::Contains(":2: error: texture_axis must be a finite direction, not zero"));
  CHECK_THAT(error_of("sphere center=0,0,0 radius=1 texture=s.txt"),
             Catch::Contains(":2: error: texture 's.txt':") &&
                 Catch::Contains("not a PNG, JPEG, Radiance HDR, PFM or OpenEXR file"));
  // shading=texture with its image is the same as the image alone.
  write_text(dir / "both.txt", "sphere center=0,0,0 radius=1 shading=texture texture=ok.png\n");
  CHECK(glint::read_scene_file(dir / "both.txt").spheres[0].shading == glint::ShadingKind::texture);
}

}  // namespace texture_test
