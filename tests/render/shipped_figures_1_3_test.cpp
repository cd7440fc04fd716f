// Properties of the report's figures 1 to 3 (scenes/fig1*.scene to fig3*.scene), each checked
// on a small render against the scene file's own geometry, lights and camera through the
// independent SceneModel (see shipped_scenes.hpp).

#include <catch2/catch.hpp>

#include "shipped_scenes.hpp"

using namespace glint::test;
using glint::Film;
using glint::RenderSettings;

TEST_CASE("fig1a-diffuse: direct light by the point-light formula, dim where turned away",
          "[render][scenes][property][fig1a-diffuse]") {
  const ShippedScene scene = load_shipped_scene("fig1a-diffuse");
  const auto& d = scene.description;
  REQUIRE(d.image.max_depth == 0);  // direct light only: the model knows every pixel
  const RenderSettings settings = small_settings(d, 96, 16, d.image.max_depth);
  const Film film = render_with(scene.variant, d, settings);
  const SceneModel model(d);
  const VariantModel variant = variant_model(scene.variant);

  // Every pixel: the expectation of the point-light formula with hard shadows under the
  // pixel filter.
  const std::vector<PixelExpectation> expected = expected_image(model, settings, variant);
  check_agreement(compare_with_model(film, expected, settings.samples_per_pixel),
                  settings.width * settings.height);

  // The white sphere (pixels wholly on it): bright where it faces the light, dim where it
  // turns away (radiance goes with the cosine to the light; distances differ by < 20%).
  const int sphere = small_sphere(d);
  double facing_sum = 0.0, turned_sum = 0.0;
  int facing = 0, turned = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      if (sphere_seen(model, settings, variant, x, y, true) != sphere) continue;
      const std::optional<Hit> hit = centre_hit(model, settings, x, y);
      const double cosine =
          glm::dot(glm::normalize(to_double(d.lights[0].position) - hit->point), hit->outward);
      const glint::Color c = film.at(x, y);
      if (cosine > 0.8) {
        ++facing;
        facing_sum += c.x + c.y + c.z;
      } else if (cosine < 0.4) {
        ++turned;
        turned_sum += c.x + c.y + c.z;
      }
    }
  INFO(facing << " pixels facing the light (cos > 0.8), mean " << facing_sum / facing << "; "
              << turned << " turned away (cos < 0.4), mean " << turned_sum / turned);
  REQUIRE(facing >= 20);
  REQUIRE(turned >= 10);
  CHECK(facing_sum / facing > 2.0 * turned_sum / turned);
}

TEST_CASE("fig1b-mirror: the mirror shows the walls it faces",
          "[render][scenes][property][fig1b-mirror]") {
  const ShippedScene scene = load_shipped_scene("fig1b-mirror");
  const auto& d = scene.description;
  const SceneModel model(d);
  const VariantModel variant = variant_model(scene.variant);
  const int mirror = small_sphere(d);
  REQUIRE(d.spheres[std::size_t(mirror)].material.mirror == 1.0f);

  SECTION("at one bounce, each mirror pixel is the mirror colour times the wall it reflects") {
    const RenderSettings settings = small_settings(d, 96, 16, 1);
    const Film film = render_with(scene.variant, d, settings);
    const auto on_mirror = [&](int x, int y) {
      return sphere_seen(model, settings, variant, x, y, false) == mirror;
    };
    check_matches_model(film, model, settings, variant, 500, on_mirror);
  }
  SECTION("with interreflection, the mirror has the hue of each wall it reflects") {
    const RenderSettings settings = small_settings(d, 128, 16, 4);
    const Film film = render_with(scene.variant, d, settings);
    CHECK(check_hues(hue_groups(model, film, settings, variant, 1), d) >= 5);
  }
}

TEST_CASE("fig1c-transparent: the glass shows the room upside down",
          "[render][scenes][property][fig1c-transparent]") {
  const ShippedScene scene = load_shipped_scene("fig1c-transparent");
  const auto& d = scene.description;
  const SceneModel model(d);
  const VariantModel variant = variant_model(scene.variant);
  const int glass = small_sphere(d);
  REQUIRE(d.spheres[std::size_t(glass)].material.transparent == 1.0f);
  const RenderSettings settings = small_settings(d, 128, 16, 4);
  const Pinhole camera(d.camera, settings.width, settings.height);

  // Geometry: through the upper half of the glass the refracted rays reach the floor.
  const Vec3d center = to_double(d.spheres[std::size_t(glass)].center);
  const int floor = 2;
  REQUIRE(d.spheres[floor].center.y < -1000.0f);
  int floor_above = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const std::optional<Hit> hit = centre_hit(model, settings, x, y);
      const std::optional<SeenSurface> seen =
          model.seen_surface(camera.eye(), camera.direction(x + 0.5, y + 0.5));
      if (hit && hit->sphere == glass && hit->point.y > center.y + 2.0 && seen &&
          seen->sphere == floor)
        ++floor_above;
    }
  INFO("the floor is seen through " << floor_above << " pixels of the upper half");
  REQUIRE(floor_above >= 100);

  // The render: the pixels showing the floor (blue) and those showing the back wall (green)
  // differ in hue as the two walls do.
  const Film film = render_with(scene.variant, d, settings);
  CHECK(check_hues(hue_groups(model, film, settings, variant, 2), d) >= 2);
}

namespace {

/// Per-pixel differences whose expectation is zero, pixels being independent: per channel,
/// their sum over the root of the sum of their squares is a z-score.
struct ZeroMean {
  Vec3d sum{0.0}, squares{0.0};
  int pixels = 0;
  void add(const Vec3d& difference) {
    sum += difference;
    squares += difference * difference;
    ++pixels;
  }
  Vec3d z() const { return sum / glm::sqrt(squares); }
};

void check_zero_mean(const ZeroMean& m, int min_pixels) {
  const Vec3d z = m.z();
  INFO(m.pixels << " pixels; z = (" << z.x << ", " << z.y << ", " << z.z << ")");
  REQUIRE(m.pixels >= min_pixels);
  CHECK(std::fabs(z.x) < 5.0);
  CHECK(std::fabs(z.y) < 5.0);
  CHECK(std::fabs(z.z) < 5.0);
}

}  // namespace

TEST_CASE("fig2-weird-material: each lobe adds its coefficient's share",
          "[render][scenes][property][fig2-weird-material]") {
  // The weird sphere's pixels (their whole footprint on it) are checked lobe by lobe, each
  // in expectation (a z-score over the sphere), with the renders compared sharing a seed.
  const ShippedScene scene = load_shipped_scene("fig2-weird-material");
  const auto& d = scene.description;
  const int weird = small_sphere(d);
  const glint::Material m = d.spheres[std::size_t(weird)].material;
  REQUIRE(m.diffuse > 0.0f);
  REQUIRE(m.mirror > 0.0f);
  REQUIRE(m.transparent > 0.0f);
  REQUIRE(m.transparent < 1.0f);  // not a Fresnel glass
  const SceneModel model(d);
  const VariantModel variant = variant_model(scene.variant);
  const auto with_material = [&](const glint::Material& material) {
    glint::SceneDescription changed = d;
    changed.spheres[std::size_t(weird)].material = material;
    return changed;
  };

  SECTION("one bounce: the diffuse lobe's share of a diffuse sphere, the mirror's of a mirror") {
    // The refracted third adds nothing at one bounce: its light reaches only the inside of
    // the sphere, where no light shines (shadow rays from there cross the sphere). The pure
    // diffuse sphere is rendered (its bounce is random); the pure mirror is exactly what the
    // model predicts, its colour times the direct light on the wall it reflects.
    const RenderSettings settings = small_settings(d, 64, 16, 1);
    const auto on_sphere = [&](int x, int y) {
      return sphere_seen(model, settings, variant, x, y, true) == weird;
    };
    glint::Material diffuse;
    diffuse.diffuse_color = m.diffuse_color;
    glint::Material mirror;
    mirror.diffuse = 0.0f;
    mirror.mirror = 1.0f;
    mirror.mirror_color = m.mirror_color;
    const Film w = render_with(scene.variant, d, settings);
    const Film a = render_with(scene.variant, with_material(diffuse), settings);
    const std::vector<PixelExpectation> b =
        expected_image(SceneModel(with_material(mirror)), settings, variant, on_sphere);
    ZeroMean differences;
    for (int y = 0; y < settings.height; ++y)
      for (int x = 0; x < settings.width; ++x)
        if (on_sphere(x, y))
          differences.add(to_double(w.at(x, y)) - double(m.diffuse) * to_double(a.at(x, y)) -
                          double(m.mirror) * b[std::size_t(y * settings.width + x)].mean);
    check_zero_mean(differences, 100);
  }
  SECTION("two bounces: the refracted lobe adds its share, twice, of the room behind") {
    // Without its refracted lobe the sphere looks the same except for the light that crosses
    // it: in at the first hit, out at the second (the refracted lobe's share and colour
    // twice), to the wall it then reaches, lit directly. A sphere hit after a bounce cannot
    // pass light through it within two bounces.
    const RenderSettings settings = small_settings(d, 64, 16, 2);
    const auto on_sphere = [&](int x, int y) {
      return sphere_seen(model, settings, variant, x, y, true) == weird;
    };
    glint::Material opaque = m;
    opaque.transparent = 0.0f;
    glint::Material clear;
    clear.diffuse = 0.0f;
    clear.transparent = m.transparent;
    clear.transparent_color = m.transparent_color;
    clear.ior = m.ior;
    const Film w = render_with(scene.variant, d, settings);
    const Film a = render_with(scene.variant, with_material(opaque), settings);
    const std::vector<PixelExpectation> through =
        expected_image(SceneModel(with_material(clear)), settings, variant, on_sphere);
    ZeroMean differences;
    Vec3d added(0.0);
    for (int y = 0; y < settings.height; ++y)
      for (int x = 0; x < settings.width; ++x)
        if (on_sphere(x, y)) {
          const Vec3d t = through[std::size_t(y * settings.width + x)].mean;
          differences.add(to_double(w.at(x, y)) - to_double(a.at(x, y)) - t);
          added += t;
        }
    INFO("the model's refracted light: (" << added.x << ", " << added.y << ", " << added.z << ")");
    CHECK(added.x > 10.0 * added.y);  // the lobe's colour, twice: red
    check_zero_mean(differences, 100);
  }
}

TEST_CASE("fig3a-diffusion: interreflection lights the sphere beyond the direct light",
          "[render][scenes][property][fig3a-diffusion]") {
  const ShippedScene scene = load_shipped_scene("fig3a-diffusion");
  const auto& d = scene.description;
  REQUIRE(d.image.max_depth >= 2);
  const RenderSettings settings = small_settings(d, 64, 32, d.image.max_depth);
  const Film film = render_with(scene.variant, d, settings);
  const SceneModel model(d);
  const VariantModel variant = variant_model(scene.variant);
  RenderSettings direct_only = settings;
  direct_only.max_depth = 0;
  const std::vector<PixelExpectation> direct = expected_image(model, direct_only, variant);

  // Over the white sphere, the image exceeds the direct light (figure 1a's image); on its
  // bottom, which faces the floor, what it adds has the floor's blue hue (the nearest of the
  // six walls' hues).
  const int sphere = small_sphere(d);
  std::vector<double> added;
  Vec3d bottom(0.0);
  int bottom_pixels = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      if (sphere_seen(model, settings, variant, x, y, true) != sphere) continue;
      const Vec3d indirect =
          to_double(film.at(x, y)) - direct[std::size_t(y * settings.width + x)].mean;
      added.push_back(indirect.x + indirect.y + indirect.z);
      if (centre_hit(model, settings, x, y)->outward.y < -0.5) {
        bottom += indirect;
        ++bottom_pixels;
      }
    }
  REQUIRE(added.size() >= 100);
  REQUIRE(bottom_pixels >= 5);
  double mean = 0.0, variance = 0.0;
  for (const double v : added)
    mean += v / double(added.size());
  for (const double v : added)
    variance += (v - mean) * (v - mean) / double(added.size() - 1);
  const double t = mean / std::sqrt(variance / double(added.size()));
  INFO(added.size() << " pixels add " << mean << " on average, t = " << t);
  CHECK(t > 5.0);

  const int floor = 2;
  REQUIRE(d.spheres[floor].center.y < -1000.0f);
  int nearest = -1;
  for (int i = 0; i < 6; ++i)
    if (nearest < 0 ||
        chroma_distance(bottom, to_double(d.spheres[std::size_t(i)].material.diffuse_color)) <
            chroma_distance(bottom,
                            to_double(d.spheres[std::size_t(nearest)].material.diffuse_color)))
      nearest = i;
  INFO("the bottom's added light (" << bottom.x << ", " << bottom.y << ", " << bottom.z
                                    << ") is nearest in hue to wall " << nearest);
  CHECK(nearest == floor);
}

TEST_CASE("fig3b-diffusion-mirror-glass: the mirror and the glass show the room",
          "[render][scenes][property][fig3b-diffusion-mirror-glass]") {
  const ShippedScene scene = load_shipped_scene("fig3b-diffusion-mirror-glass");
  const auto& d = scene.description;
  const SceneModel model(d);
  const VariantModel variant = variant_model(scene.variant);
  const int mirror = small_sphere(d, 0), glass = small_sphere(d, 2);
  REQUIRE(d.spheres[std::size_t(mirror)].material.mirror == 1.0f);
  REQUIRE(d.spheres[std::size_t(glass)].material.transparent == 1.0f);

  SECTION("at one bounce: the mirror reflects the room, the glass its Fresnel share of it") {
    const RenderSettings settings = small_settings(d, 96, 16, 1);
    const Film film = render_with(scene.variant, d, settings);
    const auto specular = [&](int x, int y) {
      const int s = sphere_seen(model, settings, variant, x, y, false);
      return s == mirror || s == glass;
    };
    check_matches_model(film, model, settings, variant, 500, specular);
  }
  SECTION("with interreflection, each surface seen in them has its hue") {
    const RenderSettings settings = small_settings(d, 128, 16, 6);
    const Film film = render_with(scene.variant, d, settings);
    CHECK(check_hues(hue_groups(model, film, settings, variant, 1), d) >= 6);
  }
}
