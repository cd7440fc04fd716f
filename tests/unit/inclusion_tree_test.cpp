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

#include "glint/io/scene_reader.hpp"
#include "glint/math/random.hpp"
#include "glint/scene/inclusion_tree.hpp"
#include "glint/scene/scene.hpp"
#include "random_vectors.hpp"

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
  SECTION("touching as written, but overlapping by more than the decimals' rounding") {
    // 87.5 + 12.6 = 100.1: 0.1 of overlap; and 87.4001 + 12.6 = 100.0001, 1e-4 of overlap, twice
    // the tolerance at magnitude 100 (100 * 2^-21 = 4.8e-5).
    expect_error(scene_of({glass({0, 0, 0}, 100, 1.5f, 7), glass({87.5f, 0, 0}, 12.6f, 1.3f, 8)}),
                 7, 8);
    expect_error(
        scene_of({glass({0, 0, 0}, 100, 1.5f, 7), glass({87.4001f, 0, 0}, 12.6f, 1.3f, 8)}), 7, 8);
  }
}

TEST_CASE("spheres that touch as written in decimals touch once read as floats", "[inclusion]") {
  // The floats nearest 87.4 and 12.6 add up to 100.0000019: read exactly, the inner sphere
  // pokes 1.9e-6 out of the outer one; so does the radius-2.2 sphere into the radius-1.1 one
  // (by 1.2e-7) when their centres are 3.3 apart. Both within rounding of the decimals.
  const auto classify = [](Vec3 ca, float ra, Vec3 cb, float rb) {
    return glint::classify_spheres(sphere(ca, ra), sphere(cb, rb));
  };
  REQUIRE(double(87.4f) + double(12.6f) > 100.0);
  REQUIRE(double(1.1f) + double(2.2f) > double(3.3f));
  CHECK(classify({87.4f, 0, 0}, 12.6f, {0, 0, 0}, 100) == SphereRelation::first_inside_second);
  CHECK(classify({0, 0, 0}, 100, {0, -87.4f, 0}, 12.6f) == SphereRelation::second_inside_first);
  CHECK(classify({0, 0, 0}, 1.1f, {3.3f, 0, 0}, 2.2f) == SphereRelation::disjoint);
  // Coincident within rounding stays an overlap.
  CHECK(classify({0.1f, 0, 0}, 3.3f, {0.1f + 1e-7f, 0, 0}, 3.3f) == SphereRelation::overlapping);

  // The inclusion tree puts the inner sphere inside, and so does a whole scene read from text.
  const glint::InclusionTree tree = glint::build_inclusion_tree(
      scene_of({glass({0, 0, 0}, 100, 1.5f), glass({87.4f, 0, 0}, 12.6f, 1.2f),
                glass({-87.4f, 0, 0}, 12.6f, 1.7f)}));
  CHECK(tree.parent[1] == 0u);
  CHECK(tree.parent[2] == 0u);
  CHECK(tree.outside_ior[1] == 1.5f);
  CHECK(tree.outside_ior[2] == 1.5f);
  const glint::SceneDescription read = glint::read_scene_text(
      "camera position=0,0,300 look_at=0,0,0 fov=45\n"
      "light position=0,150,150 intensity=1000\n"
      "sphere center=0,0,0 radius=100 transparent=1 diffuse=0 ior=1.5\n"
      "sphere center=87.4,0,0 radius=12.6 transparent=1 diffuse=0 ior=1.2\n",
      "touching.scene");
  const glint::Scene scene = glint::Scene::build(read);
  CHECK(scene.surface(1).ior_outside == 1.5f);
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

using glint::test::uniform;

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

// ---- the fast builder against the reference builder ----------------------------------------

namespace {

/// Both builders on one scene: the same parent and outside index for every sphere, or the same
/// SceneError (message and line). With `fast`, the fast builder must also have answered by
/// itself rather than by falling back on the reference.
void require_same_as_reference(const glint::SceneDescription& scene, bool fast = true) {
  std::string reference_error, error;
  int reference_line = -1, line = -1;
  glint::InclusionTree reference, tree;
  try {
    reference = glint::build_inclusion_tree_reference(scene);
  } catch (const glint::SceneError& e) {
    reference_error = e.what();
    reference_line = e.line();
  }
  try {
    tree = glint::build_inclusion_tree(scene);
  } catch (const glint::SceneError& e) {
    error = e.what();
    line = e.line();
  }
  REQUIRE(error == reference_error);
  REQUIRE(line == reference_line);
  if (!reference_error.empty()) return;
  REQUIRE(tree.parent.size() == scene.spheres.size());
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    INFO("sphere " << i);
    REQUIRE(tree.parent[i] == reference.parent[i]);
    REQUIRE(tree.outside_ior[i] == reference.outside_ior[i]);
  }
  if (fast) REQUIRE(glint::detail::build_inclusion_tree_fast(scene).has_value());
}

void shuffle(glint::Pcg32& rng, std::vector<glint::SphereDescription>& spheres) {
  for (std::size_t i = spheres.size(); i > 1; --i)
    std::swap(spheres[i - 1], spheres[rng.next_u32() % i]);
}

/// Lines follow the list, as the reader numbers them.
glint::SceneDescription numbered(std::vector<glint::SphereDescription> spheres,
                                 float medium = 1.0f) {
  for (std::size_t i = 0; i < spheres.size(); ++i)
    spheres[i].line = int(i) + 10;
  return scene_of(std::move(spheres), medium);
}

/// `count` glass shells around `center`, radii first + k * step, with a tiny opaque sphere
/// between each pair (in the glass of the larger shell, on the surface of neither).
std::vector<glint::SphereDescription> onion(Vec3 center, int count, float first, float step,
                                            glint::Pcg32& rng) {
  std::vector<glint::SphereDescription> spheres;
  for (int k = 0; k < count; ++k) {
    const float radius = first + float(k) * step;
    spheres.push_back(glass(center, radius, uniform(rng, 1.0f, 2.5f)));
    if (k > 0) spheres.push_back(opaque(center + Vec3(radius - 0.5f * step, 0, 0), 0.1f * step));
  }
  return spheres;
}

}  // namespace

TEST_CASE("inclusion tree equals the reference on random nested scenes", "[inclusion]") {
  for (const std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    glint::Pcg32 rng(seed, 11u);
    for (int trial = 0; trial < 6; ++trial) {
      INFO("seed " << seed << ", trial " << trial);
      glint::SceneDescription scene = random_scene(rng, 50 + 60 * trial, true);
      require_same_as_reference(scene);
      shuffle(rng, scene.spheres);
      require_same_as_reference(scene);
    }
  }
}

TEST_CASE("inclusion tree equals the reference on concentric shells", "[inclusion]") {
  glint::Pcg32 rng(8u, 12u);
  SECTION("one onion, outermost first, innermost first, shuffled") {
    std::vector<glint::SphereDescription> spheres = onion({1, 2, 3}, 300, 1.0f, 1.0f, rng);
    require_same_as_reference(numbered(spheres));
    std::reverse(spheres.begin(), spheres.end());
    require_same_as_reference(numbered(spheres));
    shuffle(rng, spheres);
    require_same_as_reference(numbered(spheres, 1.2f));
  }
  SECTION("shells of slowly growing radius, many per power of two") {
    require_same_as_reference(numbered(onion({0, 0, 0}, 400, 100.0f, 0.05f, rng)));
  }
  SECTION("shells whose centres drift, each still inside the next") {
    std::vector<glint::SphereDescription> spheres;
    Vec3 center(0.0f);
    for (int k = 0; k < 300; ++k) {
      const float radius = 1.0f + 0.5f * float(k);
      spheres.push_back(glass(center, radius, 1.5f));
      // The next shell (radius + 0.5) still contains this one with a margin of 0.2.
      center += Vec3(uniform(rng, -0.17f, 0.17f), uniform(rng, -0.17f, 0.17f), 0.0f);
    }
    shuffle(rng, spheres);
    require_same_as_reference(numbered(spheres));
  }
  SECTION("an onion beside a heap of beads, and beads between its shells") {
    std::vector<glint::SphereDescription> spheres = onion({0, 0, 0}, 200, 1.0f, 0.05f, rng);
    for (int k = 0; k < 300; ++k) {
      // Beads in the shell between radius 12 and 20 of a second onion at x = 30, and outside
      // the first onion, whose outer radius is 10.95.
      const Vec3 direction = glm::normalize(
          Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)) + Vec3(1e-3f));
      const float distance = uniform(rng, 12.0f, 20.0f);
      spheres.push_back(glass(direction * distance, 0.02f, 1.7f));
    }
    const auto second = onion({60, 0, 0}, 100, 1.0f, 0.3f, rng);
    spheres.insert(spheres.end(), second.begin(), second.end());
    // The beads may overlap one another; then both builders must name the same pair.
    require_same_as_reference(numbered(spheres), false);
  }
  SECTION("several onions inside one glass block") {
    std::vector<glint::SphereDescription> spheres = {glass({0, 0, 0}, 500, 1.33f)};
    for (int o = 0; o < 8; ++o) {
      const auto shells =
          onion({float(o % 2) * 200 - 100, float(o / 2 % 2) * 200 - 100, float(o / 4) * 200 - 100},
                60, 0.5f, 1.0f, rng);
      spheres.insert(spheres.end(), shells.begin(), shells.end());
    }
    shuffle(rng, spheres);
    require_same_as_reference(numbered(spheres));
  }
}

TEST_CASE("inclusion tree equals the reference on edge cases", "[inclusion]") {
  glint::Pcg32 rng(21u, 13u);
  SECTION("many disjoint equal spheres, touching their neighbours") {
    std::vector<glint::SphereDescription> spheres;
    for (int x = 0; x < 12; ++x)
      for (int y = 0; y < 12; ++y)
        for (int z = 0; z < 4; ++z) {
          const Vec3 center(2.0f * float(x), 2.0f * float(y), 2.0f * float(z));
          spheres.push_back((x + y + z) % 3 == 0 ? opaque(center, 1.0f)
                                                 : glass(center, 1.0f, 1.5f));
        }
    require_same_as_reference(numbered(spheres));
  }
  SECTION("internally tangent chains and externally tangent siblings") {
    std::vector<glint::SphereDescription> spheres;
    for (int k = 0; k < 10; ++k) {  // radius 2^k, all touching the plane x = 1024 from inside
      const float radius = std::ldexp(1.0f, k);
      spheres.push_back(glass({1024.0f - radius, 0, 0}, radius, 1.1f + 0.1f * float(k)));
      spheres.push_back(opaque({1024.0f - radius, 0, 0}, 0.25f));
    }
    spheres.push_back(glass({1020, 0, 0}, 2, 2.0f));  // tangent to the sphere of radius 4
    spheres.push_back(glass({1016, 0, 0}, 2, 2.0f));  // and externally to the previous one
    spheres.push_back(opaque({1018, 0, 0}, 1.0f));    // opaque, cutting both
    require_same_as_reference(numbered(spheres));
    shuffle(rng, spheres);
    require_same_as_reference(numbered(spheres));
  }
  SECTION("duplicates: opaque ones are fine, transparent ones are rejected alike") {
    std::vector<glint::SphereDescription> spheres = {glass({0, 0, 0}, 10, 1.5f)};
    for (int k = 0; k < 50; ++k)
      spheres.push_back(opaque({1, 1, 1}, 2));
    for (int k = 0; k < 50; ++k)
      spheres.push_back(opaque({0, 0, 0}, 10));
    spheres.push_back(glass({1, 1, 1}, 2, 1.2f));
    require_same_as_reference(numbered(spheres));
    spheres.push_back(glass({1, 1, 1}, 2, 1.3f));
    require_same_as_reference(numbered(spheres), false);
  }
  SECTION("walls of radius 1e5 holding everything, or nothing") {
    glint::SceneDescription scene = random_scene(rng, 200, true);
    std::vector<glint::SphereDescription> spheres = scene.spheres;
    spheres.push_back(glass({100, 0, 0}, 1e5f, 1.05f));  // around the whole strip
    spheres.push_back(opaque({100, 1e5f + 100, 0}, 1e5f));
    spheres.push_back(glass({100, -1e5f - 100, 0}, 1e5f, 1.4f));  // clear of everything
    spheres.push_back(glass({100, -1e5f - 100, 0}, 5e4f, 1.3f));  // inside that one
    require_same_as_reference(numbered(spheres));
    shuffle(rng, spheres);
    require_same_as_reference(numbered(spheres));
  }
  SECTION("radii from 1e-3 to 1e5") {
    std::vector<glint::SphereDescription> spheres = {glass({0, 0, 0}, 1e5f, 1.2f)};
    for (int k = 0; k < 200; ++k) {
      const float radius = std::pow(10.0f, uniform(rng, -3.0f, 1.0f));
      const Vec3 center(uniform(rng, -500, 500), uniform(rng, -500, 500), uniform(rng, -500, 500));
      spheres.push_back(glass(center, radius, 1.5f));
      spheres.push_back(glass(center, 0.5f * radius, 1.0f));
      spheres.push_back(opaque(center + Vec3(0.75f * radius, 0, 0), 0.1f * radius));
    }
    require_same_as_reference(numbered(spheres), false);  // rare random overlaps allowed
  }
}

TEST_CASE("inclusion tree names the same overlapping pair as the reference", "[inclusion]") {
  glint::Pcg32 rng(5u, 14u);
  int rejected = 0;
  for (int trial = 0; trial < 200; ++trial) {
    INFO("trial " << trial);
    glint::SceneDescription scene = random_scene(rng, 2 + trial % 40, false);
    if (reference_rejects(scene)) ++rejected;
    require_same_as_reference(scene, false);
  }
  CHECK(rejected > 20);
  // A bead cutting one shell of a deep nest: near its bottom, in its middle (where the shells
  // of one power of two of radius form a long chain), at its top.
  for (const float radius : {1.2f, 1.0f, 6.0f, 6.6f, 10.95f}) {
    INFO("bead on the shell of radius " << radius);
    std::vector<glint::SphereDescription> spheres = onion({0, 0, 0}, 200, 1.0f, 0.05f, rng);
    spheres.push_back(glass({radius, 0, 0}, 0.01f, 1.5f));
    require_same_as_reference(numbered(spheres), false);
    CHECK_THROWS_AS(glint::build_inclusion_tree(numbered(spheres)), glint::SceneError);
  }
  // A sphere inside the first of two nested spheres of a level, cutting the second.
  require_same_as_reference(
      numbered({glass({0, 0, 0}, 10, 1.5f), glass({0, 0, 0}, 9, 1.2f), glass({9, 0, 0}, 1, 1.7f)}),
      false);
}

TEST_CASE("inclusion tree of ten thousand concentric shells", "[inclusion]") {
  // The reference's worst case (n^2/2 nested pairs); here each shell's parent is the next one.
  std::vector<glint::SphereDescription> spheres;
  for (int k = 0; k < 10000; ++k)
    spheres.push_back(glass({0, 0, 0}, 1.0f + float(k), 1.5f));
  const auto tree = glint::build_inclusion_tree(scene_of(spheres));
  for (std::size_t k = 0; k + 1 < spheres.size(); ++k)
    REQUIRE(tree.parent[k] == k + 1);
  CHECK(tree.parent.back() == glint::kNoParent);
}
