// The Light interface (render/light.hpp) for every kind of light, against values worked out here:
// the irradiance a sphere of radiance L brings to a point outside it (pi L (r/d)^2 facing it) and
// inside it (pi L), a point light's I / d^2, the distribution of sample_li's directions against
// pdf_li and of sample_le's points and directions against pdf_le by chi-square tests over the
// sphere of directions (direction_cells.hpp), every light path carrying the light's power, and
// the choice by power over a scene's lights (render/scene_lights.hpp,
// render/light_selection.hpp).
//
// Each chi-square test rejects a correct density with probability about 1e-6 (statistics.hpp);
// the means are held to five standard errors (a normal tail of 6e-7). With the few dozen checks
// here, the file's false-alarm rate is below 1e-4. A density with 5% of its mass moved is shown
// to be rejected.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "direction_cells.hpp"
#include "glint/io/scene_reader.hpp"
#include "glint/math/random.hpp"
#include "glint/render/light.hpp"
#include "glint/render/light_selection.hpp"
#include "glint/render/lights/point_light_source.hpp"
#include "glint/render/lights/sphere_light.hpp"
#include "glint/render/scene_lights.hpp"
#include "glint/scene/scene.hpp"
#include "statistics.hpp"

using glint::Color;
using glint::LightPoint;
using glint::LightSample;
using glint::SphereLight;
using glint::Vec2;
using glint::Vec3;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::uint32_t kLightSphere = 3;
constexpr std::uint32_t kOtherSphere = 9;

Vec2 next_2d(glint::Pcg32& rng) {
  const float x = rng.next_float();
  return {x, rng.next_float()};
}

SphereLight sphere_light(const Vec3& center, float radius, const Color& radiance) {
  return SphereLight(glint::SphereEmitter{center, radius, radiance, kLightSphere});
}

/// The distance along the unit `direction` from `origin` to the first point of the sphere
/// (center, radius) beyond it, in double (a point on the sphere does not meet itself); negative:
/// none.
double distance_to_sphere(const Vec3& origin, const Vec3& direction, const Vec3& center,
                          double radius) {
  const double ox = double(origin.x) - center.x, oy = double(origin.y) - center.y,
               oz = double(origin.z) - center.z;
  const double b = ox * direction.x + oy * direction.y + oz * direction.z;
  const double c = ox * ox + oy * oy + oz * oz - radius * radius;
  const double discriminant = b * b - c;
  if (discriminant < 0.0) return -1.0;
  const double root = std::sqrt(discriminant);
  const double least = 1e-5 * radius;
  return -b - root > least ? -b - root : (-b + root > least ? -b + root : -1.0);
}

/// sample_li's directions from `at`, n of them, against pdf_li by chi-square; the density of a
/// direction is pdf_li where the ray meets the light, zero where it misses.
glint::test::ChiSquare sample_li_against_pdf_li(const SphereLight& light, const LightPoint& at,
                                                int n, std::uint64_t seed) {
  glint::Pcg32 rng(seed, 5u);
  std::vector<double> observed(glint::test::kCells, 0.0), expected(glint::test::kCells, 0.0);
  for (int i = 0; i < n; ++i) {
    const LightSample sample = light.sample_li(at, next_2d(rng));
    REQUIRE(sample.valid);
    ++observed[std::size_t(glint::test::cell_of(sample.direction))];
  }
  const std::vector<double> mass = glint::test::cell_masses([&](const Vec3& direction) {
    const double t = distance_to_sphere(at.point, direction, light.center, light.radius);
    if (!(t > 0.0)) return 0.0f;
    const Vec3 hit = at.point + float(t) * direction;
    return light.pdf_li(at, direction, float(t), glm::normalize(hit - light.center));
  });
  for (int k = 0; k < glint::test::kCells; ++k)
    expected[std::size_t(k)] = n * mass[std::size_t(k)];
  return glint::test::chi_square_pooled(observed, expected);
}

struct Estimate {
  double mean, standard_error;
};

/// The mean and standard error of radiance.r x cos / pdf over n of sample_li's samples at a
/// point of normal `normal`: an estimate of the irradiance there.
Estimate irradiance(const SphereLight& light, const LightPoint& at, const Vec3& normal, int n) {
  glint::Pcg32 rng(77u, 3u);
  std::vector<double> values;
  for (int i = 0; i < n; ++i) {
    const LightSample sample = light.sample_li(at, next_2d(rng));
    const double cosine = std::max(0.0f, glm::dot(sample.direction, normal));
    values.push_back(sample.valid ? double(sample.radiance.r) * cosine / sample.pdf : 0.0);
  }
  const glint::test::Moments m = glint::test::moments(values);
  return {m.mean, std::sqrt(m.variance / double(n))};
}

/// An orthonormal frame around unit `z`, built here (any frame serves a density that depends on
/// the angle to z only).
struct TestFrame {
  Vec3 x, y, z;
  explicit TestFrame(const Vec3& n) : z(n) {
    const Vec3 helper = std::fabs(n.x) < 0.9f ? Vec3(1.0f, 0.0f, 0.0f) : Vec3(0.0f, 1.0f, 0.0f);
    x = glm::normalize(glm::cross(helper, n));
    y = glm::cross(n, x);
  }
  Vec3 to_local(const Vec3& v) const { return {glm::dot(v, x), glm::dot(v, y), glm::dot(v, z)}; }
};

/// Chi-square of the cells of `directions` against the density `pdf` per unit solid angle.
template <typename Density>
glint::test::ChiSquare directions_against(const std::vector<Vec3>& directions, Density&& pdf) {
  std::vector<double> observed(glint::test::kCells, 0.0), expected(glint::test::kCells, 0.0);
  for (const Vec3& d : directions)
    ++observed[std::size_t(glint::test::cell_of(d))];
  const std::vector<double> mass = glint::test::cell_masses(pdf);
  for (int k = 0; k < glint::test::kCells; ++k)
    expected[std::size_t(k)] = double(directions.size()) * mass[std::size_t(k)];
  return glint::test::chi_square_pooled(observed, expected);
}

}  // namespace

TEST_CASE("A sphere light brings the irradiance worked out by hand, from outside and inside",
          "[lights][statistical]") {
  const Vec3 center(1.0f, -2.0f, 0.5f);
  const float radius = 2.0f;
  const SphereLight light = sphere_light(center, radius, Color(3.0f));
  const int n = 1 << 16;
  SECTION("outside, facing the centre: pi L (r/d)^2") {
    for (const float distance : {2.5f, 6.0f, 40.0f}) {
      const Vec3 axis = glm::normalize(Vec3(0.3f, 1.0f, -0.4f));
      const LightPoint at{center + distance * axis, kOtherSphere, false};
      const Estimate e = irradiance(light, at, -axis, n);
      const double expected = kPi * 3.0 * (radius / distance) * (radius / distance);
      CHECK(std::fabs(e.mean - expected) <= 5.0 * e.standard_error + 1e-6 * expected);
    }
  }
  SECTION("inside, the sphere all around: pi L on any plane") {
    const LightPoint at{center + Vec3(0.5f, 0.9f, -0.3f), kOtherSphere, false};
    const Estimate e = irradiance(light, at, glm::normalize(Vec3(1.0f, 1.0f, 0.0f)), n);
    CHECK(std::fabs(e.mean - kPi * 3.0) <= 5.0 * e.standard_error);
  }
  SECTION("on its own surface, from inside: pi L; from outside: nothing") {
    const Vec3 normal = glm::normalize(Vec3(0.0f, 0.6f, 0.8f));
    const Vec3 on_surface = center + radius * normal;
    const Estimate e = irradiance(light, {on_surface, kLightSphere, true}, -normal, n);
    CHECK(std::fabs(e.mean - kPi * 3.0) <= 5.0 * e.standard_error);
    glint::Pcg32 rng(1u, 1u);
    for (int i = 0; i < 64; ++i)
      CHECK_FALSE(light.sample_li(LightPoint{on_surface, kLightSphere, false}, next_2d(rng)).valid);
  }
}

TEST_CASE("A sphere light's directions are distributed as pdf_li says", "[lights][statistical]") {
  const Vec3 center(0.0f, 0.0f, 3.0f);
  // From the origin the sphere subtends a cone of cos = 0.75 about +z: a band edge of the cells.
  const float radius = 3.0f * std::sqrt(1.0f - 0.75f * 0.75f);
  const SphereLight light = sphere_light(center, radius, Color(1.0f));
  const int n = 200000;
  CHECK_FALSE(sample_li_against_pdf_li(light, {Vec3(0.0f), kOtherSphere, false}, n, 1).rejected());
  CHECK_FALSE(sample_li_against_pdf_li(light, {Vec3(0.2f, -0.4f, 3.5f), kOtherSphere, true}, n, 2)
                  .rejected());
  const Vec3 on_surface = center + radius * glm::normalize(Vec3(1.0f, 0.0f, -1.0f));
  CHECK_FALSE(sample_li_against_pdf_li(light, {on_surface, kLightSphere, true}, n, 3).rejected());
}

TEST_CASE("A point light brings I colour / d^2 from its one direction", "[lights]") {
  glint::PointLight description;
  description.position = Vec3(1.0f, 4.0f, -2.0f);
  description.intensity = 8.0f;
  description.color = Color(0.5f, 1.0f, 0.25f);
  const glint::PointLightSource light(description);
  const LightPoint at{Vec3(1.0f, 0.0f, 1.0f), kOtherSphere, false};
  const LightSample sample = light.sample_li(at, Vec2(0.3f, 0.7f));
  REQUIRE(sample.valid);
  CHECK(sample.pdf == 1.0f);
  CHECK(sample.sphere == glint::kNoSphere);
  CHECK(sample.distance == Approx(5.0f));
  CHECK(sample.direction.y == Approx(0.8f));
  CHECK(sample.direction.z == Approx(-0.6f));
  CHECK(sample.radiance.r == Approx(8.0 * 0.5 / 25.0));
  CHECK(sample.radiance.g == Approx(8.0 * 1.0 / 25.0));
  CHECK(sample.point == description.position);
  // No ray meets a point: no density for any direction.
  CHECK(light.pdf_li(at, sample.direction, 5.0f, Vec3(0.0f)) == 0.0f);
  // At the light's own point nothing arrives.
  CHECK_FALSE(light.sample_li(LightPoint{description.position, kOtherSphere, false}).valid);
}

TEST_CASE("Light paths leave every kind of light as pdf_le says, each carrying its power",
          "[lights][statistical]") {
  const int n = 200000;
  glint::Pcg32 rng(2026u, 12u);
  SECTION("a point light: uniform over the sphere of directions") {
    glint::PointLight description;
    description.position = Vec3(0.5f, 2.0f, 1.0f);
    description.intensity = 3.0f;
    description.color = Color(1.0f, 0.5f, 0.25f);
    const glint::PointLightSource light(description);
    const double power = 4.0 * kPi * 3.0 * (1.0 + 0.5 + 0.25) / 3.0;
    CHECK(light.power() == Approx(power).epsilon(1e-6));
    std::vector<Vec3> directions;
    for (int i = 0; i < n; ++i) {
      const Vec2 u_point = next_2d(rng);
      const glint::EmittedRay ray = light.sample_le(u_point, next_2d(rng));
      REQUIRE(ray.ray.origin == description.position);
      const glint::EmissionDensity density = light.pdf_le(ray.normal, ray.ray.direction);
      REQUIRE(density.position == ray.position_pdf);
      REQUIRE(density.direction == ray.direction_pdf);
      const double carried = glint::channel_mean(ray.radiance) * ray.cosine /
                             (double(ray.position_pdf) * ray.direction_pdf);
      REQUIRE(carried == Approx(power).epsilon(1e-5));
      directions.push_back(ray.ray.direction);
    }
    CHECK_FALSE(directions_against(directions, [](const Vec3&) { return 0.25 / kPi; }).rejected());
    // A density with 5% of its mass moved from -z to +z is caught.
    CHECK(directions_against(directions, [](const Vec3& d) {
            return (1.0 + 0.2 * d.z) / (4 * kPi);
          }).rejected());
  }
  SECTION("a sphere light: a uniform point, a side, the cosine about it") {
    const Vec3 center(-1.0f, 0.5f, 2.0f);
    const float radius = 1.5f;
    const SphereLight light = sphere_light(center, radius, Color(2.0f, 1.0f, 3.0f));
    const double area = 4.0 * kPi * 1.5 * 1.5;
    const double power = 2.0 * kPi * area * 2.0;
    CHECK(light.power() == Approx(power).epsilon(1e-6));
    std::vector<Vec3> normals, local_directions;
    for (int i = 0; i < n; ++i) {
      const Vec2 u_point = next_2d(rng);
      const glint::EmittedRay ray = light.sample_le(u_point, next_2d(rng));
      REQUIRE(ray.sphere == kLightSphere);
      REQUIRE(glm::length(ray.ray.origin - center) == Approx(radius).epsilon(1e-5));
      REQUIRE(glm::dot(ray.normal, glm::normalize(ray.ray.origin - center)) ==
              Approx(1.0).epsilon(1e-5));
      const glint::EmissionDensity density = light.pdf_le(ray.normal, ray.ray.direction);
      REQUIRE(density.position == Approx(1.0 / area).epsilon(1e-6));
      REQUIRE(density.direction == Approx(ray.direction_pdf).epsilon(1e-6));
      const double carried = glint::channel_mean(ray.radiance) * ray.cosine /
                             (double(ray.position_pdf) * ray.direction_pdf);
      REQUIRE(carried == Approx(power).epsilon(1e-4));
      normals.push_back(ray.normal);
      local_directions.push_back(TestFrame(ray.normal).to_local(ray.ray.direction));
    }
    // The points: a uniform point of the area is a uniform normal.
    CHECK_FALSE(directions_against(normals, [](const Vec3&) { return 0.25 / kPi; }).rejected());
    // The directions about the normal, either side.
    CHECK_FALSE(directions_against(local_directions, [&](const Vec3& d) {
                  return light.pdf_le(Vec3(0.0f, 0.0f, 1.0f), d).direction;
                }).rejected());
  }
}

TEST_CASE("A scene's lights in the order of their kinds, chosen in proportion to power",
          "[lights]") {
  const glint::Scene scene = glint::Scene::build(
      glint::read_scene_text("camera position=0,0,30 look_at=0,0,0\n"
                             "material lamp diffuse=0 emission=4,4,4\n"
                             "material dim diffuse=0 emission=1,2,3\n"
                             "sphere center=0,0,0 radius=2 material=lamp\n"
                             "light position=0,20,0 intensity=100\n"
                             "sphere center=5,0,0 radius=1 color=0.5,0.5,0.5\n"
                             "sphere center=-5,0,0 radius=3 material=dim\n"
                             "light position=0,-20,0 intensity=10 color=1,0,0\n"));
  const glint::SceneLights lights(scene);
  REQUIRE(lights.size() == 4);
  const std::vector<double> power = {4.0 * kPi * 100.0, 4.0 * kPi * 10.0 / 3.0,
                                     2.0 * kPi * (4.0 * kPi * 4.0) * 4.0,
                                     2.0 * kPi * (4.0 * kPi * 9.0) * 2.0};
  double total = 0.0;
  for (const double p : power)
    total += p;
  std::vector<bool> delta;
  lights.for_each([&](const auto& light) { delta.push_back(light.kDeltaPosition); });
  CHECK(delta == std::vector<bool>{true, true, false, false});
  for (glint::LightId id = 0; id < 4; ++id)
    CHECK(lights.visit(id, [](const auto& light) { return light.power(); }) ==
          Approx(power[id]).epsilon(1e-6));
  // The emitters, in the scene's order, after the point lights.
  CHECK(lights.sphere_light(0) == 2);
  CHECK(lights.sphere_light(1) == 3);

  const glint::LightSelectionByPower selection(lights);
  REQUIRE_FALSE(selection.empty());
  double sum = 0.0;
  std::vector<int> chosen(4, 0);
  const int steps = 1 << 16;
  for (int i = 0; i < steps; ++i) {
    const glint::LightSelectionByPower::Choice choice = selection.choose((i + 0.5f) / steps);
    REQUIRE(choice.probability == selection.probability(choice.light));
    ++chosen[choice.light];
  }
  for (glint::LightId id = 0; id < 4; ++id) {
    CHECK(selection.probability(id) == Approx(power[id] / total).epsilon(1e-6));
    CHECK(chosen[id] == Approx(steps * power[id] / total).margin(1.0));
    sum += selection.probability(id);
  }
  CHECK(sum == Approx(1.0).epsilon(1e-7));
}
