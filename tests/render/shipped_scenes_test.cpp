// Every scene shipped in scenes/*.scene (the report's figures) loads, builds and renders with
// the renderer variant its "# variant: NAME" line names (as scenes/render-all reads it), at a
// tiny size: a finite image, not all black, with no NaN or infinite samples.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/scene/scene.hpp"
#include "glint/variants.hpp"

namespace {

std::vector<std::filesystem::path> shipped_scenes() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(GLINT_SOURCE_DIR "/scenes"))
    if (entry.is_regular_file() && entry.path().extension() == ".scene")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// The variant named by the file's first "# variant: NAME" line, as scenes/render-all reads
/// it (whitespace removed); "report" when there is none.
std::string variant_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    std::size_t i = 0;
    if (line.empty() || line[0] != '#') continue;
    for (i = 1; i < line.size() && std::isspace(static_cast<unsigned char>(line[i])); ++i) {
    }
    if (line.compare(i, 8, "variant:") != 0) continue;
    std::string name;
    for (const char c : line.substr(i + 8))
      if (!std::isspace(static_cast<unsigned char>(c))) name += c;
    return name;
  }
  return "report";
}

struct TinyRender {
  bool finite = true;
  double sum = 0.0;
  std::uint64_t invalid_samples = 0;
};

template <typename Variant>
TinyRender render_tiny(const glint::Scene& scene) {
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.width = 16;
  settings.height = 16;
  settings.samples_per_pixel = 2;
  settings.max_depth = 3;
  settings.threads = 2;
  const glint::RenderResult result = glint::Renderer<Variant>::render(scene, settings);
  TinyRender out;
  out.invalid_samples = result.stats.invalid_samples;
  for (const glint::Color& c : result.film.pixels()) {
    for (int k = 0; k < 3; ++k) {
      out.finite = out.finite && std::isfinite(c[k]);
      out.sum += c[k];
    }
  }
  return out;
}

}  // namespace

TEST_CASE("every shipped scene renders with the variant it names", "[render][scenes]") {
  const std::vector<std::filesystem::path> files = shipped_scenes();
  REQUIRE(!files.empty());
  for (const std::filesystem::path& file : files) {
    const std::string variant = variant_of(file);
    INFO(file.filename().string() << " (variant " << variant << ")");
    const glint::Scene scene = glint::Scene::build(glint::read_scene_file(file));
    TinyRender image;
    const bool known = glint::variants::visit_by_name(
        variant, [&]<typename V>() { image = render_tiny<V>(scene); });
    if (!known) {
      FAIL_CHECK("unknown variant '" << variant << "'");
      continue;
    }
    CHECK(image.finite);
    CHECK(image.sum > 0.0);
    CHECK(image.invalid_samples == 0);
  }
}
