// The hierarchy must answer exactly like a brute-force scan of intersect_sphere (with the rule
// for an origin on a crossing sphere, sphere_kernel.hpp): same nearest sphere, same distance,
// same occlusion verdict, for random rays through random sphere sets,
// including degenerate ones (all centres equal, all in a plane, one huge sphere among tiny ones).

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <vector>

#include "glint/geometry/sphere_bvh.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/math/random.hpp"
#include "glint/math/sampling.hpp"

namespace {

using glint::SphereBvh;
using glint::Vec3;

struct BruteForce {
  std::vector<SphereBvh::Input> spheres;

  glint::SphereHit closest(const glint::Ray& ray) const {
    glint::SphereHit best;
    best.t = ray.t_max;
    for (const auto& s : spheres) {
      if (s.id == ray.origin_sphere) continue;
      const float r2 = s.radius * s.radius;
      const glint::SphereQuadratic q = glint::quadratic(
          glint::line_lane(ray.origin, ray.direction),
          glint::BasicSphereLanes<glint::Lanes1>{s.center.x, s.center.y, s.center.z, r2});
      if (!(q.discriminant >= 0.0f)) continue;
      // An origin on this sphere too (a duplicate of the one the ray leaves): t = 0 heading in,
      // no hit heading out. The tolerance of sphere_kernel.hpp, c^2 < 8 tol^2 r^2 (|o|^2 + r^2),
      // in its order of operations.
      const bool leaves_sphere = ray.origin_sphere != glint::kNoSphere && ray.t_min <= 0.0f;
      const float factor = leaves_sphere ? glint::kOnSurfaceFactor : 0.0f;
      const glint::Vec3& o = ray.origin;
      const float tolerance =
          r2 * std::fma(factor, r2, factor * std::fma(o.x, o.x, std::fma(o.y, o.y, o.z * o.z)));
      if (q.c * q.c < tolerance) {
        if (q.b < 0.0f && (0.0f < best.t || (best.t == 0.0f && s.id < best.sphere))) {
          best.t = 0.0f;
          best.sphere = s.id;
        }
        continue;
      }
      const glint::SphereRoots roots = glint::roots_of(q);
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
  const Vec3 d = glint::sample_uniform_hemisphere(glint::Vec2(rng.next_float(), rng.next_float()));
  return rng.next_float() < 0.5f ? d : -d;
}

void check_against_reference(const std::vector<SphereBvh::Input>& spheres, std::uint64_t seed,
                             float extent) {
  const SphereBvh bvh(spheres);
  REQUIRE(bvh.size() == spheres.size());
  const BruteForce reference{spheres};
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

namespace {

/// Rays that stress the leaf cull: grazing a sphere (passing at exactly its radius, and a
/// hair inside and outside), leaving one from its surface, from inside nested spheres, far
/// from a huge one.
std::vector<glint::Ray> hard_rays(const std::vector<SphereBvh::Input>& spheres, glint::Pcg32& rng,
                                  float extent, int count) {
  std::vector<glint::Ray> rays;
  for (int i = 0; i < count; ++i) {
    const SphereBvh::Input& s = spheres[rng.next_u32() % spheres.size()];
    glint::Ray ray;
    ray.direction = random_direction(rng);
    // A unit vector perpendicular to the direction.
    const Vec3 side = glm::normalize(glm::cross(
        ray.direction, std::abs(ray.direction.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    switch (i % 4) {
      case 0: {  // grazing: the ray's closest approach to the centre is (about) the radius
        const float scale = 1.0f + (rng.next_float() - 0.5f) * 2e-6f;
        ray.origin =
            s.center + side * (s.radius * scale) - ray.direction * (2.0f * s.radius + 1.0f);
        break;
      }
      case 1: {  // leaving the sphere from its surface
        ray.origin = s.center + random_direction(rng) * s.radius;
        ray.origin_sphere = s.id;
        break;
      }
      case 2:  // from the centre (inside, and inside any sphere nested around it)
        ray.origin = s.center;
        break;
      default:  // anywhere, far
        ray.origin = random_point(rng, 3.0f * extent);
        break;
    }
    if (i % 7 == 0) ray.t_max = rng.next_float() * extent;
    rays.push_back(ray);
  }
  return rays;
}

}  // namespace

TEST_CASE("bvh matches brute force on grazing, leaving, nested and huge-sphere rays", "[bvh]") {
  glint::Pcg32 rng(21, 5);
  std::vector<SphereBvh::Input> spheres;
  for (std::uint32_t i = 0; i < 2000; ++i)
    spheres.push_back({random_point(rng, 100.0f), 0.2f + 5.0f * rng.next_float(), i});
  for (std::uint32_t i = 0; i < 40; ++i)  // nested around one centre
    spheres.push_back({Vec3(3.0f, -2.0f, 1.0f), 0.5f + 0.5f * float(i), 2000 + i});
  spheres.push_back({Vec3(0.0f, -1e5f - 60.0f, 0.0f), 1e5f, 3000});  // a huge wall
  spheres.push_back({Vec3(5.0f, 5.0f, 5.0f), 2.0f, 3001});           // duplicates: a tie
  spheres.push_back({Vec3(5.0f, 5.0f, 5.0f), 2.0f, 3002});
  const SphereBvh bvh(spheres);
  const BruteForce reference{spheres};
  int hits = 0;
  for (const glint::Ray& ray : hard_rays(spheres, rng, 100.0f, 20000)) {
    const glint::SphereHit expected = reference.closest(ray);
    glint::SphereHit actual;
    actual.t = ray.t_max;
    const bool found = bvh.closest_hit(ray, actual);
    REQUIRE(found == (expected.sphere != glint::kNoSphere));
    if (found) {
      ++hits;
      REQUIRE(actual.sphere == expected.sphere);
      REQUIRE(std::memcmp(&actual.t, &expected.t, sizeof(float)) == 0);
    }
    REQUIRE(bvh.any_hit(ray) == found);
  }
  CHECK(hits > 10000);
}

TEST_CASE("the leaf groups hold each leaf's spheres, as the binary tree has them", "[bvh]") {
  glint::Pcg32 rng(31, 1);
  std::vector<SphereBvh::Input> spheres;
  for (std::uint32_t i = 0; i < 5000; ++i)
    spheres.push_back({random_point(rng, 300.0f), 0.1f + 3.0f * rng.next_float(), i * 2 + 1});
  glint::bvh::BinaryTree tree = glint::bvh::build_binary_tree(spheres, 1);
  std::vector<glint::bvh::WideNode> wide = glint::bvh::collapse_to_wide(tree.nodes);
  const std::vector<glint::bvh::WideNode> before = wide;
  const std::vector<glint::SphereGroup> groups = glint::bvh::group_leaves(wide, tree.spheres);
  const glint::GroupedSpheres grouped{groups.data()};
  std::size_t leaf_spheres = 0;
  std::vector<bool> group_used(groups.size(), false);
  for (std::size_t n = 0; n < wide.size(); ++n)
    for (int c = 0; c < glint::bvh::kWideWidth; ++c) {
      const std::uint32_t count = wide[n].count[c];
      if (count == 0) {  // inner and empty slots keep their child
        REQUIRE(wide[n].child[c] == before[n].child[c]);
        continue;
      }
      const std::uint32_t first = wide[n].child[c];
      REQUIRE(first % glint::SphereGroup::kSize == 0);
      REQUIRE(count <= 2 * glint::bvh::kMaxLeafSize);
      for (std::uint32_t i = 0; i < count; ++i) {
        const glint::bvh::LeafSphere& s = tree.spheres[before[n].child[c] + i];
        REQUIRE(grouped.id(first + i) == s.id);
        REQUIRE(grouped.center(first + i) == s.center);
        REQUIRE(grouped.radius_squared(first + i) == s.radius * s.radius);
        // Every sphere inside its leaf's box.
        for (int axis = 0; axis < 3; ++axis) {
          const float lower[3] = {wide[n].lower_x[c], wide[n].lower_y[c], wide[n].lower_z[c]};
          const float upper[3] = {wide[n].upper_x[c], wide[n].upper_y[c], wide[n].upper_z[c]};
          REQUIRE(lower[axis] <= s.center[axis] - s.radius);
          REQUIRE(upper[axis] >= s.center[axis] + s.radius);
        }
      }
      constexpr std::uint32_t kGroupSize = glint::SphereGroup::kSize;
      for (std::uint32_t g = first / kGroupSize; g < (first + count + kGroupSize - 1) / kGroupSize;
           ++g) {
        REQUIRE_FALSE(group_used[g]);  // no two leaves share a group
        group_used[g] = true;
      }
      // The lanes past the leaf's last sphere are padding.
      for (std::uint32_t i = first + count; i % glint::SphereGroup::kSize != 0; ++i)
        REQUIRE(grouped.id(i) == glint::kNoSphere);
      leaf_spheres += count;
    }
  CHECK(leaf_spheres == spheres.size());
}

TEST_CASE("test_grouped_spheres answers as test_spheres, bit for bit", "[bvh]") {
  // Groups of spheres of very different sizes, against rays that graze, leave, start inside
  // or far away; the AVX2 cull must never drop a sphere that test_sphere would hit.
  glint::Pcg32 rng(41, 2);
  std::vector<SphereBvh::Input> spheres;
  for (std::uint32_t i = 0; i < 16 * 64; ++i) {
    const float radius =
        i % 97 == 0 ? 1e4f : (i % 13 == 0 ? 1e-3f : 0.05f + 4.0f * rng.next_float());
    spheres.push_back({random_point(rng, 60.0f), radius, i});
  }
  constexpr std::size_t kGroupSize = glint::SphereGroup::kSize;
  std::vector<glint::SphereGroup> groups(spheres.size() / kGroupSize);
  std::vector<glint::bvh::LeafSphere> flat;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    glint::SphereGroup& g = groups[i / kGroupSize];
    const std::size_t lane = i % kGroupSize;
    g.cx[lane] = spheres[i].center.x;
    g.cy[lane] = spheres[i].center.y;
    g.cz[lane] = spheres[i].center.z;
    g.radius[lane] = spheres[i].radius;
    g.id[lane] = spheres[i].id;
    flat.push_back({spheres[i].center, spheres[i].radius, spheres[i].id});
  }
  struct Flat {
    const glint::bvh::LeafSphere* s;
    Vec3 center(std::size_t i) const { return s[i].center; }
    float radius_squared(std::size_t i) const { return s[i].radius * s[i].radius; }
    std::uint32_t id(std::size_t i) const { return s[i].id; }
  };
  int hits = 0;
  for (const glint::Ray& ray : hard_rays(spheres, rng, 60.0f, 4000)) {
    const glint::GroupRay group_ray(ray);
    for (std::size_t first = 0; first < spheres.size(); first += 16) {
      const std::size_t count = 1 + rng.next_u32() % 16;
      for (const bool stop : {false, true}) {
        glint::SphereHit expected, actual;
        expected.t = actual.t = ray.t_max;
        const bool expected_found = glint::test_spheres(group_ray.one, Flat{flat.data()}, first,
                                                        first + count, expected, stop);
        const bool found =
            glint::test_grouped_spheres(group_ray, groups.data(), first, count, actual, stop);
        // With `stop` both return at the first sphere in index order that test_sphere takes.
        REQUIRE(found == expected_found);
        REQUIRE(actual.sphere == expected.sphere);
        REQUIRE(std::memcmp(&actual.t, &expected.t, sizeof(float)) == 0);
        hits += found ? 1 : 0;
      }
    }
  }
  CHECK(hits > 1000);
}
