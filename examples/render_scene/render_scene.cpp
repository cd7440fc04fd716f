// The smallest complete use of glint as a library: read a scene file, render it with a named
// variant, write the image.
//
//   glint-render-scene SCENE OUT.png [SPP]

#include <glint/glint.hpp>

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: glint-render-scene SCENE OUT.png [SPP]\n");
    return 2;
  }
  try {
    // Parsing checks every line; building checks the scene as a whole and makes the BVH.
    const glint::Scene scene = glint::Scene::build(glint::read_scene_file(argv[1]));
    glint::RenderSettings settings = glint::RenderSettings::from(scene);  // the file's `image`
    if (argc == 4) settings.samples_per_pixel = std::atoi(argv[3]);
    // Any Config works here: a named variant, or one with a policy swapped (with_fresnel<...>).
    const glint::RenderResult result =
        glint::Renderer<glint::variants::fast>::render(scene, settings);
    glint::write_png(result.film, argv[2]);  // 8-bit sRGB; write_pfm keeps linear radiance
    std::printf("%s: %dx%d, %d spp in %.2f s\n", argv[2], settings.width, settings.height,
                result.samples_per_pixel, result.stats.seconds);
  } catch (const glint::Error& error) {  // SceneError says FILE:LINE: error: ...
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  return 0;
}
