// A shading policy written outside the library: spheres marked `shading=custom` in the scene
// file get horizontal stripes; every other kind keeps glint's built-in meaning. The renderer
// variant is the report's with only the shading policy swapped.
//
//   glint-custom-shading SCENE OUT.png [SPP]

#include <glint/glint.hpp>

#include <charconv>
#include <cmath>
#include <iostream>
#include <string_view>

struct StripesShading {
  static bool supports(glint::ShadingKind) { return true; }

  static glint::Color color(glint::ShadingKind kind, glint::Color base,
                            const glint::ShadingPoint& at) {
    if (kind != glint::ShadingKind::custom) return glint::BuiltinShading::color(kind, base, at);
    // Ten bands from pole to pole, alternating the sphere's colour and a dark grey.
    const int band = static_cast<int>(std::floor((at.direction.y + 1.0f) * 5.0f));
    return band % 2 == 0 ? base : glint::Color(0.1f);
  }
};
static_assert(glint::SphereShading<StripesShading>);

using Striped = glint::variants::report::with_sphere_shading<StripesShading>;

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::cerr << "usage: glint-custom-shading SCENE OUT.png [SPP]\n";
    return 2;
  }
  try {
    const glint::Scene scene = glint::Scene::build(glint::read_scene_file(argv[1]));
    glint::RenderSettings settings = glint::RenderSettings::from(scene);
    if (argc == 4) {
      const std::string_view text = argv[3];
      const auto [end, error] =
          std::from_chars(text.data(), text.data() + text.size(), settings.samples_per_pixel);
      if (error != std::errc() || end != text.data() + text.size() ||
          settings.samples_per_pixel < 1) {
        std::cerr << "glint-custom-shading: SPP must be a positive integer\n";
        return 2;
      }
    }
    const glint::RenderResult result = glint::Renderer<Striped>::render(scene, settings);
    glint::write_png(result.film, argv[2]);
    std::cerr << "rendered " << argv[2] << " in " << result.stats.seconds << " s\n";
    return 0;
  } catch (const std::exception& error) {
    std::cerr << error.what() << "\n";
    return 1;
  }
}
