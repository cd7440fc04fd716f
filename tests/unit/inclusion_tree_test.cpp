// The inclusion precomputation: sphere relations, the refractive index outside each sphere,
// and the rejection of partially overlapping transparent spheres; random configurations are
// checked against an O(n^2) reference written here.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "glint/math/random.hpp"
#include "glint/scene/inclusion_tree.hpp"

using glint::SphereRelation;
using glint::Vec3;

namespace {

glint::SphereDescription sphere(Vec3 center, float radius, int line = 0) {
  glint::SphereDescription s;
  s.center = center;
  s.radius = radius;
  s.line = line;
  return s;
}

glint::SphereDescription glass(Vec3 center, float radius, float ior, int line = 0) {
  glint::SphereDescription s = sphere(center, radius, line);
  s.material.diffuse = 0.0f;
  s.material.transparent = 1.0f;
  s.material.ior = ior;
  return s;
}

glint::SphereDescription opaque(Vec3 center, float radius, int line = 0) {
  glint::SphereDescription s = sphere(center, radius, line);
  s.material.diffuse = 0.7f;
  s.material.mirror = 0.3f;
  s.material.ior = 7.0f;  // irrelevant for an opaque sphere: must never leak out
  return s;
}

glint::SceneDescription scene_of(std::vector<glint::SphereDescription> spheres,
                                 float medium = 1.0f) {
  glint::SceneDescription scene;
  scene.source = "test.scene";
  scene.medium_ior = medium;
  scene.spheres = std::move(spheres);
  return scene;
}

}  // namespace

TEST_CASE("classify_spheres", "[inclusion]") {
  const auto classify = [](Vec3 ca, float ra, Vec3 cb, float rb) {
    return glint::classify_spheres(sphere(ca, ra), sphere(cb, rb));
  };
  SECTION("disjoint") {
    CHECK(classify({0, 0, 0}, 1, {3, 0, 0}, 1) == SphereRelation::disjoint);
    CHECK(classify({0, 0, 0}, 1, {0, 5, 5}, 2) == SphereRelation::disjoint);
  }
  SECTION("externally tangent counts as disjoint") {
    CHECK(classify({0, 0, 0}, 1, {2, 0, 0}, 1) == SphereRelation::disjoint);
    CHECK(classify({0, 0, 0}, 1, {0, 0, 3}, 2) == SphereRelation::disjoint);
  }
  SECTION("nested, either order") {
    CHECK(classify({0.5f, 0, 0}, 1, {0, 0, 0}, 3) == SphereRelation::first_inside_second);
    CHECK(classify({0, 0, 0}, 3, {0.5f, 0, 0}, 1) == SphereRelation::second_inside_first);
    CHECK(classify({0, 0, 0}, 1, {0, 0, 0}, 2) == SphereRelation::first_inside_second);
  }
  SECTION("internally tangent counts as nested") {
    CHECK(classify({2, 0, 0}, 1, {0, 0, 0}, 3) == SphereRelation::first_inside_second);
    CHECK(classify({0, 0, 0}, 3, {0, -2, 0}, 1) == SphereRelation::second_inside_first);
  }
  SECTION("coincident spheres overlap") {
    CHECK(classify({1, 2, 3}, 2, {1, 2, 3}, 2) == SphereRelation::overlapping);
  }
  SECTION("partial overlap") {
    CHECK(classify({0, 0, 0}, 1, {1.5f, 0, 0}, 1) == SphereRelation::overlapping);
    CHECK(classify({0, 0, 0}, 3, {2.5f, 0, 0}, 1) == SphereRelation::overlapping);
    // Just past internal tangency.
    CHECK(classify({2.001f, 0, 0}, 1, {0, 0, 0}, 3) == SphereRelation::overlapping);
  }
}

TEST_CASE("outside_ior of transparent and opaque spheres", "[inclusion]") {
  SECTION("a glass bubble: the air sphere inside glass sees glass outside") {
    const auto tree = glint::build_inclusion_tree(
        scene_of({glass({0, 0, 0}, 10, 1.5f), glass({1, 2, 0}, 2, 1.0f)}));
    CHECK(tree.outside_ior[0] == 1.0f);
    CHECK(tree.outside_ior[1] == 1.5f);
    CHECK(tree.parent[0] == glint::kNoParent);
    CHECK(tree.parent[1] == 0u);
  }
  SECTION("denser glass inside lighter glass") {
    const auto tree = glint::build_inclusion_tree(
        scene_of({glass({0, 0, 0}, 3, 1.7f), glass({0, 0, 0}, 10, 1.3f)}));
    CHECK(tree.outside_ior[0] == 1.3f);
    CHECK(tree.outside_ior[1] == 1.0f);
  }
  SECTION("three levels") {
    const auto tree = glint::build_inclusion_tree(scene_of(
        {glass({0, 0, 0}, 1, 1.6f), glass({0.5f, 0, 0}, 5, 1.4f), glass({1, 1, 0}, 20, 1.2f)}));
    CHECK(tree.outside_ior[2] == 1.0f);
    CHECK(tree.outside_ior[1] == 1.2f);
    CHECK(tree.outside_ior[0] == 1.4f);
    CHECK(tree.parent[0] == 1u);
    CHECK(tree.parent[1] == 2u);
  }
  SECTION("siblings inside one container") {
    const auto tree = glint::build_inclusion_tree(scene_of(
        {glass({0, 0, 0}, 10, 1.33f), glass({-4, 0, 0}, 3, 1.5f), glass({4, 0, 0}, 3, 1.9f),
         glass({0, 6, 0}, 2, 1.1f), glass({30, 0, 0}, 1, 2.0f)}));
    CHECK(tree.outside_ior[0] == 1.0f);
    CHECK(tree.outside_ior[1] == 1.33f);
    CHECK(tree.outside_ior[2] == 1.33f);
    CHECK(tree.outside_ior[3] == 1.33f);
    CHECK(tree.outside_ior[4] == 1.0f);
  }
  SECTION("opaque spheres may cut through glass and take no part") {
    glint::InclusionTree tree;
    REQUIRE_NOTHROW(tree = glint::build_inclusion_tree(
                        scene_of({glass({0, 0, 0}, 5, 1.5f), opaque({4, 0, 0}, 3),
                                  opaque({5, 0, 0}, 3), glass({0.5f, 0, 0}, 1, 1.8f)})));
    CHECK(tree.outside_ior[0] == 1.0f);
    CHECK(tree.outside_ior[1] == 1.0f);  // straddles the glass: in no transparent sphere
    CHECK(tree.parent[1] == glint::kNoParent);
    CHECK(tree.outside_ior[3] == 1.5f);  // the opaque ior 7 never matters
  }
  SECTION("an opaque sphere inside glass sits in the glass") {
    const auto tree =
        glint::build_inclusion_tree(scene_of({opaque({1, 0, 0}, 1), glass({0, 0, 0}, 4, 1.5f)}));
    CHECK(tree.parent[0] == 1u);
    CHECK(tree.outside_ior[0] == 1.5f);
  }
  SECTION("glass inside an opaque sphere sees the medium: opaque spheres have no inside") {
    const auto tree = glint::build_inclusion_tree(
        scene_of({opaque({0, 0, 0}, 10), glass({0, 0, 0}, 2, 1.5f)}, 1.2f));
    CHECK(tree.outside_ior[1] == 1.2f);
    CHECK(tree.parent[1] == glint::kNoParent);
  }
  SECTION("a medium other than air") {
    const auto tree = glint::build_inclusion_tree(scene_of(
        {glass({0, 0, 0}, 3, 1.5f), opaque({10, 0, 0}, 1), glass({0, 0, 0}, 1, 2.4f)}, 1.33f));
    CHECK(tree.outside_ior[0] == 1.33f);
    CHECK(tree.outside_ior[1] == 1.33f);
    CHECK(tree.outside_ior[2] == 1.5f);
  }
  SECTION("tangent transparent spheres are accepted") {
    const auto tree = glint::build_inclusion_tree(scene_of(
        {glass({0, 0, 0}, 1, 1.5f), glass({2, 0, 0}, 1, 1.6f), glass({1, 0, 0}, 2, 1.2f)}));
    CHECK(tree.outside_ior[0] == 1.2f);  // internally tangent to the big one
    CHECK(tree.outside_ior[1] == 1.2f);
    CHECK(tree.outside_ior[2] == 1.0f);
  }
}

TEST_CASE("partially overlapping transparent spheres are rejected, naming both lines",
          "[inclusion]") {
  const auto expect_error = [](const glint::SceneDescription& scene, int first, int second) {
    try {
      (void)glint::build_inclusion_tree(scene);
      FAIL("no SceneError");
    } catch (const glint::SceneError& e) {
      const std::string message = e.what();
      INFO(message);
      CHECK(message.rfind("test.scene:", 0) == 0);
      CHECK(message.find(std::to_string(first)) != std::string::npos);
      CHECK(message.find(std::to_string(second)) != std::string::npos);
      CHECK((e.line() == first || e.line() == second));
    }
  };
  SECTION("two spheres") {
    expect_error(scene_of({glass({0, 0, 0}, 1, 1.5f, 31), glass({1.5f, 0, 0}, 1, 1.5f, 57)}), 31,
                 57);
  }
  SECTION("found among many, whatever the order") {
    std::vector<glint::SphereDescription> spheres;
    for (int i = 0; i < 20; ++i)
      spheres.push_back(glass({float(i) * 3.0f, 0, 0}, 1, 1.5f, 100 + i));
    spheres.push_back(glass({30.5f, 0, 0}, 0.8f, 1.5f, 913));  // cuts the sphere at 30 (line 110)
    expect_error(scene_of(spheres), 110, 913);
    std::reverse(spheres.begin(), spheres.end());
    expect_error(scene_of(spheres), 110, 913);
  }
  SECTION("coincident transparent spheres") {
    expect_error(scene_of({glass({1, 1, 1}, 2, 1.5f, 44), glass({1, 1, 1}, 2, 1.3f, 45)}), 44, 45);
  }
  SECTION("glass overlapping a bubble inside other glass") {
    expect_error(scene_of({glass({0, 0, 0}, 10, 1.5f, 3), glass({0, 0, 0}, 2, 1.0f, 4),
                           glass({2.5f, 0, 0}, 1, 1.7f, 5)}),
                 4, 5);
  }
}

namespace {

// ---- random configurations against an O(n^2) reference ------------------------------------

double distance(const glint::SphereDescription& a, const glint::SphereDescription& b) {
  const double dx = double(a.center.x) - b.center.x, dy = double(a.center.y) - b.center.y,
               dz = double(a.center.z) - b.center.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// True if `inner` lies inside `outer` (touching allowed), and they are not the same sphere.
bool contains(const glint::SphereDescription& outer, const glint::SphereDescription& inner) {
  const double d = distance(outer, inner);
  if (d == 0.0 && outer.radius == inner.radius) return false;
  return d + inner.radius <= outer.radius;
}

bool partially_overlap(const glint::SphereDescription& a, const glint::SphereDescription& b) {
  const double d = distance(a, b);
  return d < double(a.radius) + b.radius && !contains(a, b) && !contains(b, a);
}

/// The index just outside each sphere: that of the smallest transparent sphere containing it.
std::vector<float> reference_outside_ior(const glint::SceneDescription& scene) {
  std::vector<float> result;
  for (const auto& s : scene.spheres) {
    float ior = scene.medium_ior;
    float smallest = std::numeric_limits<float>::infinity();
    for (const auto& other : scene.spheres) {
      if (&other == &s || !other.material.is_transparent() || !contains(other, s)) continue;
      if (other.radius < smallest) {
        smallest = other.radius;
        ior = other.material.ior;
      }
    }
    result.push_back(ior);
  }
  return result;
}

bool reference_rejects(const glint::SceneDescription& scene) {
  for (std::size_t i = 0; i < scene.spheres.size(); ++i)
    for (std::size_t j = i + 1; j < scene.spheres.size(); ++j)
      if (scene.spheres[i].material.is_transparent() &&
          scene.spheres[j].material.is_transparent() &&
          partially_overlap(scene.spheres[i], scene.spheres[j]))
        return true;
  return false;
}

float uniform(glint::Pcg32& rng, float lo, float hi) {
  return lo + (hi - lo) * rng.next_float();
}

/// Spheres of many sizes along a long strip (so that the sweep prunes), a third of them
/// opaque. With `valid`, transparent spheres that would partially overlap another transparent
/// sphere, or come within 1e-3 of tangency, are redrawn.
glint::SceneDescription random_scene(glint::Pcg32& rng, int count, bool valid) {
  glint::SceneDescription scene;
  scene.source = "random";
  scene.medium_ior = uniform(rng, 1.0f, 1.4f);
  int attempts = 0;
  while (int(scene.spheres.size()) < count && attempts++ < 100000) {
    const bool transparent = rng.next_u32() % 3 != 0;
    glint::SphereDescription s =
        transparent ? glass({}, 1, uniform(rng, 1.0f, 2.5f)) : opaque({}, 1);
    s.center = {uniform(rng, 0.0f, 200.0f), uniform(rng, -10.0f, 10.0f),
                uniform(rng, -10.0f, 10.0f)};
    s.radius = 0.3f * std::pow(60.0f, rng.next_float());
    s.line = int(scene.spheres.size()) + 1;
    if (valid && transparent) {
      bool ok = true;
      for (const auto& other : scene.spheres) {
        if (!other.material.is_transparent()) continue;
        const double d = distance(s, other);
        const double margin = 1e-3;
        const bool clear = d > double(s.radius) + other.radius + margin ||
                           d + s.radius < other.radius - margin ||
                           d + other.radius < s.radius - margin;
        if (!clear) ok = false;
      }
      if (!ok) continue;
    }
    scene.spheres.push_back(s);
  }
  return scene;
}

}  // namespace

TEST_CASE("inclusion tree of random nested configurations matches the O(n^2) reference",
          "[inclusion]") {
  glint::Pcg32 rng(4242u, 1u);
  int nested = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const glint::SceneDescription scene = random_scene(rng, 20 + trial * 5, true);
    REQUIRE_FALSE(reference_rejects(scene));
    const glint::InclusionTree tree = glint::build_inclusion_tree(scene);
    const std::vector<float> expected = reference_outside_ior(scene);
    REQUIRE(tree.outside_ior.size() == scene.spheres.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
      INFO("trial " << trial << ", sphere " << i);
      CHECK(tree.outside_ior[i] == expected[i]);
      if (tree.parent[i] != glint::kNoParent) {
        CHECK(contains(scene.spheres[tree.parent[i]], scene.spheres[i]));
        ++nested;
      }
    }
  }
  CHECK(nested > 100);  // the configurations did nest
}

TEST_CASE("inclusion tree does not depend on the order of the spheres", "[inclusion]") {
  glint::Pcg32 rng(77u, 2u);
  for (int trial = 0; trial < 20; ++trial) {
    const glint::SceneDescription scene = random_scene(rng, 60, true);
    const glint::InclusionTree tree = glint::build_inclusion_tree(scene);
    glint::SceneDescription shuffled = scene;
    for (std::size_t i = shuffled.spheres.size(); i > 1; --i)
      std::swap(shuffled.spheres[i - 1], shuffled.spheres[rng.next_u32() % i]);
    const glint::InclusionTree shuffled_tree = glint::build_inclusion_tree(shuffled);
    for (std::size_t i = 0; i < shuffled.spheres.size(); ++i) {
      const auto original = std::size_t(shuffled.spheres[i].line - 1);  // lines are 1-based
      CHECK(shuffled_tree.outside_ior[i] == tree.outside_ior[original]);
    }
  }
  // The same for a hand-made nest listed innermost first and outermost first.
  std::vector<glint::SphereDescription> nest = {
      glass({0, 0, 0}, 1, 1.9f), glass({0, 0, 0}, 2, 1.7f), glass({0, 0, 0}, 3, 1.5f),
      glass({0, 0, 0}, 4, 1.3f)};
  const auto inner_first = glint::build_inclusion_tree(scene_of(nest));
  std::reverse(nest.begin(), nest.end());
  const auto outer_first = glint::build_inclusion_tree(scene_of(nest));
  for (std::size_t i = 0; i < 4; ++i)
    CHECK(inner_first.outside_ior[i] == outer_first.outside_ior[3 - i]);
  CHECK(inner_first.outside_ior[0] == 1.7f);
  CHECK(inner_first.outside_ior[3] == 1.0f);
}

TEST_CASE("random overlapping configurations are rejected exactly when the reference says so",
          "[inclusion]") {
  glint::Pcg32 rng(99u, 3u);
  int rejected = 0, accepted = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const glint::SceneDescription scene = random_scene(rng, 2 + trial % 12, false);
    const bool expected = reference_rejects(scene);
    bool threw = false;
    try {
      (void)glint::build_inclusion_tree(scene);
    } catch (const glint::SceneError&) {
      threw = true;
    }
    INFO("trial " << trial);
    CHECK(threw == expected);
    (threw ? rejected : accepted) += 1;
  }
  CHECK(rejected > 10);
  CHECK(accepted > 10);
}
