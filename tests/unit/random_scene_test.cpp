// The random scene generator, checked against independent brute-force computations: every pair
// of spheres disjoint or nested with the gap (all pairs, no grid), every sphere inside the room,
// every radius as large as the spheres before it allowed, material frequencies within binomial
// bounds, determinism, parameter errors, and a round trip through the scene file format.

#include "glint/generate/random_scene.hpp"

#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "glint/io/scene_reader.hpp"
#include "glint/io/scene_writer.hpp"
#include "glint/scene/inclusion_tree.hpp"
#include "glint/scene/validate.hpp"

namespace {

glint::RandomSceneParameters report_parameters(int count, std::uint64_t seed) {
  glint::RandomSceneParameters p;  // the defaults are the report's, but say so explicitly
  p.domain_size = 80.0f;
  p.sphere_count = count;
  p.diffuse_probability = 0.15f;
  p.mirror_probability = 0.35f;
  p.transparent_probability = 0.5f;
  p.min_radius = 5.0f;
  p.max_radius = 10.0f;
  p.seed = seed;
  return p;
}

/// Crowded enough that many centres land inside earlier spheres, so nesting happens often.
glint::RandomSceneParameters crowded_parameters(std::uint64_t seed) {
  glint::RandomSceneParameters p;
  p.domain_size = 60.0f;
  p.sphere_count = 700;
  p.min_radius = 0.5f;
  p.max_radius = 12.0f;
  p.gap_fraction = 0.05f;
  p.seed = seed;
  return p;
}

/// Small spheres in a large domain: the generator's grid hashes its cells.
glint::RandomSceneParameters sparse_parameters(std::uint64_t seed) {
  glint::RandomSceneParameters p;
  p.domain_size = 1000.0f;
  p.sphere_count = 400;
  p.min_radius = 1.0f;
  p.max_radius = 2.0f;
  p.seed = seed;
  return p;
}

double distance(const glint::Vec3& a, const glint::Vec3& b) {
  const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

struct Geometry {
  int pairs = 0;
  int nested_pairs = 0;
};

/// The checks of the generator's contract, written without its grid or its interval search.
Geometry check_geometry(const glint::RandomSceneParameters& p,
                        const glint::RandomSceneResult& result) {
  const auto& spheres = result.scene.spheres;
  const int walls = result.wall_count;
  const double half = 0.5 * double(p.domain_size);
  const double gap = double(p.gap_fraction) * p.min_radius;
  REQUIRE(result.gap == Approx(gap));
  REQUIRE(walls == 6);
  REQUIRE(int(spheres.size()) == walls + result.placed);
  REQUIRE(result.placed <= result.requested);
  const double tolerance = 1e-9 * p.domain_size;  // double rounding in these very checks

  for (int i = walls; i < int(spheres.size()); ++i) {
    const glint::SphereDescription& s = spheres[std::size_t(i)];
    INFO("sphere " << i << " at " << s.center.x << "," << s.center.y << "," << s.center.z
                   << " radius " << s.radius);
    REQUIRE(s.radius >= p.min_radius);
    REQUIRE(s.radius <= p.max_radius);
    const float coords[] = {s.center.x, s.center.y, s.center.z};
    for (const float c : coords)
      REQUIRE(std::abs(double(c)) + s.radius <= half - gap + tolerance);
    for (int w = 0; w < walls; ++w) {  // the room is the inside of every wall sphere
      const glint::SphereDescription& wall = spheres[std::size_t(w)];
      REQUIRE(distance(s.center, wall.center) + s.radius <= wall.radius - gap + 1e-6);
    }
  }

  Geometry geometry;
  for (int i = walls; i < int(spheres.size()); ++i) {
    for (int j = walls; j < i; ++j) {
      const glint::SphereDescription& a = spheres[std::size_t(i)];
      const glint::SphereDescription& b = spheres[std::size_t(j)];
      const double d = distance(a.center, b.center);
      const bool disjoint = d - a.radius - b.radius >= gap - tolerance;
      const bool a_in_b = b.radius - d - a.radius >= gap - tolerance;
      const bool b_in_a = a.radius - d - b.radius >= gap - tolerance;
      ++geometry.pairs;
      if (a_in_b || b_in_a) ++geometry.nested_pairs;
      if (!(disjoint || a_in_b || b_in_a))
        FAIL("spheres " << j << " and " << i << " are neither disjoint nor nested with gap " << gap
                        << ": distance " << d << ", radii " << b.radius << " and " << a.radius);
    }
  }
  return geometry;
}

/// Each sphere's radius must be the largest the room and the earlier spheres allowed. With d
/// the distance to an earlier sphere j, the radii in (|d - r_j| - gap, d + r_j + gap) are
/// forbidden (partial overlap, or touching within the gap); everything else up to the room's
/// bound is allowed. The largest allowed radius is therefore the room's bound or the lower end
/// of one of those intervals, so it is enough to check that the chosen radius is allowed and
/// that every such candidate above it is forbidden. This scans all earlier spheres, without
/// the generator's grid.
void check_radii_are_maximal(const glint::RandomSceneParameters& p,
                             const glint::RandomSceneResult& result) {
  const auto& spheres = result.scene.spheres;
  const double half = 0.5 * double(p.domain_size);
  const double gap = result.gap;
  std::vector<std::pair<double, double>> forbidden;
  for (std::size_t i = std::size_t(result.wall_count); i < spheres.size(); ++i) {
    const glint::SphereDescription& s = spheres[i];
    const double r = s.radius;
    double bound = p.max_radius;
    const float coords[] = {s.center.x, s.center.y, s.center.z};
    for (const float c : coords)
      bound = std::min(bound, half - std::abs(double(c)) - gap);
    for (int w = 0; w < result.wall_count; ++w) {
      const glint::SphereDescription& wall = spheres[std::size_t(w)];
      bound = std::min(bound, wall.radius - distance(s.center, wall.center) - gap);
    }
    forbidden.clear();
    for (std::size_t j = std::size_t(result.wall_count); j < i; ++j) {
      const double d = distance(s.center, spheres[j].center);
      forbidden.emplace_back(std::abs(d - spheres[j].radius) - gap, d + spheres[j].radius + gap);
    }
    const auto allowed = [&](double v) {
      for (const auto& [low, high] : forbidden)
        if (low < v && v < high) return false;
      return v <= bound;
    };
    INFO("sphere " << i << " radius " << r << ", room bound " << bound);
    REQUIRE(allowed(r));
    // The radius was rounded down to a float: a candidate within a few float steps above it
    // is the same answer.
    const double slack = 4.0 * (double(std::nextafter(s.radius, 2.0f * s.radius)) - r);
    std::vector<double> candidates{bound};
    for (const auto& interval : forbidden)
      candidates.push_back(interval.first);
    for (const double v : candidates)
      if (v > r + slack && v <= bound) {
        INFO("a larger radius " << v << " was allowed");
        REQUIRE_FALSE(allowed(v));
      }
  }
}

}  // namespace

TEST_CASE("random scene: any two spheres are disjoint or nested with the gap between them",
          "[generate]") {
  int nested = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto p = crowded_parameters(seed);
    const auto result = glint::generate_random_scene(p);
    CHECK(result.placed > 300);
    nested += check_geometry(p, result).nested_pairs;
  }
  // The crowded scenes must exercise the nested branch, not only the disjoint one.
  CHECK(nested > 20);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto p = sparse_parameters(seed);
    const auto result = glint::generate_random_scene(p);
    CHECK(result.complete());
    check_geometry(p, result);
  }
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const auto p = report_parameters(40, seed);
    check_geometry(p, glint::generate_random_scene(p));
  }
}

TEST_CASE("random scene: every radius is as large as the spheres before it allowed", "[generate]") {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto crowded = crowded_parameters(seed);
    check_radii_are_maximal(crowded, glint::generate_random_scene(crowded));
    const auto report = report_parameters(40, seed);
    check_radii_are_maximal(report, glint::generate_random_scene(report));
  }
}

TEST_CASE("random scene: a domain too small for one grid cell still works", "[generate]") {
  glint::RandomSceneParameters p;
  p.domain_size = 21.0f;
  p.sphere_count = 60;
  p.min_radius = 0.5f;
  p.max_radius = 10.0f;
  const auto result = glint::generate_random_scene(p);
  CHECK(result.placed > 10);
  check_geometry(p, result);
}

TEST_CASE("random scene: the generated scene is valid for the renderer", "[generate]") {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    for (const auto& p : {report_parameters(40, seed), crowded_parameters(seed)}) {
      const auto result = glint::generate_random_scene(p);
      REQUIRE_NOTHROW(glint::validate(result.scene));
      // The renderer's own nesting check, a second independent implementation.
      REQUIRE_NOTHROW(glint::build_inclusion_tree(result.scene));
    }
  }
}

TEST_CASE("random scene: the report's parameters place every sphere", "[generate]") {
  for (const int count : {15, 40}) {
    for (std::uint64_t seed = 1; seed <= 50; ++seed) {
      const auto result = glint::generate_random_scene(report_parameters(count, seed));
      INFO(count << " spheres, seed " << seed);
      CHECK(result.complete());
      CHECK(result.placed == count);
    }
  }
}

TEST_CASE("random scene: a scene too crowded for its count reports what it placed", "[generate]") {
  glint::RandomSceneParameters p = report_parameters(200, 4);
  p.domain_size = 30.0f;
  p.max_attempts = 20;
  glint::RandomSceneResult result;
  REQUIRE_NOTHROW(result = glint::generate_random_scene(p));
  CHECK_FALSE(result.complete());
  CHECK(result.requested == 200);
  CHECK(result.placed > 0);
  CHECK(result.placed < 200);
  CHECK(result.attempts >= 20LL * (200 - result.placed));
  check_geometry(p, result);
}

TEST_CASE("random scene: material frequencies follow the probabilities",
          "[generate][statistical]") {
  // Many spheres at the report's density; a fixed seed makes the outcome reproducible, and the
  // bounds (5 standard deviations of a binomial count) keep it from depending on luck.
  glint::RandomSceneParameters p = report_parameters(30000, 12345);
  p.domain_size = float(80.0 * std::cbrt(30000.0 / 15.0));
  const auto result = glint::generate_random_scene(p);
  REQUIRE(result.complete());
  int diffuse = 0, mirror = 0, transparent = 0;
  double ior_sum = 0.0;
  for (std::size_t i = std::size_t(result.wall_count); i < result.scene.spheres.size(); ++i) {
    const glint::Material& m = result.scene.spheres[i].material;
    if (m.transparent == 1.0f) {
      ++transparent;
      CHECK(m.diffuse == 0.0f);
      CHECK(m.mirror == 0.0f);
      CHECK(m.ior >= 1.1f);
      CHECK(m.ior <= 1.9f);
      ior_sum += m.ior;
    } else if (m.mirror == 1.0f) {
      ++mirror;
      CHECK(m.diffuse == 0.0f);
    } else {
      ++diffuse;
      CHECK(m.diffuse == 1.0f);
      CHECK(m.mirror == 0.0f);
      CHECK(m.transparent == 0.0f);
      CHECK(glint::max_component(m.diffuse_color) <= 0.9f);
      CHECK(std::min({m.diffuse_color.x, m.diffuse_color.y, m.diffuse_color.z}) >= 0.1f);
    }
    CHECK(m.emission == glint::Color(0.0f));
  }
  const double n = result.placed;
  const auto within_binomial = [n](int count, double probability) {
    const double sigma = std::sqrt(n * probability * (1.0 - probability));
    INFO("count " << count << ", expected " << n * probability << " +- " << 5 * sigma);
    CHECK(std::abs(count - n * probability) <= 5.0 * sigma);
  };
  within_binomial(diffuse, 0.15);
  within_binomial(mirror, 0.35);
  within_binomial(transparent, 0.5);
  // Chi-square with 2 degrees of freedom; 30 is exceeded with probability about 3e-7.
  const double chi2 = std::pow(diffuse - 0.15 * n, 2) / (0.15 * n) +
                      std::pow(mirror - 0.35 * n, 2) / (0.35 * n) +
                      std::pow(transparent - 0.5 * n, 2) / (0.5 * n);
  CHECK(chi2 < 30.0);
  // The index is uniform on [1.1, 1.9]: mean 1.5, standard deviation 0.8 / sqrt(12).
  const double ior_sigma = 0.8 / std::sqrt(12.0) / std::sqrt(double(transparent));
  CHECK(std::abs(ior_sum / transparent - 1.5) <= 5.0 * ior_sigma);
}

TEST_CASE("random scene: a probability of 1 gives a single kind of material", "[generate]") {
  glint::RandomSceneParameters p = report_parameters(40, 9);
  p.diffuse_probability = 0.0f;
  p.mirror_probability = 0.0f;
  p.transparent_probability = 1.0f;
  auto result = glint::generate_random_scene(p);
  for (std::size_t i = std::size_t(result.wall_count); i < result.scene.spheres.size(); ++i)
    CHECK(result.scene.spheres[i].material.transparent == 1.0f);
  p.diffuse_probability = 1.0f;
  p.transparent_probability = 0.0f;
  result = glint::generate_random_scene(p);
  for (std::size_t i = std::size_t(result.wall_count); i < result.scene.spheres.size(); ++i)
    CHECK(result.scene.spheres[i].material.diffuse == 1.0f);
}

TEST_CASE("random scene: the same seed gives the same file and another seed another one",
          "[generate]") {
  const auto text = [](const glint::RandomSceneParameters& p) {
    return glint::format_scene(glint::generate_random_scene(p).scene);
  };
  const std::string first = text(report_parameters(40, 17));
  CHECK(text(report_parameters(40, 17)) == first);
  CHECK(text(report_parameters(40, 18)) != first);
  CHECK(text(crowded_parameters(5)) == text(crowded_parameters(5)));
  CHECK(text(crowded_parameters(5)) != text(crowded_parameters(6)));
}

TEST_CASE("random scene: a seed gives the same file with every compiler and flag set",
          "[generate]") {
  // Pinned output. Nothing in the generator may depend on the standard library's
  // distributions, on the order in which a call's arguments are evaluated, or on whether the
  // compiler fuses multiplies and adds; checked with g++ 12 and clang++ 14 at -O0 and at -O3
  // -march=native -ffp-contract=fast. If the generator changes on purpose, update the values.
  const std::string report =
      glint::format_scene(glint::generate_random_scene(report_parameters(15, 1)).scene);
  CHECK(report.find("\nsphere center=25.181429,-0.21786338,4.363367 radius=10 transparent=1 "
                    "ior=1.534\nsphere center=7.381778,-28.160048,-24.453999 radius=10 "
                    "mirror=1\n") != std::string::npos);
  const std::string crowded =
      glint::format_scene(glint::generate_random_scene(crowded_parameters(5)).scene);
  std::uint64_t fnv = 0xcbf29ce484222325ULL;  // FNV-1a
  for (const unsigned char c : crowded)
    fnv = (fnv ^ c) * 0x100000001b3ULL;
  CHECK(crowded.size() == 56892);
  CHECK(fnv == 0x46f5f659fe399649ULL);
}

TEST_CASE("random scene: a scene with fewer spheres is a prefix of one with more", "[generate]") {
  // Each sphere draws from its own stream, so asking for more spheres never changes the first.
  const auto small = glint::generate_random_scene(crowded_parameters(3));
  auto more_parameters = crowded_parameters(3);
  more_parameters.sphere_count = 1000;
  const auto more = glint::generate_random_scene(more_parameters);
  REQUIRE(more.scene.spheres.size() >= small.scene.spheres.size());
  for (std::size_t i = 0; i < small.scene.spheres.size(); ++i) {
    const auto& a = small.scene.spheres[i];
    const auto& b = more.scene.spheres[i];
    REQUIRE(a.center == b.center);
    REQUIRE(a.radius == b.radius);
    REQUIRE(a.material.ior == b.material.ior);
  }
}

TEST_CASE("random scene: the room and camera and lights frame the domain", "[generate]") {
  const auto p = report_parameters(40, 2);
  const auto result = glint::generate_random_scene(p);
  const glint::SceneDescription& scene = result.scene;
  const double half = 0.5 * double(p.domain_size);
  const auto inside_every_wall = [&](const glint::Vec3& point) {
    for (int w = 0; w < result.wall_count; ++w) {
      const auto& wall = scene.spheres[std::size_t(w)];
      if (distance(point, wall.center) >= wall.radius) return false;
    }
    return true;
  };
  const auto outside_every_sphere = [&](const glint::Vec3& point) {
    for (std::size_t i = std::size_t(result.wall_count); i < scene.spheres.size(); ++i)
      if (distance(point, scene.spheres[i].center) <= scene.spheres[i].radius) return false;
    return true;
  };
  // The six walls bound the domain on every side: the points just outside each face centre
  // are outside some wall, the domain's corners inside all of them.
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {-1.0, 1.0}) {
      if (axis == 2 && sign > 0) continue;  // the room extends towards the camera
      glint::Vec3 beyond(0.0f);
      beyond[axis] = float(sign * (half + 0.01));
      CHECK_FALSE(inside_every_wall(beyond));
    }
  for (const float x : {-1.0f, 1.0f})
    for (const float y : {-1.0f, 1.0f})
      for (const float z : {-1.0f, 1.0f})
        CHECK(inside_every_wall(glint::Vec3(x, y, z) * float(half - 0.02)));
  // Left red, right green, as in the report's room.
  const auto& left = scene.spheres[0];
  const auto& right = scene.spheres[1];
  CHECK(left.center.x > 0.0f);  // the left wall's surface is at x = -s/2, its centre far right
  CHECK(left.material.diffuse_color.x > left.material.diffuse_color.y);
  CHECK(right.material.diffuse_color.y > right.material.diffuse_color.x);
  for (int w = 0; w < result.wall_count; ++w)
    CHECK(scene.spheres[std::size_t(w)].radius >= 1e5f);

  CHECK(inside_every_wall(scene.camera.position));
  CHECK(outside_every_sphere(scene.camera.position));
  REQUIRE_FALSE(scene.lights.empty());
  for (const auto& light : scene.lights) {
    CHECK(inside_every_wall(light.position));
    CHECK(outside_every_sphere(light.position));
    CHECK(light.intensity > 0.0f);
  }
  // The whole front face of the domain is in the (square) field of view.
  const double camera_z = scene.camera.position.z;
  REQUIRE(camera_z > half);
  CHECK(scene.camera.look_at == glint::Vec3(0.0f));
  const double tan_half_fov =
      std::tan(double(scene.camera.fov_degrees) * 3.14159265358979323846 / 360.0);
  CHECK(half / (camera_z - half) <= tan_half_fov);
  // The report's render settings, which are glint's defaults.
  CHECK(scene.image.width == glint::defaults::image_width);
  CHECK(scene.image.height == glint::defaults::image_height);
  CHECK(scene.image.samples_per_pixel == glint::defaults::samples_per_pixel);
  CHECK(scene.image.max_depth == glint::defaults::max_depth);
}

TEST_CASE("random scene: bad parameters are refused with a message naming them", "[generate]") {
  struct Case {
    const char* problem;
    std::function<void(glint::RandomSceneParameters&)> change;
  };
  const Case cases[] = {
      {"minimum radius 11 is larger than maximum radius 10", [](auto& p) { p.min_radius = 11; }},
      {"diffuse, mirror and transparent probabilities must sum to 1, got 1.05",
       [](auto& p) { p.mirror_probability = 0.4f; }},
      {"diffuse, mirror and transparent probabilities must sum to 1, got 0.5",
       [](auto& p) { p.transparent_probability = 0.0f; }},
      {"mirror probability must be in [0, 1], got -0.1",
       [](auto& p) {
         p.mirror_probability = -0.1f;
         p.transparent_probability = 0.95f;
       }},
      {"domain size must be positive and finite, got -80", [](auto& p) { p.domain_size = -80; }},
      {"domain size must be positive and finite, got 0", [](auto& p) { p.domain_size = 0; }},
      {"domain size must be positive and finite, got nan", [](auto& p) { p.domain_size = NAN; }},
      {"domain size must be at most 1e+06, got 2e+06", [](auto& p) { p.domain_size = 2e6f; }},
      {"sphere count must be between 1 and 100000000, got 0", [](auto& p) { p.sphere_count = 0; }},
      {"sphere count must be between 1 and 100000000, got -5",
       [](auto& p) { p.sphere_count = -5; }},
      {"minimum radius must be positive and finite, got 0", [](auto& p) { p.min_radius = 0; }},
      {"maximum radius must be positive and finite, got -1", [](auto& p) { p.max_radius = -1; }},
      {"maximum radius must be positive and finite, got inf",
       [](auto& p) { p.max_radius = INFINITY; }},
      {"maximum radius 40 is too large for a domain of size 80 (a sphere and its gap must fit: "
       "2 * (radius + gap) <= size)",
       [](auto& p) { p.max_radius = 40; }},
      {"gap fraction must be in (0, 1], got 0", [](auto& p) { p.gap_fraction = 0; }},
      {"attempts per sphere must be between 1 and 1000000, got 0",
       [](auto& p) { p.max_attempts = 0; }},
      {"the gap between spheres (0.001 = gap fraction * minimum radius) is too small for float "
       "positions in a domain of size 9e+05; raise the minimum radius or shrink the domain",
       [](auto& p) {
         p.domain_size = 9e5f;
         p.min_radius = 0.1f;
       }},
  };
  for (const Case& c : cases) {
    glint::RandomSceneParameters p = report_parameters(15, 1);
    c.change(p);
    INFO(c.problem);
    try {
      glint::validate(p);
      FAIL("validate accepted the parameters");
    } catch (const glint::RandomSceneError& e) {
      CHECK(e.problem() == c.problem);
      CHECK(std::string(e.what()) == "random scene: " + std::string(c.problem));
    }
    // A program can catch every library error as glint::Error.
    CHECK_THROWS_AS(glint::generate_random_scene(p), glint::Error);
    CHECK_THROWS_AS(glint::generate_random_scene(p), glint::RandomSceneError);
  }
  CHECK_NOTHROW(glint::validate(report_parameters(15, 1)));
  // Probabilities typed as decimals do not sum to exactly 1 in float; that is fine.
  glint::RandomSceneParameters p = report_parameters(15, 1);
  p.diffuse_probability = 0.1f;
  p.mirror_probability = 0.2f;
  p.transparent_probability = 0.7f;
  CHECK_NOTHROW(glint::validate(p));
}

TEST_CASE("random scene: the written file reads back to the same description", "[generate][io]") {
  for (const auto& p : {report_parameters(40, 21), crowded_parameters(21)}) {
    const glint::SceneDescription scene = glint::generate_random_scene(p).scene;
    const std::string text = glint::format_scene(scene);
    const glint::SceneDescription read = glint::read_scene_text(text, "random.scene");
    REQUIRE(read.spheres.size() == scene.spheres.size());
    REQUIRE(read.lights.size() == scene.lights.size());
    // Writing what was read gives the same text, and the text pins down every float bit.
    CHECK(glint::format_scene(read) == text);
    for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
      const auto& a = scene.spheres[i];
      const auto& b = read.spheres[i];
      REQUIRE(std::bit_cast<std::uint32_t>(a.radius) == std::bit_cast<std::uint32_t>(b.radius));
      REQUIRE(a.center == b.center);
      REQUIRE(a.material.diffuse == b.material.diffuse);
      REQUIRE(a.material.mirror == b.material.mirror);
      REQUIRE(a.material.transparent == b.material.transparent);
      REQUIRE(a.material.ior == b.material.ior);
      REQUIRE(a.material.diffuse_color == b.material.diffuse_color);
    }
    REQUIRE_NOTHROW(glint::build_inclusion_tree(read));
  }
}
