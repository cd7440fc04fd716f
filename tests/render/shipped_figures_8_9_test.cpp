// Properties of the report's random scenes, figures 8 and 9 (scenes/fig8*.scene and
// fig9*.scene): glint-random-scene output, a box of coloured walls with 15 or 40 spheres of
// glass, mirror or diffuse colour, and two lights. Checked against the scene file's own
// geometry through the independent SceneModel (see shipped_scenes.hpp):
//  - direct light only (depth 0): every pixel is the expectation of the point-light formula
//    from both lights, with hard shadows cast by every sphere, under the pixel filter;
//  - one bounce: every pixel whose ray first meets a mirror or glass shows what the mirror
//    reflects, or the Fresnel share of what the glass reflects, lit directly;
//  - with interreflection: the surfaces seen in the mirrors and through the glass have their
//    hues.

#include <catch2/catch.hpp>

#include "shipped_scenes.hpp"

using namespace glint::test;
using glint::Film;
using glint::RenderSettings;

namespace {

void check_random_scene(const std::string& name) {
  const ShippedScene scene = load_shipped_scene(name);
  const auto& d = scene.description;
  REQUIRE(d.lights.size() == 2);
  const SceneModel model(d);
  const VariantModel variant = variant_model(scene.variant);

  SECTION("direct light from both lights with hard shadows") {
    const RenderSettings settings = small_settings(d, 48, 16, 0);
    const Film film = render_with(scene.variant, d, settings);
    check_matches_model(film, model, settings, variant, settings.width * settings.height);
  }
  SECTION("one bounce off the mirrors and the glass") {
    const RenderSettings settings = small_settings(d, 64, 16, 1);
    const Film film = render_with(scene.variant, d, settings);
    const auto specular = [&](int x, int y) {
      const int s = sphere_seen(model, settings, variant, x, y, false);
      if (s < 0) return false;
      const glint::Material& m = d.spheres[std::size_t(s)].material;
      return m.diffuse == 0.0f && (m.mirror > 0.0f || m.transparent > 0.0f);
    };
    check_matches_model(film, model, settings, variant, 100, specular);
  }
  SECTION("with interreflection, what the mirrors and glass show has its hue") {
    const RenderSettings settings = small_settings(d, 128, 16, 6);
    const Film film = render_with(scene.variant, d, settings);
    CHECK(check_hues(hue_groups(model, film, settings, variant, 1), d) >= 3);
  }
}

}  // namespace

TEST_CASE("fig8a-random-15: direct light, one bounce and hues match the geometry",
          "[render][scenes][property][fig8a-random-15]") {
  check_random_scene("fig8a-random-15");
}

TEST_CASE("fig8b-random-15: direct light, one bounce and hues match the geometry",
          "[render][scenes][property][fig8b-random-15]") {
  check_random_scene("fig8b-random-15");
}

TEST_CASE("fig9a-random-40: direct light, one bounce and hues match the geometry",
          "[render][scenes][property][fig9a-random-40]") {
  check_random_scene("fig9a-random-40");
}

TEST_CASE("fig9b-random-40: direct light, one bounce and hues match the geometry",
          "[render][scenes][property][fig9b-random-40]") {
  check_random_scene("fig9b-random-40");
}
