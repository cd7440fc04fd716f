// Renders a lit diffuse sphere from a scene built in code and checks the image is lit where the
// sphere faces the light, dark elsewhere, and written to disk.
#include <glint/glint.hpp>

#include <cstdio>
#include <filesystem>
#ifdef GLINT_CONSUMER_EXR
#include <glint/exr/exr_image.hpp>
#endif

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  glint::SceneDescription description;
  description.camera.position = {0.0f, 0.0f, 10.0f};
  glint::SphereDescription ball;
  ball.radius = 2.0f;
  description.spheres.push_back(ball);
  glint::PointLight light;
  light.position = {0.0f, 0.0f, 10.0f};
  light.intensity = 100.0f;
  description.lights.push_back(light);

  const glint::Scene scene = glint::Scene::build(description);
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.width = settings.height = 32;
  settings.samples_per_pixel = 4;
  const glint::RenderResult result =
      glint::Renderer<glint::variants::report>::render(scene, settings);
  // Facing the light head on at distance 8: radiance = I / (pi d^2) = 100 / (64 pi).
  const float centre = result.film.at(16, 16).x, corner = result.film.at(0, 0).x;
  const float expected = 100.0f / (64.0f * 3.14159265f);
  if (std::abs(centre - expected) > 0.02f * expected || corner != 0.0f) {
    std::fprintf(stderr, "unexpected radiance: centre %g (expected %g), corner %g\n", centre,
                 expected, corner);
    return 1;
  }
  glint::write_png(result.film, argv[1]);
#ifdef GLINT_CONSUMER_EXR
  const std::filesystem::path exr = std::filesystem::path(argv[1]).replace_extension(".exr");
  glint::write_exr(result.film, exr, {glint::ExrPixelType::float32, {{"consumer", 1}}});
  const glint::ExrImage back = glint::read_exr(exr);
  if (back.film.pixels() != result.film.pixels() || !back.find("consumer")) {
    std::fprintf(stderr, "the EXR read back differs from the film\n");
    return 1;
  }
#endif
  return std::filesystem::file_size(argv[1]) > 0 ? 0 : 1;
}
