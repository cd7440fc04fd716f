// Image textures rendered (ShadingKind::texture through BuiltinShading): an image of one colour
// renders as a sphere of that colour, bit for bit, with every renderer that supports textures
// (the others refuse the scene); and in a uniform white background, where a convex diffuse
// sphere returns exactly its albedo times the background, each quarter of an image appears where
// the map puts it, seen from the camera: its top left at the sphere's top left.

#include <catch2/catch.hpp>
#include <memory>
#include <string>
#include <vector>

#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"
#include "same_bits.hpp"

namespace texture_render_test {

using glint::Color;

/// A texture of `width` x `height` texels of colour `c`.
std::shared_ptr<const glint::Texture> flat(Color c, int width = 5, int height = 3) {
  return std::make_shared<const glint::Texture>(
      "flat", width, height, std::vector<Color>(std::size_t(width) * std::size_t(height), c));
}

template <typename R>
void check_flat_texture(const glint::SceneDescription& textured,
                        const glint::SceneDescription& coloured) {
  INFO(glint_test::renderer_name<R>());
  glint::RenderSettings settings = glint::RenderSettings::from(glint::Scene::build(coloured));
  settings.threads = 2;
  if (!R::Config::sphere_shading::supports(glint::ShadingKind::texture)) {
    CHECK_THROWS_AS(glint_test::render_by<R>(glint::Scene::build(textured), settings),
                    glint::UnsupportedSceneError);
    return;
  }
  const glint::RenderResult a = glint_test::render_by<R>(glint::Scene::build(textured), settings);
  const glint::RenderResult b = glint_test::render_by<R>(glint::Scene::build(coloured), settings);
  CHECK(a.stats.invalid_samples == 0);
  CHECK(glint_test::same_bits(a.film, b.film));
}

TEST_CASE("an image of one colour renders as a sphere of that colour, bit for bit",
          "[render][texture]") {
  // The room of the estimators' same-bits checks (black behind, which light tracing needs): its
  // floor and its half-mirror get an image.
  const glint::SceneDescription room = glint::read_scene_text(glint_test::kMixedRoom, "room");
  glint::SceneDescription textured = room, coloured = room;
  const Color floor_color(0.6f, 0.55f, 0.3f), ball_color(0.2f, 0.7f, 0.9f);
  for (const auto& [index, color] : {std::pair{0, floor_color}, std::pair{2, ball_color}}) {
    glint::SphereDescription& t = textured.spheres[std::size_t(index)];
    t.shading = glint::ShadingKind::texture;
    t.texture = flat(color);
    t.texture_placement = {{0.3f, 1.0f, -0.2f}, 40.0f};
    t.material.diffuse_color = Color(1.0f);
    coloured.spheres[std::size_t(index)].material.diffuse_color = color;
  }
  [&]<typename... R>(std::tuple<R...>*) {
    (check_flat_texture<R>(textured, coloured), ...);
  }(static_cast<glint_test::CameraPathRenderers*>(nullptr));
  check_flat_texture<glint::Renderer<glint::variants::light_tracing>>(textured, coloured);
  check_flat_texture<glint::Renderer<glint::variants::bidirectional>>(textured, coloured);
  check_flat_texture<glint::Renderer<glint::variants::vcm>>(textured, coloured);
}

template <typename R>
void check_quarters() {
  INFO(glint_test::renderer_name<R>());
  // Quarters of red, green, blue and grey; white light from every direction; the ball, seen
  // from +z, fills the middle of a 64x64 image. A path meets the ball once and leaves it for the
  // background, so a pixel is the image's colour where its rays meet the ball (times 1).
  const Color top_left(0.9f, 0.1f, 0.1f), top_right(0.1f, 0.8f, 0.1f),
      bottom_left(0.1f, 0.1f, 0.7f), bottom_right(0.5f);
  constexpr int kWidth = 64, kHeight = 32;
  std::vector<Color> texels(std::size_t(kWidth) * kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      texels[std::size_t(y) * kWidth + std::size_t(x)] =
          y < kHeight / 2 ? (x < kWidth / 2 ? top_left : top_right)
                          : (x < kWidth / 2 ? bottom_left : bottom_right);
  glint::SceneDescription scene = glint::read_scene_text(
      "image width=64 height=64 spp=16 max_depth=4\n"
      "camera position=0,0,55 look_at=0,0,0 fov=60\n"
      "background color=1,1,1\n"
      "sphere center=0,0,0 radius=20\n",
      "quarters");
  scene.spheres[0].shading = glint::ShadingKind::texture;
  scene.spheres[0].texture =
      std::make_shared<const glint::Texture>("quarters", kWidth, kHeight, std::move(texels));
  const glint::Scene built = glint::Scene::build(scene);
  glint::RenderSettings settings = glint::RenderSettings::from(built);
  settings.threads = 2;
  const glint::RenderResult result = glint_test::render_by<R>(built, settings);
  // Pixels ten from the middle each way: about 30 degrees from the view axis on the ball, far
  // from the quarters' edges (the image's middle column and row) and from the pixel filter's.
  const auto check = [&](int x, int y, Color expected) {
    const Color got = result.film.at(x, y);
    INFO("pixel (" << x << ", " << y << "): " << got.r << ", " << got.g << ", " << got.b
                   << "; expected " << expected.r << ", " << expected.g << ", " << expected.b);
    CHECK(glm::length(got - expected) < 1e-5f);
  };
  check(22, 22, top_left);
  check(42, 22, top_right);
  check(22, 42, bottom_left);
  check(42, 42, bottom_right);
}

TEST_CASE("an image lies on the sphere as the map puts it, seen from the camera",
          "[render][texture]") {
  check_quarters<glint::Renderer<glint::variants::fast>>();
  check_quarters<glint::WavefrontRenderer<glint::variants::fast>>();
}

}  // namespace texture_render_test
