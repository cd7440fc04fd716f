// Small renders whose answer is known exactly (or in expectation) from the physics, not from
// a previous run: determinism across thread counts, hard shadows, two-sided diffuse shading
// with the point-light formula, emission, a mirror and glass in a uniform emissive enclosure,
// refraction through nested glass traced independently here, the near clipping plane, and the
// rejection of unsupported shading kinds.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "../support/float_values.hpp"
#include "glint/render/renderer.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"

using glint::Color;
using glint::Vec3;

namespace {

using glint_test::kDegree;

glint::SceneDescription empty_scene(Vec3 camera, Vec3 look_at, float fov_degrees) {
  glint::SceneDescription scene;
  scene.source = "physics";
  scene.camera.position = camera;
  scene.camera.look_at = look_at;
  scene.camera.up = {0.0f, 1.0f, 0.0f};
  scene.camera.fov_degrees = fov_degrees;
  scene.background = Color(0.0f);
  return scene;
}

glint::SphereDescription& add_sphere(glint::SceneDescription& scene, Vec3 center, float radius) {
  glint::SphereDescription s;
  s.center = center;
  s.radius = radius;
  s.line = int(scene.spheres.size()) + 10;
  scene.spheres.push_back(s);
  return scene.spheres.back();
}

glint::Material emitter(Color emission) {
  glint::Material m;
  m.diffuse = 0.0f;
  m.emission = emission;
  return m;
}

glint::Material glass_material(float ior, Color color = Color(1.0f)) {
  glint::Material m;
  m.diffuse = 0.0f;
  m.transparent = 1.0f;
  m.transparent_color = color;
  m.ior = ior;
  return m;
}

glint::RenderSettings settings(int width, int height, int spp, int max_depth) {
  glint::RenderSettings s;
  s.width = width;
  s.height = height;
  s.samples_per_pixel = spp;
  s.max_depth = max_depth;
  s.antialias_sigma = 0.5f;
  s.seed = 1;
  s.threads = 2;
  return s;
}

/// The image of renderer R (a Renderer or a WavefrontRenderer).
template <typename R>
glint::Film render(const glint::SceneDescription& description, const glint::RenderSettings& s) {
  const glint::Scene scene = glint::Scene::build(description);
  INFO(glint_test::renderer_name<R>());
  const glint::RenderResult result = glint_test::render_by<R>(scene, s);
  CHECK(result.stats.invalid_samples == 0);
  return result.film;
}

using glint_test::same_bits;

/// Every pixel equal to `expected`, bit for bit.
void check_every_pixel(const glint::Film& film, Color expected) {
  int wrong = 0;
  Color example(0.0f);
  for (const Color& c : film.pixels()) {
    if (c != expected) {
      ++wrong;
      example = c;
    }
  }
  INFO("expected (" << expected.x << ", " << expected.y << ", " << expected.z << "), e.g. got ("
                    << example.x << ", " << example.y << ", " << example.z << ")");
  CHECK(wrong == 0);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("renders are bit-identical for 1, 2 and 5 threads", "[render][physics]",
                        glint_test::CameraPathRenderers) {
  // A bit of everything: a lit diffuse floor, octant shading, glass, a mirror, an emitter.
  glint::SceneDescription scene = empty_scene({0.0f, 4.0f, 14.0f}, {0.0f, 1.0f, 0.0f}, 50.0f);
  scene.background = Color(0.05f, 0.1f, 0.2f);
  add_sphere(scene, {0.0f, -1000.0f, 0.0f}, 1000.0f).material.diffuse_color = {0.8f, 0.7f, 0.6f};
  add_sphere(scene, {-2.5f, 1.0f, 0.0f}, 1.0f).shading = glint::ShadingKind::uniform;
  add_sphere(scene, {0.0f, 1.2f, 0.0f}, 1.2f).material = glass_material(1.5f);
  auto& mirror = add_sphere(scene, {2.5f, 1.0f, 0.0f}, 1.0f).material;
  mirror.diffuse = 0.2f;
  mirror.mirror = 0.8f;
  add_sphere(scene, {0.0f, 5.0f, -3.0f}, 0.5f).material = emitter(Color(4.0f));
  scene.lights.push_back({{3.0f, 8.0f, 5.0f}, 60.0f, Color(1.0f, 0.9f, 0.8f), 3});

  glint::RenderSettings s = settings(24, 20, 3, 3);
  s.tile_size = 8;  // 3 x 3 tiles, the last row and column partial
  s.threads = 1;
  const glint::Film one = render<TestType>(scene, s);
  s.threads = 2;
  const glint::Film two = render<TestType>(scene, s);
  s.threads = 5;
  const glint::Film five = render<TestType>(scene, s);
  CHECK(same_bits(one, two));
  CHECK(same_bits(one, five));
  s.seed = 2;
  const glint::Film reseeded = render<TestType>(scene, s);
  CHECK_FALSE(same_bits(one, reseeded));
}

TEMPLATE_LIST_TEST_CASE("hard shadows: opaque and glass blockers stop all direct light",
                        "[render][physics]", glint_test::CameraPathRenderers) {
  // A diffuse floor (the top of a big sphere, at y = 0) lit by a point light 10 above the
  // origin; the camera sees a small patch around the origin.
  glint::SceneDescription scene = empty_scene({0.0f, 3.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, 0.5f);
  const float albedo = 0.8f, intensity = 100.0f;
  add_sphere(scene, {0.0f, -100.0f, 0.0f}, 100.0f).material.diffuse = albedo;
  scene.lights.push_back({{0.0f, 10.0f, 0.0f}, intensity, Color(1.0f), 1});
  const glint::RenderSettings s = settings(8, 8, 2, 0);

  SECTION("unblocked: rho I cos / (pi d^2), the patch lies straight below the light") {
    // The patch has a radius below 0.1, where cos / d^2 differs from 1 / 10^2 by < 1.5e-4.
    const glint::Film film = render<TestType>(scene, s);
    const double expected = albedo * intensity / (M_PI * 100.0);
    for (const Color& c : film.pixels()) {
      CHECK(c.x == Approx(expected).epsilon(1e-3));
      CHECK(c.y == c.x);
    }
  }
  SECTION("an opaque blocker halfway") {
    add_sphere(scene, {0.0f, 5.0f, 0.0f}, 1.0f);
    check_every_pixel(render<TestType>(scene, s), Color(0.0f));
  }
  SECTION("a glass blocker halfway") {
    add_sphere(scene, {0.0f, 5.0f, 0.0f}, 1.0f).material = glass_material(1.5f);
    check_every_pixel(render<TestType>(scene, s), Color(0.0f));
  }
  SECTION("a mirror blocker just below the light") {
    auto& m = add_sphere(scene, {0.0f, 9.0f, 0.0f}, 0.5f).material;
    m.diffuse = 0.0f;
    m.mirror = 1.0f;
    check_every_pixel(render<TestType>(scene, s), Color(0.0f));
  }
}

TEMPLATE_LIST_TEST_CASE("two-sided diffuse: inside shades like outside", "[render][physics]",
                        glint_test::CameraPathRenderers) {
  // The camera looks at P = (0, 0, 10) on a sphere of radius 10, from outside or from inside.
  // A light at distance d = 8 from P, at 60 degrees from the normal on the camera's side, gives
  // radiance rho I cos(60) / (pi d^2) either way (direct light only).
  const float albedo = 0.6f, intensity = 50.0f, d = 8.0f;
  const double theta = 60.0 * kDegree;
  const double expected = albedo * intensity * std::cos(theta) / (M_PI * d * d);
  const Vec3 p(0.0f, 0.0f, 10.0f);
  const Vec3 sideways(float(d * std::sin(theta)), 0.0f, 0.0f);
  const Vec3 along(0.0f, 0.0f, float(d * std::cos(theta)));

  // A field of view of 1e-4 degrees keeps every (jittered) ray within 1e-4 of P.
  glint::SceneDescription outside = empty_scene({0.0f, 0.0f, 30.0f}, p, 1e-4f);
  add_sphere(outside, Vec3(0.0f), 10.0f).material.diffuse = albedo;
  outside.lights.push_back({p + sideways + along, intensity, Color(1.0f), 1});

  glint::SceneDescription inside = empty_scene({0.0f, 0.0f, 0.0f}, p, 1e-4f);
  add_sphere(inside, Vec3(0.0f), 10.0f).material.diffuse = albedo;
  inside.lights.push_back({p + sideways - along, intensity, Color(1.0f), 1});
  REQUIRE(glm::length(inside.lights[0].position) < 10.0f);

  const glint::RenderSettings s = settings(3, 3, 2, 0);
  const glint::Film out = render<TestType>(outside, s);
  const glint::Film in = render<TestType>(inside, s);
  for (std::size_t i = 0; i < out.pixels().size(); ++i) {
    CHECK(out.pixels()[i].x == Approx(expected).epsilon(1e-4));
    CHECK(in.pixels()[i].x == Approx(expected).epsilon(1e-4));
    CHECK(in.pixels()[i].x == Approx(out.pixels()[i].x).epsilon(1e-4));
  }
  // A light behind the surface (outside, for the inside view) gives nothing.
  inside.lights[0].position = p + sideways + along;
  check_every_pixel(render<TestType>(inside, s), Color(0.0f));
}

TEMPLATE_LIST_TEST_CASE("an emissive sphere shows its emission from outside and inside",
                        "[render][physics]", glint_test::CameraPathRenderers) {
  // Emission with few mantissa bits, so that averaging 4 equal samples is exact.
  const Color emission(0.25f, 1.5f, 3.0f);
  glint::SceneDescription scene = empty_scene({0.0f, 0.0f, 20.0f}, Vec3(0.0f), 10.0f);
  // Emission only: a diffuse lobe would add the light the sphere sheds on itself inside it.
  add_sphere(scene, Vec3(0.0f), 5.0f).material = emitter(emission);
  const glint::RenderSettings s = settings(6, 6, 4, 0);
  check_every_pixel(render<TestType>(scene, s), emission);
  scene.camera.position = {1.0f, 2.0f, 0.5f};
  scene.camera.fov_degrees = 120.0f;
  check_every_pixel(render<TestType>(scene, s), emission);
}

TEMPLATE_LIST_TEST_CASE("a mirror sphere in a uniform emissive enclosure shows c Le",
                        "[render][physics]", glint_test::CameraPathRenderers) {
  const Color le(2.0f, 4.0f, 1.0f), c(0.5f, 0.25f, 0.75f);
  glint::SceneDescription scene = empty_scene({0.0f, 0.0f, 40.0f}, Vec3(0.0f), 6.0f);
  add_sphere(scene, Vec3(0.0f), 100.0f).material = emitter(le);
  auto& m = add_sphere(scene, Vec3(0.0f), 5.0f).material;
  m.diffuse = 0.0f;
  m.mirror = 1.0f;
  m.mirror_color = c;
  // The mirror is the one scattering vertex between the camera and the enclosure, which every
  // max_depth allows (light after at most max_depth + 1 of them).
  for (const int depth : {0, 1, 2}) {
    INFO("max_depth " << depth);
    check_every_pixel(render<TestType>(scene, settings(8, 8, 4, depth)), c * le);
  }
}

TEST_CASE("glass without Fresnel in a uniform enclosure transmits Le times colour per crossing",
          "[render][physics]") {
  // Every camera ray hits the sphere, enters (weight transparent_color), leaves (weight
  // transparent_color again; a sphere never traps a ray that entered it) and meets the
  // enclosure: transparent_color^2 * Le.
  using Variant = glint::variants::no_fresnel;
  const Color le(2.0f, 4.0f, 1.0f), tc(0.5f, 1.0f, 0.25f);
  glint::SceneDescription scene = empty_scene({0.0f, 0.0f, 50.0f}, Vec3(0.0f), 10.0f);
  add_sphere(scene, Vec3(0.0f), 100.0f).material = emitter(le);
  add_sphere(scene, Vec3(0.0f), 10.0f).material = glass_material(1.5f, tc);
  check_every_pixel(render<glint::Renderer<Variant>>(scene, settings(8, 8, 4, 4)), tc * tc * le);
  // Two scattering vertices (entering and leaving) need one bounce; with none the ray inside
  // the glass is not followed.
  check_every_pixel(render<glint::Renderer<Variant>>(scene, settings(8, 8, 4, 1)), tc * tc * le);
  check_every_pixel(render<glint::Renderer<Variant>>(scene, settings(8, 8, 4, 0)), Color(0.0f));
}

TEMPLATE_LIST_TEST_CASE("clear glass in a uniform enclosure conserves energy", "[render][physics]",
                        glint_test::CameraPathRenderers) {
  // Reflected or refracted, with or without Fresnel, every path ends on the enclosure: Le.
  // Exact per sample with a fixed depth; with Russian roulette exact in expectation.
  const Color le(1.0f, 2.0f, 0.5f);
  glint::SceneDescription scene = empty_scene({0.0f, 0.0f, 50.0f}, Vec3(0.0f), 10.0f);
  add_sphere(scene, Vec3(0.0f), 100.0f).material = emitter(le);
  add_sphere(scene, Vec3(0.0f), 10.0f).material = glass_material(1.5f);
  add_sphere(scene, {0.0f, 0.0f, -4.0f}, 3.0f).material = glass_material(1.0f);  // a bubble
  const glint::Film film = render<TestType>(scene, settings(8, 8, 8, 64));
  if constexpr (!TestType::Config::path_termination::uses_roulette) {
    check_every_pixel(film, le);
  } else {
    double sum = 0.0, sum2 = 0.0;
    for (const Color& c : film.pixels()) {
      CHECK(c.y == Approx(2.0 * c.x).epsilon(1e-5));
      sum += c.x;
      sum2 += double(c.x) * c.x;
    }
    const double n = double(film.pixels().size());
    const double mean = sum / n;
    const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    CHECK(std::abs(mean - 1.0) <= 5.0 * se + 1e-5);
  }
}

namespace {

// ---- an independent ray tracer for refraction through concentric glass --------------------

struct DVec {
  double x, y, z;
  DVec operator+(const DVec& o) const { return {x + o.x, y + o.y, z + o.z}; }
  DVec operator-(const DVec& o) const { return {x - o.x, y - o.y, z - o.z}; }
  DVec operator*(double s) const { return {x * s, y * s, z * s}; }
  double dot(const DVec& o) const { return x * o.x + y * o.y + z * o.z; }
  DVec unit() const { return *this * (1.0 / std::sqrt(dot(*this))); }
};

struct Shell {
  double radius, inside, outside;  // concentric about the origin, with these indices
};

/// Follows a ray through concentric transparent spheres by Snell's law, n1 sin t1 = n2 sin t2
/// written for vectors; returns the ray after it has left the outermost sphere.
void trace_shells(const std::vector<Shell>& shells, DVec& origin, DVec& direction) {
  for (int step = 0; step < 16; ++step) {
    double best = 1e300;
    const Shell* hit = nullptr;
    for (const Shell& s : shells) {
      const double b = origin.dot(direction);
      const double disc = b * b - (origin.dot(origin) - s.radius * s.radius);
      if (disc < 0) continue;
      for (const double t : {-b - std::sqrt(disc), -b + std::sqrt(disc)})
        if (t > 1e-9 && t < best) {
          best = t;
          hit = &s;
        }
    }
    if (!hit) return;
    origin = origin + direction * best;
    const DVec outward = origin.unit();
    const bool leaving = direction.dot(outward) > 0;
    const DVec n = leaving ? outward * -1.0 : outward;  // facing the incoming ray
    const double eta = leaving ? hit->inside / hit->outside : hit->outside / hit->inside;
    const double cos_i = -direction.dot(n);
    const double sin2_t = eta * eta * (1 - cos_i * cos_i);
    REQUIRE(sin2_t < 1.0);  // these configurations have no total internal reflection
    direction = (direction * eta + n * (eta * cos_i - std::sqrt(1 - sin2_t))).unit();
  }
}

}  // namespace

TEST_CASE("refraction through glass inside glass uses the inclusion tree's index",
          "[render][physics]") {
  // Concentric spheres: glass of index 1.5 (radius 10) holding glass of index 2.0 (radius 5).
  // A camera ray parallel to the axis at height h is followed here through all four
  // interfaces, and a small emitter is put on the predicted exit ray; the render sees it only
  // if every interface refracted with the right pair of indices.
  using Variant = glint::variants::no_fresnel;
  const Color target_emission(0.5f, 1.0f, 2.0f);
  for (const float h : {0.0f, 1.0f, 3.0f}) {
    INFO("height " << h);
    DVec origin{0.0, h, 50.0}, direction{0.0, 0.0, -1.0};
    trace_shells({{10.0, 1.5, 1.0}, {5.0, 2.0, 1.5}}, origin, direction);
    const DVec target = origin + direction * 20.0;
    const double target_radius = 0.3;
    if (h == 0.0f) {  // normal incidence: straight through
      CHECK(std::abs(target.y) < 1e-12);
      CHECK(target.z == Approx(-30.0));
    } else {  // with the medium's index around the inner sphere, the ray would miss the target
      DVec wrong_origin{0.0, h, 50.0}, wrong_direction{0.0, 0.0, -1.0};
      trace_shells({{10.0, 1.5, 1.0}, {5.0, 2.0, 1.0}}, wrong_origin, wrong_direction);
      const DVec to_target = target - wrong_origin;
      const double along = to_target.dot(wrong_direction);
      const double miss = std::sqrt(to_target.dot(to_target) - along * along);
      CHECK(miss > 3.0 * target_radius);
    }
    glint::SceneDescription scene = empty_scene({0.0f, h, 50.0f}, {0.0f, h, 0.0f}, 0.01f);
    add_sphere(scene, Vec3(0.0f), 10.0f).material = glass_material(1.5f);
    add_sphere(scene, Vec3(0.0f), 5.0f).material = glass_material(2.0f);
    add_sphere(scene, Vec3(float(target.x), float(target.y), float(target.z)), float(target_radius))
        .material = emitter(target_emission);
    glint::RenderSettings s = settings(1, 1, 4, 8);
    s.antialias_sigma = 0.0f;
    check_every_pixel(render<glint::Renderer<Variant>>(scene, s), target_emission);
  }
}

TEMPLATE_LIST_TEST_CASE("the near clipping plane hides what is in front of it", "[render][physics]",
                        glint_test::CameraPathRenderers) {
  // From z = 20 looking down the axis: a red sphere spanning t in [4, 6], a blue one spanning
  // t in [17, 23], then the background.
  const Color red(1.0f, 0.0f, 0.0f), blue(0.0f, 0.0f, 1.0f), green(0.0f, 0.5f, 0.0f);
  glint::SceneDescription scene = empty_scene({0.0f, 0.0f, 20.0f}, Vec3(0.0f), 0.5f);
  scene.background = green;
  add_sphere(scene, {0.0f, 0.0f, 15.0f}, 1.0f).material = emitter(red);
  add_sphere(scene, Vec3(0.0f), 3.0f).material = emitter(blue);
  const glint::RenderSettings s = settings(3, 3, 2, 0);
  const std::pair<float, Color> cases[] = {
      {0.0f, red},    // nothing clipped
      {5.0f, red},    // inside the red sphere: its far side, seen from inside
      {8.0f, blue},   // the red sphere is wholly in front of the plane
      {18.0f, blue},  // the far side of the blue one
      {24.0f, green}};
  for (const auto& [near, expected] : cases) {
    INFO("near " << near);
    scene.camera.near = near;
    check_every_pixel(render<TestType>(scene, s), expected);
  }
}

namespace {
using UniformOnly = glint::variants::uniform_shading;
}

TEST_CASE("a shading kind the variant lacks is rejected when rendering", "[render][physics]") {
  glint::SceneDescription scene = empty_scene({0.0f, 0.0f, 20.0f}, Vec3(0.0f), 30.0f);
  add_sphere(scene, Vec3(0.0f), 3.0f);
  scene.lights.push_back({{0.0f, 10.0f, 10.0f}, 10.0f, Color(1.0f), 1});
  const glint::Scene uniform = glint::Scene::build(scene);
  CHECK_NOTHROW(glint_test::render_by<glint::Renderer<UniformOnly>>(uniform, settings(4, 4, 1, 1)));

  auto& octants = add_sphere(scene, {5.0f, 0.0f, 0.0f}, 1.0f);
  octants.shading = glint::ShadingKind::octants;
  octants.line = 12;
  const glint::Scene mixed = glint::Scene::build(scene);
  try {
    (void)glint_test::render_by<glint::Renderer<UniformOnly>>(mixed, settings(4, 4, 1, 1));
    FAIL("rendered a scene with octant shading");
  } catch (const glint::SceneError& e) {
    CHECK(e.line() == 12);
    const std::string message = e.what();
    CHECK(message.find("physics:12: error:") == 0);
    CHECK(message.find("octants") != std::string::npos);
  }
  // The built-in shading renders it.
  CHECK_NOTHROW(
      glint_test::render_by<glint::Renderer<glint::variants::report>>(mixed, settings(4, 4, 1, 1)));
}
