// Every scene shipped in scenes/*.scene (the report's figures) loads, builds and renders with
// the renderer variant its "# variant: NAME" line names (as scenes/render-all reads it), at a
// tiny size: a finite image, not all black, with no NaN or infinite samples. And every one of
// them has a test of a property it must have (shipped_figures_*_test.cpp), tagged with its
// name: a new shipped scene makes this fail until it gets one.

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "shipped_scenes.hpp"

TEST_CASE("every shipped scene renders with the variant it names", "[render][scenes]") {
  const std::vector<std::filesystem::path> files = glint::test::shipped_scene_files();
  REQUIRE(!files.empty());
  for (const std::filesystem::path& file : files) {
    const std::string variant = glint::test::variant_of(file);
    INFO(file.filename().string() << " (variant " << variant << ")");
    const glint::SceneDescription description = glint::read_scene_file(file);
    const glint::RenderSettings settings = glint::test::small_settings(description, 16, 2, 3);
    // render_with also checks that no sample was invalid.
    const glint::Film film = glint::test::render_with(variant, description, settings);
    bool finite = true;
    double sum = 0.0;
    for (const glint::Color& c : film.pixels())
      for (int k = 0; k < 3; ++k) {
        finite = finite && std::isfinite(c[k]);
        sum += c[k];
      }
    CHECK(finite);
    CHECK(sum > 0.0);
  }
}

TEST_CASE("every shipped scene has a property test", "[render][scenes]") {
  // The property tests carry the tags [property] and [NAME] for scenes/NAME.scene.
  std::set<std::string> tagged;
  for (const Catch::TestCase& test : Catch::getRegistryHub().getTestCaseRegistry().getAllTests())
    if (test.tags.end() != std::find(test.tags.begin(), test.tags.end(), "property"))
      tagged.insert(test.tags.begin(), test.tags.end());
  const std::vector<std::filesystem::path> files = glint::test::shipped_scene_files();
  REQUIRE(files.size() >= 17);
  for (const std::filesystem::path& file : files) {
    const std::string name = file.stem().string();
    INFO("scenes/" << name << ".scene has no TEST_CASE tagged [property][" << name
                   << "] (see tests/render/shipped_figures_*_test.cpp)");
    CHECK(tagged.count(name) == 1);
  }
}
