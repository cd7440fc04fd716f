// Summing a pixel's samples: in double, so that a constant converges to itself at any sample
// count and large finite samples give a finite mean; a mean beyond the float range is clamped
// to the largest float and counted, never written as infinity.

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "glint/image/pixel_sums.hpp"
#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"

namespace {

/// No sphere in view: every sample of every pixel is the background, whatever the antialiasing.
glint::Scene background_scene(glint::Color background) {
  glint::SceneDescription d;
  d.source = "accumulation";
  d.background = background;
  glint::SphereDescription behind;
  behind.center = {0.0f, 0.0f, 100.0f};  // behind the camera, which looks down -z from z = 55
  d.spheres.push_back(behind);
  return glint::Scene::build(d);
}

glint::RenderSettings settings_of(int width, int height, int spp) {
  glint::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.samples_per_pixel = spp;
  settings.max_depth = 2;
  settings.threads = 2;
  return settings;
}

}  // namespace

TEST_CASE("a constant background is its own mean at any sample count", "[accumulation]") {
  // 0.1f is no short binary fraction: a float running sum of it drifts (by about 1% at 2^20
  // samples), while its double sum of up to 2^29 terms is exact, and so is the mean.
  const glint::Color background(0.1f, 0.7f, 3.3f);
  const glint::Scene scene = background_scene(background);
  for (const int spp : {1, 3, 1000, 1 << 20}) {
    INFO(spp << " samples per pixel");
    const glint::RenderResult result =
        glint_test::render_by<glint::Renderer<glint::variants::fast>>(scene,
                                                                      settings_of(1, 1, spp));
    CHECK(result.film.at(0, 0) == background);
    CHECK(result.stats.invalid_samples == 0);
    CHECK(result.stats.clamped_pixels == 0);
  }
}

TEST_CASE("large finite samples give a finite mean", "[accumulation]") {
  // A float sum of 1000 samples of 1e36 overflows to infinity; their mean does not.
  const glint::Color background(1e36f, 3e38f, 0.0f);
  const glint::Scene scene = background_scene(background);
  const glint::RenderResult result =
      glint_test::render_by<glint::Renderer<glint::variants::report>>(scene,
                                                                      settings_of(3, 2, 1000));
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      CHECK(result.film.at(x, y) == background);
  CHECK(result.stats.invalid_samples == 0);
  CHECK(result.stats.clamped_pixels == 0);
}

TEST_CASE("a mean beyond the float range is clamped and counted", "[accumulation]") {
  const double largest = std::numeric_limits<float>::max();
  bool out_of_range = false;
  CHECK(glint::mean_color(glint::ColorSum(4.0 * largest, 1.0, 0.0), 4, out_of_range) ==
        glint::Color(std::numeric_limits<float>::max(), 0.25f, 0.0f));
  CHECK_FALSE(out_of_range);
  // Just above the largest float, where rounding to float would give infinity.
  const glint::Color clamped =
      glint::mean_color(glint::ColorSum(largest * (1.0 + 1e-9), -1e300, 2.0), 1, out_of_range);
  CHECK(out_of_range);
  CHECK(clamped ==
        glint::Color(std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(), 2.0f));

  // Through a render resumed from sums no render of finite samples makes (a forged checkpoint).
  const glint::Scene scene = background_scene(glint::Color(1.0f));
  const glint::RenderSettings settings = settings_of(3, 2, 2);  // passes end at 1 and 2
  glint::PixelSums sums(3, 2);
  sums.at(1, 1) = glint::ColorSum(1e300, 0.0, 0.0);
  sums.at(2, 0) = glint::ColorSum(0.0, 0.0, 1e40);
  const glint::RenderResult result =
      glint_test::render_by<glint::Renderer<glint::variants::report>>(
          scene, settings, glint::RenderControl{}, {&sums, 1});
  CHECK(result.stats.clamped_pixels == 2);
  for (const glint::Color& pixel : result.film.pixels())
    CHECK((std::isfinite(pixel.x) && std::isfinite(pixel.y) && std::isfinite(pixel.z)));
  CHECK(result.film.at(1, 1).x == std::numeric_limits<float>::max());
  CHECK(result.film.at(0, 0) == glint::Color(0.5f));  // a forged zero, then one sample of 1
}
