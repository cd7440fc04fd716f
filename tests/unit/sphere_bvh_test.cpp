// The hierarchy must answer exactly like a brute-force scan of intersect_sphere: same nearest
// sphere, same distance, same occlusion verdict, for random rays through random sphere sets,
// including degenerate ones (all centres equal, all in a plane, one huge sphere among tiny ones).

#include <catch2/catch.hpp>
#include <cstring>
#include <vector>

#include "glint/geometry/sphere_bvh.hpp"
#include "glint/math/random.hpp"
#include "glint/math/sampling.hpp"

namespace {

using glint::SphereBvh;
using glint::Vec3;

struct Reference {
  std::vector<SphereBvh::Input> spheres;

  glint::SphereHit closest(const glint::Ray& ray) const {
    glint::SphereHit best;
    best.t = ray.t_max;
    for (const auto& s : spheres) {
      if (s.id == ray.origin_sphere) continue;
      glint::SphereRoots roots;
      if (!glint::intersect_sphere(ray.origin, ray.direction, s.center, s.radius, roots)) continue;
      const float t = roots.near > ray.t_min ? roots.near : roots.far;
      // Nearest first, the lowest id at equal t; t_max itself is excluded.
      if (t > ray.t_min && t < ray.t_max && (t < best.t || (t == best.t && s.id < best.sphere))) {
        best.t = t;
        best.sphere = s.id;
      }
    }
    return best;
  }
};

Vec3 random_point(glint::Pcg32& rng, float extent) {
  return {(rng.next_float() - 0.5f) * extent, (rng.next_float() - 0.5f) * extent,
          (rng.next_float() - 0.5f) * extent};
}

Vec3 random_direction(glint::Pcg32& rng) {
  const Vec3 d = glint::sample_uniform_hemisphere({rng.next_float(), rng.next_float()});
  return rng.next_float() < 0.5f ? d : -d;
}

void check_against_reference(const std::vector<SphereBvh::Input>& spheres, std::uint64_t seed,
                             float extent) {
  const SphereBvh bvh(spheres);
  REQUIRE(bvh.size() == spheres.size());
  const Reference reference{spheres};
  glint::Pcg32 rng(seed, 3);
  int hits = 0;
  for (int i = 0; i < 4000; ++i) {
    glint::Ray ray;
    ray.origin = random_point(rng, 1.5f * extent);
    ray.direction = random_direction(rng);
    if (i % 2 == 0 && !spheres.empty()) {  // aim at a sphere so that small sets get hit too
      const Vec3 target = spheres[rng.next_u32() % spheres.size()].center;
      if (glm::length(target - ray.origin) > 0.0f)
        ray.direction = glm::normalize(target - ray.origin);
    }
    if (i % 3 == 0) ray.t_max = rng.next_float() * extent;
    if (i % 5 == 0 && !spheres.empty()) ray.origin_sphere = spheres[i % spheres.size()].id;
    const glint::SphereHit expected = reference.closest(ray);
    glint::SphereHit actual;
    actual.t = ray.t_max;
    const bool found = bvh.closest_hit(ray, actual);
    REQUIRE(found == (expected.sphere != glint::kNoSphere));
    if (found) {
      ++hits;
      REQUIRE(actual.sphere == expected.sphere);
      REQUIRE(actual.t == expected.t);
    }
    REQUIRE(bvh.any_hit(ray) == found);
  }
  CHECK(hits > 500);  // the rays must actually exercise the hierarchy
}

}  // namespace

TEST_CASE("bvh matches brute force on random sphere sets", "[bvh]") {
  for (const int count : {1, 5, 64, 1000}) {
    glint::Pcg32 rng(std::uint64_t(count), 1);
    std::vector<SphereBvh::Input> spheres;
    for (int i = 0; i < count; ++i)
      spheres.push_back(
          {random_point(rng, 100.0f), 0.5f + 4.0f * rng.next_float(), std::uint32_t(i * 3 + 7)});
    check_against_reference(spheres, std::uint64_t(count), 100.0f);
  }
}

TEST_CASE("bvh handles degenerate layouts", "[bvh]") {
  glint::Pcg32 rng(11, 1);
  SECTION("concentric spheres (all centroids equal)") {
    std::vector<SphereBvh::Input> spheres;
    for (int i = 0; i < 200; ++i)
      spheres.push_back({Vec3(1.0f, 2.0f, 3.0f), 1.0f + i * 0.25f, std::uint32_t(i)});
    check_against_reference(spheres, 5, 120.0f);
  }
  SECTION("spheres in a plane") {
    std::vector<SphereBvh::Input> spheres;
    for (int i = 0; i < 300; ++i) {
      Vec3 p = random_point(rng, 100.0f);
      p.y = 0.0f;
      spheres.push_back({p, 1.0f + rng.next_float(), std::uint32_t(i)});
    }
    check_against_reference(spheres, 6, 100.0f);
  }
  SECTION("one huge sphere among small ones") {
    std::vector<SphereBvh::Input> spheres;
    for (int i = 0; i < 300; ++i)
      spheres.push_back({random_point(rng, 100.0f), 1.0f, std::uint32_t(i)});
    spheres.push_back({Vec3(0.0f, -1000.0f, 0.0f), 950.0f, 300u});
    check_against_reference(spheres, 7, 100.0f);
  }
}

TEST_CASE("an empty bvh reports no hits", "[bvh]") {
  const SphereBvh bvh;
  glint::Ray ray;
  glint::SphereHit hit;
  CHECK_FALSE(bvh.closest_hit(ray, hit));
  CHECK_FALSE(bvh.any_hit(ray));
}

TEST_CASE("a tree built on several cores is the tree built on one", "[bvh]") {
  // Past the parallel threshold, with clusters and concentric runs so that the top levels mix
  // SAH and median splits, and leaves are made above the subtrees' ranges.
  glint::Pcg32 rng(99, 1);
  std::vector<SphereBvh::Input> spheres;
  for (std::uint32_t i = 0; i < 150000; ++i) {
    const float spread = i % 3 == 0 ? 1000.0f : 50.0f;
    const Vec3 center = i % 101 == 0 ? Vec3(7.0f) : random_point(rng, spread);
    spheres.push_back({center, 0.1f + rng.next_float(), i});
  }
  const auto build = [&](std::size_t cores) {
    std::vector<SphereBvh::Input> copy = spheres;
    return glint::bvh::build_binary_tree(copy, cores);
  };
  const glint::bvh::BinaryTree one = build(1);
  for (const std::size_t cores : {2, 3, 8}) {
    INFO(cores << " cores");
    const glint::bvh::BinaryTree many = build(cores);
    REQUIRE(many.nodes.size() == one.nodes.size());
    REQUIRE(many.spheres.size() == one.spheres.size());
    CHECK(std::memcmp(many.nodes.data(), one.nodes.data(),
                      one.nodes.size() * sizeof(glint::bvh::Node)) == 0);
    bool same_spheres = true;
    for (std::size_t i = 0; i < one.spheres.size(); ++i)
      same_spheres = same_spheres && one.spheres[i].id == many.spheres[i].id &&
                     one.spheres[i].center == many.spheres[i].center &&
                     one.spheres[i].radius == many.spheres[i].radius;
    CHECK(same_spheres);
  }
}
