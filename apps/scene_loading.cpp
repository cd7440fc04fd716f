// scene_loading.hpp's definitions.

#include "scene_loading.hpp"

#include <unordered_set>
#include <utility>

#include "command_line.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/scene/image_settings.hpp"
#include "load_progress.hpp"
#include "out_of_memory.hpp"

// GLINT_HAVE_EXR: the program links glint::exr (apps/CMakeLists.txt, when OpenEXR is found), and
// so reads OpenEXR textures and background images.
#ifdef GLINT_HAVE_EXR
#include "glint/exr/exr_image.hpp"
#endif

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

std::string scene_file_text(LoadProgress& loading, const std::string& file) {
  return with_memory_for(
      [&] { return "reading the scene " + file; },
      [&] { return glint::read_scene_file_text(file, loading.reader_callback()); });
}

std::uint64_t scene_text_hash(std::string_view text) {
  return glint::fnv1a(text.data(), text.size());
}

std::uint64_t scene_textures_hash(std::uint64_t hash, const glint::Scene& scene) {
  std::unordered_set<const glint::Texture*> seen;
  const auto add = [&](const glint::Texture& image) {
    if (!seen.insert(&image).second) return;
    const int size[2] = {image.width(), image.height()};
    hash = glint::fnv1a(size, sizeof size, hash);
    hash = glint::fnv1a(image.texels().data(), image.texels().size() * sizeof(glint::Color), hash);
  };
  for (const glint::SphereTexture& texture : scene.textures())
    add(texture.image());
  if (scene.environment().has_image()) add(scene.environment().image().image());
  return hash;
}

glint::Scene parse_and_build(LoadProgress& loading, std::string text, const std::string& source) {
#ifdef GLINT_HAVE_EXR
  glint::enable_exr_textures();
#endif
  const glint::SceneDescription description = with_memory_for(
      [&] { return "parsing the scene " + source + " (" + byte_size(double(text.size())) + ")"; },
      [&] { return glint::read_scene_text(text, source, loading.reader_callback()); });
  std::string().swap(text);
  loading.building(description.spheres.size());
  glint::Scene built = with_memory_for(
      [&] {
        return "building the scene " + source + " (" + std::to_string(description.spheres.size()) +
               " spheres)";
      },
      [&] { return glint::Scene::build(description); });
  loading.finished(built.sphere_count());
  return built;
}

LoadedScene load_scene(const std::string& file, bool report, bool hash) {
  LoadProgress loading(report, file);
  std::string text = scene_file_text(loading, file);
  const std::uint64_t text_hash = hash ? scene_text_hash(text) : 0;
  glint::Scene scene = parse_and_build(loading, std::move(text), file);
  const std::uint64_t scene_hash = hash ? scene_textures_hash(text_hash, scene) : 0;
  return {std::move(scene), scene_hash};
}

glint::RenderSettings render_settings(const Options& options, const glint::Scene& scene) {
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  if (options.spp) settings.samples_per_pixel = *options.spp;
  if (options.max_depth) settings.max_depth = *options.max_depth;
  if (options.width) settings.width = *options.width;
  if (options.height) settings.height = *options.height;
  if (options.threads) settings.threads = *options.threads;
  settings.seed = options.seed;
  if (const std::string problem = glint::image_settings_problem(settings); !problem.empty())
    throw UsageError{"the options with " + options.scene + "'s image settings: " + problem};
  return settings;
}
}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
