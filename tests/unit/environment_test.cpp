// The environment image and its light, against values worked out here: the piecewise-constant
// tables (densities that integrate to one, draws distributed as they say by chi-square, bins of
// weight zero never drawn); the image's layout, the one glint's equirectangular camera films
// (known directions, and the camera's own film position for random directions); a density that
// integrates to one over the sphere, is positive wherever light comes from, and that sample()'s
// directions follow by chi-square; the irradiance of an image on a plane estimated by its
// samples against a quadrature of its radiance in double; the light paths entering through the
// bounding sphere's disc, carrying the power; the same bits at every width; the background keys
// of the scene format, their errors and their round trip through the writer.
//
// Each chi-square test rejects a correct density with probability about 1e-6 (statistics.hpp);
// means are held to five standard errors (6e-7); with the few dozen checks here the file's
// false-alarm rate is below 1e-4. A table with 5% of one bin's mass moved is shown rejected.

#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "../support/scratch_directory.hpp"
#include "direction_cells.hpp"
#include "glint/error.hpp"
#include "glint/image/film.hpp"
#include "glint/image/texture.hpp"
#include "glint/io/image_writer.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/io/scene_writer.hpp"
#include "glint/math/piecewise_constant.hpp"
#include "glint/math/random.hpp"
#include "glint/math/wide.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/lights/environment_light.hpp"
#include "glint/scene/environment.hpp"
#include "glint/scene/scene.hpp"
#include "statistics.hpp"

namespace environment_test {

namespace fs = std::filesystem;
using glint::Color;
using glint::Vec2;
using glint::Vec3;

constexpr double kPi = std::numbers::pi;

Vec2 next_2d(glint::Pcg32& rng) {
  const float x = rng.next_float();
  return {x, rng.next_float()};
}

/// An image of `width` x `height` texels from `texel(x, y)`.
template <typename Texel>
std::shared_ptr<const glint::Texture> image(int width, int height, Texel&& texel) {
  std::vector<Color> texels;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      texels.push_back(texel(x, y));
  return std::make_shared<const glint::Texture>("test", width, height, std::move(texels));
}

/// A sky: dim blue, a band of zeros near the bottom, and a small bright sun.
std::shared_ptr<const glint::Texture> sky() {
  return image(32, 16, [](int x, int y) {
    if (y >= 12 && y < 14) return Color(0.0f);
    if (x == 20 && y == 4) return Color(400.0f, 380.0f, 300.0f);
    return Color(0.2f, 0.3f, 0.5f + 0.02f * float(x));
  });
}

/// A uniform random unit vector.
Vec3 random_direction(glint::Pcg32& rng) {
  const double z = 2.0 * rng.next_float() - 1.0, phi = 2.0 * kPi * rng.next_float();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return glm::normalize(Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
}

/// The integral of `f` over the sphere of directions, by the midpoint rule in (cos theta, phi)
/// on an n x 2n grid, in double.
template <typename Function>
double sphere_integral(Function&& f, int n) {
  double sum = 0.0;
  const double d_cos = 2.0 / n, d_phi = kPi / n;
  for (int i = 0; i < n; ++i) {
    const double cosine = -1.0 + (i + 0.5) * d_cos, sine = std::sqrt(1.0 - cosine * cosine);
    for (int j = 0; j < 2 * n; ++j) {
      const double phi = (j + 0.5) * d_phi;
      sum += f(Vec3(float(sine * std::cos(phi)), float(sine * std::sin(phi)), float(cosine)));
    }
  }
  return sum * d_cos * d_phi;
}

TEST_CASE("a piecewise-constant table's density integrates to one, and its draws follow it",
          "[environment][statistical]") {
  glint::Pcg32 rng(3u, 7u);
  std::vector<double> weights(40);
  for (std::size_t i = 0; i < weights.size(); ++i)
    weights[i] = i % 7 == 3 ? 0.0 : double(rng.next_float()) * (i == 11 ? 50.0 : 1.0);
  const glint::PiecewiseConstant1D table(weights);
  double total = 0.0, sum = 0.0;
  for (const double w : weights)
    sum += w;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    CHECK(table.bin_pdf(i) == Approx(weights[i] * double(weights.size()) / sum).epsilon(1e-6));
    total += table.bin_pdf(i) / double(weights.size());
  }
  CHECK(total == Approx(1.0).epsilon(1e-6));

  const int n = 400000;
  const auto draw_counts = [&](const glint::PiecewiseConstant1D& drawn) {
    std::vector<double> observed(weights.size(), 0.0);
    glint::Pcg32 draws(11u, 2u);
    for (int i = 0; i < n; ++i) {
      const glint::PiecewiseConstant1D::Sample s = drawn.sample(draws.next_float());
      REQUIRE(s.x >= 0.0f);
      REQUIRE(s.x < 1.0f);
      REQUIRE(drawn.bin_of(s.x) == s.bin);
      REQUIRE(s.pdf == drawn.pdf(s.x));
      REQUIRE(s.pdf > 0.0f);  // a bin of weight zero is never drawn
      ++observed[s.bin];
    }
    return observed;
  };
  std::vector<double> expected(weights.size());
  for (std::size_t i = 0; i < weights.size(); ++i)
    expected[i] = n * weights[i] / sum;
  CHECK_FALSE(glint::test::chi_square_pooled(draw_counts(table), expected).rejected());
  // A table with 5% of bin 11's mass moved to bin 12 is told apart.
  std::vector<double> moved = weights;
  moved[12] += 0.05 * moved[11];
  moved[11] *= 0.95;
  CHECK(glint::test::chi_square_pooled(draw_counts(glint::PiecewiseConstant1D(moved)), expected)
            .rejected());

  // A table of zeros is drawn uniformly.
  const std::vector<double> zeros(5, 0.0);
  const glint::PiecewiseConstant1D flat(zeros);
  CHECK(flat.pdf(0.3f) == 1.0f);
  CHECK(flat.sample(0.5f).x == Approx(0.5f));
}

TEST_CASE("a 2D table draws cells in proportion to their weights, with the density it gives",
          "[environment][statistical]") {
  const int width = 6, height = 5;
  glint::Pcg32 rng(9u, 1u);
  std::vector<double> weights(std::size_t(width * height));
  double sum = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    // Row 2 all zero; some zeros elsewhere.
    weights[i] = (i / width == 2 || i % 5 == 1) ? 0.0 : double(rng.next_float());
    sum += weights[i];
  }
  const glint::PiecewiseConstant2D table(weights, width, height);
  const int n = 300000;
  std::vector<double> observed(weights.size(), 0.0), expected(weights.size());
  glint::Pcg32 draws(4u, 4u);
  for (int i = 0; i < n; ++i) {
    const glint::PiecewiseConstant2D::Sample s = table.sample(next_2d(draws));
    const auto x = std::size_t(s.uv.x * width), y = std::size_t(s.uv.y * height);
    const std::size_t cell = y * width + x;
    REQUIRE(weights[cell] > 0.0);
    REQUIRE(s.pdf == table.pdf(s.uv));
    REQUIRE(s.pdf == Approx(weights[cell] * width * height / sum).epsilon(1e-5));
    ++observed[cell];
  }
  for (std::size_t i = 0; i < weights.size(); ++i)
    expected[i] = n * weights[i] / sum;
  CHECK_FALSE(glint::test::chi_square_pooled(observed, expected).rejected());
}

TEST_CASE("the environment's image lies as glint's equirectangular camera films it",
          "[environment][unit]") {
  const glint::Environment environment(sky(), glint::TexturePlacement{}, 1.0f);
  // Seen from inside, facing +z with up +y: +z is the middle, +y the top row, and the right
  // (forward x up = -x) is further along u.
  const auto uv = [&](const Vec3& d) { return environment.uv(d); };
  CHECK(uv(Vec3(0.0f, 0.0f, 1.0f)).x == Approx(0.5f));
  CHECK(uv(Vec3(0.0f, 0.0f, 1.0f)).y == Approx(0.5f));
  CHECK(uv(Vec3(-1.0f, 0.0f, 0.0f)).x == Approx(0.75f));
  CHECK(uv(Vec3(1.0f, 0.0f, 0.0f)).x == Approx(0.25f));
  CHECK(uv(Vec3(0.0f, 1.0f, 0.0f)).y == Approx(0.0f).margin(1e-6));
  CHECK(uv(Vec3(0.0f, -1.0f, 0.0f)).y == Approx(1.0f));

  // A panorama camera at the origin looking along +z, up +y, puts a point in direction d at the
  // film position the image has d at.
  glint::CameraDescription camera;
  camera.position = Vec3(0.0f);
  camera.look_at = Vec3(0.0f, 0.0f, 1.0f);
  camera.up = Vec3(0.0f, 1.0f, 0.0f);
  camera.near = 1e-3f;
  camera.projection = glint::Projection::equirectangular;
  const int width = 64, height = 32;
  const glint::Camera panorama(camera, width, height);
  glint::Pcg32 rng(21u, 3u);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 d = random_direction(rng);
    const auto connection = panorama.connect(10.0f * d);
    REQUIRE(connection);
    const Vec2 at = uv(d);
    const float film_u = connection->film.x / float(width);
    // u wraps: compare on the circle.
    const float du = std::fabs(film_u - at.x);
    CHECK(std::min(du, 1.0f - du) < 1e-5f);
    CHECK(connection->film.y / float(height) == Approx(at.y).margin(1e-5));
    // direction() inverts uv().
    const Vec3 back = environment.direction(at);
    CHECK(glm::length(back - d) < 2e-5f);
  }

  // The placement: the image's top towards the axis, turned about it.
  const glint::Environment tilted(sky(), glint::TexturePlacement{Vec3(0.0f, 0.0f, 2.0f), 0.0f},
                                  1.0f);
  CHECK(tilted.uv(Vec3(0.0f, 0.0f, 1.0f)).y == Approx(0.0f).margin(1e-6));
  const glint::Environment turned(sky(), glint::TexturePlacement{Vec3(0.0f, 1.0f, 0.0f), 90.0f},
                                  1.0f);
  // Turned a quarter counterclockwise seen from above, the middle faces +x.
  CHECK(turned.uv(Vec3(1.0f, 0.0f, 0.0f)).x == Approx(0.5f));
}

TEST_CASE("an environment of one colour is that colour, times its scale, in every direction",
          "[environment][statistical]") {
  const Color color(0.3f, 1.7f, 0.05f);
  const glint::Environment environment(image(8, 4, [&](int, int) { return color; }),
                                       glint::TexturePlacement{Vec3(1.0f, 2.0f, 3.0f), 17.0f},
                                       2.0f);
  CHECK_FALSE(environment.is_black());
  CHECK(environment.mean_radiance() == Approx(2.0 * (0.3 + 1.7 + 0.05) / 3.0).epsilon(1e-6));
  glint::Pcg32 rng(2u, 8u);
  for (int i = 0; i < 500; ++i)
    REQUIRE(environment.radiance(random_direction(rng)) == 2.0f * color);
  // A constant environment and a black one. A colour's directions are drawn uniformly.
  const glint::Environment constant(color);
  CHECK(constant.radiance(Vec3(0.0f, 0.0f, 1.0f)) == color);
  CHECK(constant.find(Vec3(0.6f, 0.8f, 0.0f)).radiance == color);
  CHECK(constant.find(Vec3(0.6f, 0.8f, 0.0f)).pdf == Approx(1.0 / (4.0 * kPi)));
  CHECK(constant.pdf(Vec3(0.0f, -1.0f, 0.0f)) == Approx(1.0 / (4.0 * kPi)));
  struct Drawn {
    Vec3 direction;
    bool delta;
  };
  glint::Pcg32 draws(3u, 3u);
  CHECK_FALSE(glint::test::sampling_against_density(
                  [&] {
                    const glint::Environment::DirectionSample s = constant.sample(next_2d(draws));
                    REQUIRE(s.pdf == constant.pdf(s.direction));
                    return Drawn{s.direction, false};
                  },
                  [&](const Vec3& d) { return constant.pdf(d); }, 100000)
                  .rejected());
  CHECK(glint::Environment().is_black());
  CHECK(glint::Environment(image(2, 2, [](int, int) { return Color(0.0f); }),
                           glint::TexturePlacement{}, 1.0f)
            .is_black());
  CHECK(glint::Environment(sky(), glint::TexturePlacement{}, 0.0f).is_black());
}

TEST_CASE("the environment's density integrates to one and is positive wherever light comes from",
          "[environment][unit]") {
  const glint::Environment environment(
      sky(), glint::TexturePlacement{Vec3(0.3f, 1.0f, 0.2f), 40.0f}, 1.0f);
  const double integral =
      sphere_integral([&](const Vec3& d) { return double(environment.pdf(d)); }, 1024);
  CHECK(integral == Approx(1.0).epsilon(2e-3));
  glint::Pcg32 rng(5u, 5u);
  for (int i = 0; i < 100000; ++i) {
    const Vec3 d = random_direction(rng);
    const Color l = environment.radiance(d);
    if (l.r > 0.0f || l.g > 0.0f || l.b > 0.0f) REQUIRE(environment.pdf(d) > 0.0f);
    // find() is both at once.
    const glint::Environment::Found found = environment.find(d);
    REQUIRE(found.radiance == l);
    REQUIRE(found.pdf == environment.pdf(d));
  }
}

TEST_CASE("the environment's directions follow its density, and bring its irradiance",
          "[environment][statistical]") {
  const glint::Environment environment(
      sky(), glint::TexturePlacement{Vec3(0.3f, 1.0f, 0.2f), 40.0f}, 1.5f);
  const int n = 400000;
  glint::Pcg32 rng(13u, 1u);
  struct Drawn {
    Vec3 direction;
    bool delta;
  };
  const glint::test::ChiSquare chi = glint::test::sampling_against_density<32>(
      [&] {
        return Drawn{environment.sample(next_2d(rng)).direction, false};
      },
      [&](const Vec3& d) { return environment.pdf(d); }, n);
  INFO("chi-square " << chi.statistic << " with " << chi.degrees_of_freedom
                     << " degrees of freedom");
  CHECK_FALSE(chi.rejected());

  // Irradiance on planes facing three ways: sum of L cos / pdf over the samples against the
  // integral of L cos over the hemisphere in double.
  for (const Vec3 normal :
       {Vec3(0.0f, 1.0f, 0.0f), glm::normalize(Vec3(1.0f, 0.2f, -0.5f)), Vec3(0.0f, -1.0f, 0.0f)}) {
    glint::Pcg32 draws(17u, 9u);
    std::vector<double> values;
    const int m = 200000;
    for (int i = 0; i < m; ++i) {
      const glint::Environment::DirectionSample s = environment.sample(next_2d(draws));
      const double cosine = std::max(0.0f, glm::dot(s.direction, normal));
      values.push_back(s.pdf > 0.0f ? double(environment.radiance(s.direction).g) * cosine / s.pdf
                                    : 0.0);
    }
    const glint::test::Moments moments = glint::test::moments(values);
    const double standard_error = std::sqrt(moments.variance / m);
    const double exact = sphere_integral(
        [&](const Vec3& d) {
          return double(environment.radiance(d).g) * std::max(0.0, double(glm::dot(d, normal)));
        },
        2048);
    CHECK(std::fabs(moments.mean - exact) <= 5.0 * standard_error + 2e-3 * exact);
  }
}

TEST_CASE("the environment light's paths enter through the bounding sphere's disc with its power",
          "[environment][statistical]") {
  glint::SceneDescription description;
  description.spheres.push_back({});
  description.spheres[0].center = Vec3(1.0f, 2.0f, 3.0f);
  description.spheres[0].radius = 2.0f;
  // A floor: a wall, which the bounds leave out.
  description.spheres.push_back({});
  description.spheres[1].center = Vec3(0.0f, -100000.0f, 0.0f);
  description.spheres[1].radius = 1e5f;
  description.camera.position = Vec3(1.0f, 2.0f, -3.0f);
  description.camera.look_at = Vec3(1.0f, 2.0f, 3.0f);
  description.background_image = sky();
  const glint::Scene scene = glint::Scene::build(description);
  const glint::BoundingSphere& bounds = scene.bounds();
  // Holds the sphere and the camera.
  CHECK(glm::length(Vec3(1.0f, 2.0f, 3.0f) - bounds.center) + 2.0f <= bounds.radius);
  CHECK(glm::length(Vec3(1.0f, 2.0f, -3.0f) - bounds.center) <= bounds.radius);
  CHECK(bounds.radius < 10.0f);

  const glint::EnvironmentLight light(scene);
  glint::Pcg32 rng(31u, 2u);
  std::vector<double> carried;
  const int n = 200000;
  int across_edges = 0;
  for (int i = 0; i < n; ++i) {
    const glint::EmittedRay emitted = light.sample_le(next_2d(rng), next_2d(rng));
    const Vec3 towards = -emitted.ray.direction;
    // The origin lies on the disc facing the light's direction, tangent to the bounding sphere.
    const Vec3 offset = emitted.ray.origin - bounds.center;
    REQUIRE(glm::dot(offset, towards) == Approx(bounds.radius).epsilon(1e-4));
    REQUIRE(glm::length(offset - glm::dot(offset, towards) * towards) <= bounds.radius * 1.0001f);
    // Every point along the ray within the bounding sphere is reached with the disc's density;
    // a point before the disc, or outside its cylinder, by no light path.
    for (const float t : {0.5f, 1.0f, 1.9f})
      REQUIRE(light.disc_density(towards, emitted.ray.at(t * bounds.radius)) ==
              emitted.position_pdf);
    REQUIRE(light.disc_density(towards, emitted.ray.at(-0.1f * bounds.radius)) == 0.0f);
    const Vec3 sideways = glm::normalize(glm::cross(towards, Vec3(0.3f, 0.5f, 0.7f)));
    REQUIRE(light.disc_density(towards, bounds.center + 1.01f * bounds.radius * sideways) == 0.0f);
    const glint::EmissionDensity density = light.pdf_le(emitted.normal, emitted.ray.direction);
    REQUIRE(density.position == emitted.position_pdf);
    // The same but where rounding moves the drawn direction across a texel's edge.
    if (density.direction != Approx(emitted.direction_pdf).epsilon(1e-4)) ++across_edges;
    carried.push_back(double(glint::channel_mean(emitted.ray_weight(1.0f))));
  }
  CHECK(across_edges <= n / 10000);
  // A draw at the image's pole (a sampler may give u = 0 exactly) has no density: its path
  // carries nothing, and no infinity.
  REQUIRE(scene.environment().sample(Vec2(0.3f, 0.0f)).pdf == 0.0f);
  const glint::EmittedRay pole = light.sample_le(Vec2(0.5f, 0.5f), Vec2(0.3f, 0.0f));
  CHECK(glint::channel_mean(pole.ray_weight(1.0f)) == 0.0);
  // Each path carries its share of the power crossing the disc.
  const glint::test::Moments moments = glint::test::moments(carried);
  CHECK(std::fabs(moments.mean - light.power()) <=
        5.0 * std::sqrt(moments.variance / n) + 1e-4 * light.power());
}

TEST_CASE("the environment light gives every lane of a wide Float the bits of one point",
          "[environment][unit]") {
  glint::SceneDescription description;
  description.background_image = sky();
  description.background_placement.turn_degrees = 33.0f;
  const glint::Scene scene = glint::Scene::build(description);
  const glint::EnvironmentLight light(scene);
  using F = glint::Float<8>;
  glint::Pcg32 rng(8u, 8u);
  for (int round = 0; round < 200; ++round) {
    glint::BasicLightPoint<F> at{};
    glint::Vec2For<F> u{};
    glint::MaskFor<F> lanes{};
    for (int i = 0; i < 8; ++i) {
      glint::set_lane(at.point, i, random_direction(rng));
      u.x[i] = rng.next_float();
      u.y[i] = rng.next_float();
      lanes[i] = i != 5 ? -1 : 0;
    }
    const glint::BasicLightSample<F> wide = light.sample_li(at, u, lanes);
    for (int i = 0; i < 8; ++i) {
      if (i == 5) {
        REQUIRE_FALSE(glint::lane(wide.valid, i));
        continue;
      }
      const glint::LightSample one =
          light.sample_li(glint::LightPoint{glint::lane(at.point, i), glint::kNoSphere, false},
                          Vec2(u.x[i], u.y[i]));
      REQUIRE(std::bit_cast<std::uint32_t>(wide.pdf[i]) == std::bit_cast<std::uint32_t>(one.pdf));
      REQUIRE(glint::lane(wide.direction, i) == one.direction);
      REQUIRE(glint::lane(wide.radiance, i) == one.radiance);
      REQUIRE(bool(glint::lane(wide.valid, i)) == one.valid);
      REQUIRE(glint::lane(wide.sphere, i) == glint::kNoSphere);
    }
    const glint::Vec3For<F> looked_up = scene.environment().radiance<F>(lanes, at.point);
    for (int i = 0; i < 8; ++i)
      if (i != 5)
        REQUIRE(glint::lane(looked_up, i) ==
                scene.environment().radiance(glint::lane(at.point, i)));
  }
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// A colour PFM of `width` x `height`, by glint's own writer (rows from the top in `texels`).
void write_pfm_file(const fs::path& path, int width, int height, const std::vector<Color>& texels) {
  glint::Film film(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      film.at(x, y) = texels[std::size_t(y * width + x)];
  glint::write_pfm(film, path);
}

std::string scene_error(const fs::path& path) {
  try {
    glint::read_scene_file(path);
  } catch (const glint::SceneError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST_CASE("background image=FILE reads the image from the scene file's directory, and round-trips",
          "[environment][unit]") {
  const glint_test::ScratchDirectory dir("environment");
  fs::create_directories(dir / "skies");
  write_pfm_file(dir / "skies" / "sky.pfm", 2, 1, {Color(1.0f, 2.0f, 3.0f), Color(4.0f)});
  write_text(dir / "scene.txt",
             "background image=skies/sky.pfm axis=0,0,1 turn=45 scale=2.5\n"
             "sphere center=0,0,0 radius=1\n");
  const glint::SceneDescription scene = glint::read_scene_file(dir / "scene.txt");
  REQUIRE(scene.background_image);
  CHECK(scene.background_image->name() == "skies/sky.pfm");
  CHECK(scene.background_image->at(0, 0) == Color(1.0f, 2.0f, 3.0f));
  CHECK(scene.background_placement.axis == Vec3(0.0f, 0.0f, 1.0f));
  CHECK(scene.background_placement.turn_degrees == 45.0f);
  CHECK(scene.background_scale == 2.5f);
  CHECK(scene.background == Color(0.0f));

  std::ostringstream text;
  glint::write_scene(text, scene);
  CHECK_THAT(text.str(), Catch::Contains("background image=skies/sky.pfm axis=0,0,1 turn=45 "
                                         "scale=2.5\n"));
  write_text(dir / "again.txt", text.str());
  const glint::SceneDescription again = glint::read_scene_file(dir / "again.txt");
  CHECK(again.background_image->texels() == scene.background_image->texels());
  CHECK(again.background_scale == 2.5f);
  CHECK(again.background_placement.turn_degrees == 45.0f);

  const glint::Scene built = glint::Scene::build(scene);
  REQUIRE(built.environment().has_image());
  CHECK(built.environment().image().north() == Vec3(0.0f, 0.0f, 1.0f));
}

TEST_CASE("the background keys' mistakes are errors naming the line", "[environment][unit]") {
  const glint_test::ScratchDirectory dir("environment");
  write_pfm_file(dir / "ok.pfm", 1, 1, {Color(1.0f)});
  write_pfm_file(dir / "bright.pfm", 1, 1, {Color(3e38f)});
  const auto error_of = [&](const std::string& background) {
    write_text(dir / "s.txt", "image width=4 height=4\n" + background + "\n");
    return scene_error(dir / "s.txt");
  };
  CHECK_THAT(error_of("background image=none.pfm"),
             Catch::Contains("s.txt:2: error: background image 'none.pfm': cannot read"));
  CHECK_THAT(error_of("background color=1,1,1 image=ok.pfm"),
             Catch::Contains(":2: error: a background is a color or an image, not both"));
  CHECK_THAT(error_of("background scale=2"),
             Catch::Contains(":2: error: background axis, turn and scale place an image"));
  CHECK_THAT(error_of("background color=1,1,1 turn=3"),
             Catch::Contains(":2: error: background axis, turn and scale place an image"));
  CHECK_THAT(error_of("background image=ok.pfm axis=0,0,0"),
             Catch::Contains(":2: error: background axis must be a finite direction, not zero"));
  CHECK_THAT(error_of("background image=ok.pfm scale=-1"),
             Catch::Contains(":2: error: background scale must be finite and non-negative"));
  CHECK_THAT(error_of("background image=bright.pfm scale=10"),
             Catch::Contains(":2: error: background scale 10 takes the image's brightest texel"));
  CHECK_THAT(error_of("background image=s.txt"),
             Catch::Contains(":2: error: background image 's.txt':") &&
                 Catch::Contains("not a PNG, JPEG, Radiance HDR, PFM or OpenEXR file"));
  // The library's own descriptions are held to the same rules.
  glint::SceneDescription both;
  both.background = Color(1.0f);
  both.background_image = image(1, 1, [](int, int) { return Color(1.0f); });
  CHECK_THROWS_AS(glint::Scene::build(both), glint::SceneError);
}

}  // namespace environment_test
