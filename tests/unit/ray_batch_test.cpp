// The batched queries (Scene::closest_hits and occluded for eight rays, and for the sixteen of
// two batches) must answer exactly what the single-ray queries answer lane by lane: the same t
// to the bit, the same sphere, the same occlusion verdict, and leave the lanes they were not
// asked about alone. Small scenes
// (walls and the linear set, the ray-parallel kernel) and large ones (the BVH, packet and per
// lane), with random, grazing, surface-leaving and bounded rays, huge walls, nested spheres and
// ties between duplicates.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/sphere_bvh.hpp"
#include "glint/math/random.hpp"
#include "glint/scene/scene.hpp"
#include "random_vectors.hpp"

namespace {

using glint::LaneMask;
using glint::Ray;
using glint::RayBatch;
using glint::Vec3;

constexpr int kWidth = RayBatch::kWidth;

using glint::test::uniform;
using glint::test::unit_vector;

std::uint32_t bits_of(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

struct TestScene {
  std::vector<glint::SphereDescription> spheres;
  glint::SceneDescription description;

  void add(Vec3 center, float radius, bool glass = false) {
    glint::SphereDescription sphere;
    sphere.center = center;
    sphere.radius = radius;
    if (glass) {
      sphere.material.diffuse = 0.0f;
      sphere.material.transparent = 1.0f;
    }
    spheres.push_back(sphere);
  }

  glint::Scene build() {
    description.spheres = spheres;
    return glint::Scene::build(description);
  }
};

/// Six walls of radius `radius` around a box of half side `half`.
void add_room(TestScene& scene, float half, float radius) {
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      Vec3 center(0.0f);
      center[axis] = side * (radius + half);
      scene.add(center, radius);
    }
}

/// `count` random spheres in the cube of half side `half`, with some duplicates (ties) and a
/// few nested glass spheres.
void add_random_spheres(TestScene& scene, glint::Pcg32& rng, int count, float half,
                        float min_radius, float max_radius) {
  const int first = int(scene.spheres.size());
  std::vector<glint::SphereDescription> glass;  // the outer spheres of the glass groups
  for (int i = 0; i < count; ++i) {
    const int kind = int(rng.next_u32() % 10);
    if (kind == 0 && int(scene.spheres.size()) > first) {  // an opaque copy of an earlier sphere
      const auto copy = scene.spheres[std::size_t(first) +
                                      rng.next_u32() % unsigned(int(scene.spheres.size()) - first)];
      scene.add(copy.center, copy.radius);
      continue;
    }
    const Vec3 c(uniform(rng, -half, half), uniform(rng, -half, half), uniform(rng, -half, half));
    const float r = uniform(rng, min_radius, max_radius);
    bool disjoint = true;  // transparent spheres must be disjoint or nested
    for (const glint::SphereDescription& g : glass)
      disjoint = disjoint && glm::length(g.center - c) > 1.01f * (g.radius + r);
    if (kind == 1 && disjoint) {  // nested glass: a shell and two spheres inside it
      glass.push_back({c, r, {}, {}, 0});
      scene.add(c, r, true);
      scene.add(c, 0.6f * r, true);
      scene.add(c + Vec3(0.1f * r, 0.0f, 0.0f), 0.25f * r, true);
      continue;
    }
    scene.add(c, r);
  }
}

/// A ray of one of several kinds: from a random point in a random direction; leaving a
/// sphere's surface outwards or inwards; grazing a sphere; with random t bounds some of the
/// time (shadow rays).
Ray random_ray(glint::Pcg32& rng, const std::vector<glint::SphereDescription>& spheres,
               float half) {
  Ray ray;
  const std::uint32_t kind = rng.next_u32() % 5;
  const auto id = std::uint32_t(rng.next_u32() % spheres.size());
  const glint::SphereDescription& s = spheres[id];
  if (kind == 0 || (s.radius > 1e3f && kind != 4)) {
    ray.origin =
        Vec3(uniform(rng, -half, half), uniform(rng, -half, half), uniform(rng, -half, half));
    ray.direction = unit_vector(rng);
  } else if (kind <= 2) {
    // Leaving the surface: kind 1 inwards, kind 2 outwards.
    const Vec3 normal = unit_vector(rng);
    Vec3 direction = unit_vector(rng);
    if ((glm::dot(direction, normal) < 0.0f) != (kind == 1)) direction = -direction;
    ray = glint::ray_leaving_sphere(s.center + s.radius * normal, direction, id, normal);
  } else if (kind == 3) {
    // Grazing: towards a point at distance r (1 +- 1e-6) from the centre, perpendicular to the
    // line of sight.
    ray.origin =
        Vec3(uniform(rng, -half, half), uniform(rng, -half, half), uniform(rng, -half, half));
    const Vec3 to_center = s.center - ray.origin;
    Vec3 side = glm::cross(to_center, unit_vector(rng));
    if (glm::dot(side, side) == 0.0f) side = Vec3(1.0f, 0.0f, 0.0f);
    side = glm::normalize(side);
    const float scale = 1.0f + uniform(rng, -1e-6f, 1e-6f);
    const Vec3 target = s.center + s.radius * scale * side;
    if (target == ray.origin) return random_ray(rng, spheres, half);
    ray.direction = glm::normalize(target - ray.origin);
  } else {
    // Near a sphere's surface (a wall's too), in a random direction.
    const Vec3 normal = unit_vector(rng);
    const float distance =
        s.radius * (1.0f + uniform(rng, -1e-3f, 1e-3f)) + uniform(rng, -0.5f, 0.5f);
    ray.origin = s.center + distance * normal;
    ray.direction = unit_vector(rng);
  }
  if (rng.next_u32() % 4 == 0) ray.t_min = uniform(rng, 0.0f, 0.2f * half);
  if (rng.next_u32() % 3 == 0) ray.t_max = ray.t_min + uniform(rng, 0.0f, half);
  return ray;
}

/// Eight rays from one point through a small patch of directions: a pixel block.
void coherent_rays(glint::Pcg32& rng, float half, Ray (&rays)[kWidth]) {
  const Vec3 origin(uniform(rng, -half, half), uniform(rng, -half, half),
                    uniform(rng, -half, half));
  const Vec3 forward = unit_vector(rng);
  const float spread = std::pow(10.0f, uniform(rng, -4.0f, -1.0f));
  for (Ray& ray : rays) {
    ray = Ray{};
    ray.origin = origin;
    ray.direction = glm::normalize(forward + spread * unit_vector(rng));
  }
}

struct BatchTally {
  int lanes = 0, hits = 0, blocked = 0, batches = 0;
};

/// Checks the queries for two batches (sixteen lanes at once with AVX-512) against those for
/// one, whose answers for `batch` were `hits`, `found` and `blocked`: `batch` as the first
/// batch of the pair and again, its lanes reversed (each ray in another lane), as the second.
void check_pair(const glint::Scene& scene, const RayBatch& batch, LaneMask active,
                const glint::HitBatch& hits, LaneMask found, LaneMask blocked,
                glint::RayCoherence coherence) {
  RayBatch pair[2] = {batch, RayBatch{}};
  LaneMask pair_active = active;
  for (int lane = 0; lane < kWidth; ++lane) {
    pair[1].set(kWidth - 1 - lane, batch.get(lane));
    pair_active |= ((active >> lane) & 1u) << (2 * kWidth - 1 - lane);
  }
  glint::HitBatch pair_hits[2];
  for (int lane = 0; lane < 2 * kWidth; ++lane)
    pair_hits[lane / kWidth].set(lane % kWidth,
                                 {-7.0f - float(lane), 0xbeef0000u + std::uint32_t(lane)});
  const LaneMask pair_found =
      scene.closest_hits(std::span<const RayBatch, 2>(pair), pair_active,
                         std::span<glint::HitBatch, 2>(pair_hits), coherence);
  const LaneMask pair_blocked =
      scene.occluded(std::span<const RayBatch, 2>(pair), pair_active, coherence);
  CHECK((pair_found & ~pair_active) == 0);
  CHECK((pair_blocked & ~pair_active) == 0);
  for (int lane = 0; lane < 2 * kWidth; ++lane) {
    const glint::HitBatch& got = pair_hits[lane / kWidth];
    const int at = lane % kWidth;
    const int from = lane < kWidth ? lane : 2 * kWidth - 1 - lane;  // the lane of `batch`
    INFO("lane " << lane << " of two batches, lane " << from << " of one");
    if (!((pair_active >> lane) & 1u)) {
      CHECK(bits_of(got.t[at]) == bits_of(-7.0f - float(lane)));
      CHECK(got.sphere[at] == 0xbeef0000u + std::uint32_t(lane));
      continue;
    }
    CHECK(((pair_found >> lane) & 1u) == ((found >> from) & 1u));
    CHECK(bits_of(got.t[at]) == bits_of(hits.t[from]));
    CHECK(got.sphere[at] == hits.sphere[from]);
    CHECK(((pair_blocked >> lane) & 1u) == ((blocked >> from) & 1u));
  }
}

/// Checks closest_hits and occluded against the single-ray queries for one batch, with the
/// lanes of `active` set and the others holding `junk`.
void check_batch(const glint::Scene& scene, const Ray (&rays)[kWidth], LaneMask active,
                 const Ray& junk, BatchTally& tally,
                 glint::RayCoherence coherence = glint::RayCoherence::unknown) {
  RayBatch batch;
  batch.heads_into_origin_sphere = 0;
  for (int lane = 0; lane < kWidth; ++lane)
    batch.set(lane, (active >> lane) & 1u ? rays[lane] : junk);
  glint::HitBatch hits;
  for (int lane = 0; lane < kWidth; ++lane)
    hits.set(lane, {1234.5f + float(lane), 0xdead0000u + std::uint32_t(lane)});
  const LaneMask found = scene.closest_hits(batch, active, hits, coherence);
  const LaneMask blocked = scene.occluded(batch, active, coherence);
  CHECK((found & ~active) == 0);
  CHECK((blocked & ~active) == 0);
  ++tally.batches;
  for (int lane = 0; lane < kWidth; ++lane) {
    if (!((active >> lane) & 1u)) {
      // Untouched.
      CHECK(bits_of(hits.t[lane]) == bits_of(1234.5f + float(lane)));
      CHECK(hits.sphere[lane] == 0xdead0000u + std::uint32_t(lane));
      continue;
    }
    const Ray& ray = rays[lane];
    const std::optional<glint::SphereHit> expected = scene.closest_hit(ray);
    const glint::SphereHit want = expected.value_or(glint::SphereHit{});
    INFO("lane " << lane << " origin (" << ray.origin.x << ", " << ray.origin.y << ", "
                 << ray.origin.z << ") direction (" << ray.direction.x << ", " << ray.direction.y
                 << ", " << ray.direction.z << ") t in (" << ray.t_min << ", " << ray.t_max
                 << ") origin sphere " << ray.origin_sphere << " inwards "
                 << ray.heads_into_origin_sphere << "; expected t " << want.t << " sphere "
                 << want.sphere << ", got t " << hits.t[lane] << " sphere " << hits.sphere[lane]);
    CHECK(((found >> lane) & 1u) == (expected ? 1u : 0u));
    CHECK(bits_of(hits.t[lane]) == bits_of(want.t));
    CHECK(hits.sphere[lane] == want.sphere);
    CHECK(((blocked >> lane) & 1u) == (scene.occluded(ray) ? 1u : 0u));
    ++tally.lanes;
    tally.hits += expected ? 1 : 0;
    tally.blocked += (blocked >> lane) & 1u;
  }
  check_pair(scene, batch, active, hits, found, blocked, coherence);
}

/// Random and coherent batches, all lanes active and random subsets, against `scene`.
BatchTally check_scene(const glint::Scene& scene,
                       const std::vector<glint::SphereDescription>& spheres, float half,
                       std::uint64_t seed, int batches,
                       glint::RayCoherence coherence = glint::RayCoherence::unknown) {
  glint::Pcg32 rng(seed, 11);
  BatchTally tally;
  for (int b = 0; b < batches; ++b) {
    Ray rays[kWidth];
    if (b % 3 == 2)
      coherent_rays(rng, half, rays);
    else
      for (Ray& ray : rays)
        ray = random_ray(rng, spheres, half);
    LaneMask active = RayBatch::kAllLanes;
    if (b % 2 == 1) active = rng.next_u32() & RayBatch::kAllLanes;
    // Inactive lanes hold another ray, or NaNs.
    Ray junk = random_ray(rng, spheres, half);
    if (b % 4 == 1) {
      const float nan = std::numeric_limits<float>::quiet_NaN();
      junk.origin = Vec3(nan);
      junk.direction = Vec3(nan);
      junk.t_min = nan;
      junk.t_max = nan;
    }
    check_batch(scene, rays, active, junk, tally, coherence);
  }
  return tally;
}

void check_coverage(const BatchTally& tally) {
  CHECK(tally.hits > tally.lanes / 8);
  CHECK(tally.blocked > tally.lanes / 8);
  CHECK(tally.blocked < tally.lanes);
}

}  // namespace

TEST_CASE("closest_hits and occluded: small scenes, walls and the linear set",
          "[geometry][ray_batch]") {
  for (const int count : {1, 5, 8, 9, 23, 40, 58, int(glint::Scene::kLinearSceneSize)}) {
    for (const bool walls : {false, true}) {
      DYNAMIC_SECTION(count << " spheres" << (walls ? " in a room" : "")) {
        glint::Pcg32 rng(std::uint64_t(count), walls ? 1 : 2);
        TestScene test;
        if (walls) add_room(test, 30.0f, 1e5f);
        add_random_spheres(test, rng, count, 20.0f, 0.5f, 6.0f);
        const glint::Scene scene = test.build();
        const BatchTally tally =
            check_scene(scene, test.spheres, 25.0f, 100 + std::uint64_t(count), 600);
        check_coverage(tally);
      }
    }
  }
}

TEST_CASE("closest_hits and occluded: huge walls, rays near them", "[geometry][ray_batch]") {
  for (const float radius : {1e5f, 1e7f, 1e9f}) {
    DYNAMIC_SECTION("walls of radius " << radius) {
      glint::Pcg32 rng(5, std::uint64_t(std::log10(radius)));
      TestScene test;
      // A floor just below the camera and a wall behind it, and spheres standing on the floor.
      test.description.camera.position = Vec3(0.0f, 0.001f, 20.0f);
      test.add(Vec3(0.0f, -radius, 0.0f), radius);
      test.add(Vec3(0.0f, 0.0f, -radius - 40.0f), radius);
      test.add(Vec3(radius + 30.0f, 0.0f, 0.0f), radius);
      add_random_spheres(test, rng, 20, 15.0f, 0.5f, 3.0f);
      const glint::Scene scene = test.build();
      BatchTally tally = check_scene(scene, test.spheres, 20.0f, 7, 600);
      // Rays from just above the floor, along it and into it.
      for (int b = 0; b < 200; ++b) {
        Ray rays[kWidth];
        for (Ray& ray : rays) {
          ray.origin = Vec3(uniform(rng, -20.0f, 20.0f), std::pow(10.0f, uniform(rng, -4.0f, 0.0f)),
                            uniform(rng, -20.0f, 20.0f));
          Vec3 d = unit_vector(rng);
          d.y *= std::pow(10.0f, uniform(rng, -4.0f, 0.0f));
          ray.direction = glm::normalize(d);
        }
        check_batch(scene, rays, RayBatch::kAllLanes, rays[0], tally);
      }
      CHECK(tally.hits > tally.lanes / 4);
    }
  }
}

TEST_CASE("closest_hits and occluded: large scenes, the BVH", "[geometry][ray_batch]") {
  constexpr int kSmallestHierarchy = int(glint::Scene::kLinearSceneSize) + 1;
  for (const int count : {kSmallestHierarchy, 1000, 8000}) {
    for (const bool walls : {false, true}) {
      DYNAMIC_SECTION(count << " spheres" << (walls ? " in a room" : "")) {
        glint::Pcg32 rng(std::uint64_t(count), walls ? 3 : 4);
        TestScene test;
        if (walls) add_room(test, 60.0f, 1e5f);
        const float half = 50.0f * std::cbrt(float(count) / 1000.0f);
        add_random_spheres(test, rng, count, half, 0.3f, 3.0f);
        const glint::Scene scene = test.build();
        const BatchTally tally =
            check_scene(scene, test.spheres, half, 200 + std::uint64_t(count), 1500);
        check_coverage(tally);
      }
    }
  }
}

TEST_CASE("closest_hits and occluded: incoherent batches in a BVH beyond the caches",
          "[geometry][ray_batch]") {
  // Large enough for SphereBvh to interleave the traversals of incoherent batches.
  for (const bool walls : {false, true}) {
    DYNAMIC_SECTION((walls ? "in a room" : "no walls")) {
      glint::Pcg32 rng(41, walls ? 1 : 2);
      TestScene test;
      if (walls) add_room(test, 140.0f, 1e5f);
      add_random_spheres(test, rng, 40000, 120.0f, 0.3f, 2.0f);
      std::vector<glint::SphereBvh::Input> inputs;
      for (const glint::SphereDescription& s : test.spheres)
        if (s.radius < 1e3f) inputs.push_back({s.center, s.radius, std::uint32_t(inputs.size())});
      REQUIRE(glint::SphereBvh(inputs).traversal_bytes() >
              glint::SphereBvh::kInterleavedTraversalBytes);
      const glint::Scene scene = test.build();
      const BatchTally tally =
          check_scene(scene, test.spheres, 120.0f, 300, 1500, glint::RayCoherence::incoherent);
      check_coverage(tally);
    }
  }
}

TEST_CASE("closest_hits: ties between duplicates go to the lowest id in every lane",
          "[geometry][ray_batch]") {
  for (const int copies_of_each : {2, 3}) {
    for (const int count : {10, 300}) {
      DYNAMIC_SECTION(count << " spheres, " << copies_of_each << " copies") {
        glint::Pcg32 rng(9, std::uint64_t(count));
        TestScene test;
        for (int i = 0; i < count; ++i) {
          const Vec3 c(uniform(rng, -20.0f, 20.0f), uniform(rng, -20.0f, 20.0f),
                       uniform(rng, -20.0f, 20.0f));
          const float r = uniform(rng, 0.5f, 2.0f);
          for (int k = 0; k < copies_of_each; ++k)
            test.add(c, r);
        }
        const glint::Scene scene = test.build();
        BatchTally tally;
        for (int b = 0; b < 300; ++b) {
          Ray rays[kWidth];
          for (Ray& ray : rays) {
            // Aimed at a random sphere, from outside all of them.
            const auto& s = test.spheres[rng.next_u32() % test.spheres.size()];
            ray.origin = 40.0f * unit_vector(rng);
            ray.direction =
                glm::normalize(s.center + 0.5f * s.radius * unit_vector(rng) - ray.origin);
          }
          check_batch(scene, rays, rng.next_u32() & RayBatch::kAllLanes, rays[0], tally);
        }
        CHECK(tally.hits > tally.lanes / 2);
      }
    }
  }
}

namespace {

/// A batched SphereBvh query under test: closest hits into `hits`, and the blocked lanes.
struct BatchedBvhQuery {
  const char* name;
  LaneMask (*closest)(const glint::SphereBvh&, const RayBatch&, LaneMask,
                      glint::SphereHit (&)[kWidth]);
  LaneMask (*any)(const glint::SphereBvh&, const RayBatch&, LaneMask);
};

const BatchedBvhQuery kBatchedBvhQueries[] = {
    {"interleaved",
     [](const glint::SphereBvh& bvh, const RayBatch& rays, LaneMask active,
        glint::SphereHit (&hits)[kWidth]) {
       return bvh.closest_hits_interleaved(rays, active, hits);
     },
     [](const glint::SphereBvh& bvh, const RayBatch& rays, LaneMask active) {
       return bvh.any_hits_interleaved(rays, active);
     }},
#ifdef GLINT_AVX2
    {"packet",
     [](const glint::SphereBvh& bvh, const RayBatch& rays, LaneMask active,
        glint::SphereHit (&hits)[kWidth]) { return bvh.closest_hits_packet(rays, active, hits); },
     [](const glint::SphereBvh& bvh, const RayBatch& rays, LaneMask active) {
       return bvh.any_hits_packet(rays, active);
     }},
#endif
};

}  // namespace

TEST_CASE("SphereBvh: the packet and interleaved traversals answer as one traversal per lane",
          "[geometry][ray_batch]") {
  // Directly, whatever closest_hits would choose: coherent and incoherent batches, some lanes
  // inactive, some with a hit to beat.
  glint::Pcg32 rng(17, 1);
  std::vector<glint::SphereBvh::Input> inputs;
  std::vector<glint::SphereDescription> spheres;
  for (std::uint32_t i = 0; i < 5000; ++i) {
    const Vec3 c(uniform(rng, -60.0f, 60.0f), uniform(rng, -60.0f, 60.0f),
                 uniform(rng, -60.0f, 60.0f));
    const float r = uniform(rng, 0.2f, 3.0f);
    const std::uint32_t copies = i % 50 == 0 ? 2 : 1;  // some ties
    for (std::uint32_t k = 0; k < copies; ++k) {
      inputs.push_back({c, r, std::uint32_t(inputs.size())});
      glint::SphereDescription s;
      s.center = c;
      s.radius = r;
      spheres.push_back(s);
    }
  }
  const glint::SphereBvh bvh(inputs);
  for (const BatchedBvhQuery& query : kBatchedBvhQueries) {
    DYNAMIC_SECTION(query.name) {
      int hits = 0, blocked = 0, lanes = 0;
      for (int b = 0; b < 3000; ++b) {
        Ray rays[kWidth];
        if (b % 2 == 0)
          coherent_rays(rng, 60.0f, rays);
        else
          for (Ray& ray : rays)
            ray = random_ray(rng, spheres, 60.0f);
        const LaneMask active =
            b % 3 == 0 ? RayBatch::kAllLanes : rng.next_u32() & RayBatch::kAllLanes;
        RayBatch batch;
        batch.heads_into_origin_sphere = 0;
        for (int lane = 0; lane < kWidth; ++lane)
          batch.set(lane, rays[lane]);
        glint::SphereHit batched[kWidth], single[kWidth];
        for (int lane = 0; lane < kWidth; ++lane) {
          // Some lanes start from an earlier hit to beat.
          if (lane % 3 == 1) batched[lane] = single[lane] = {uniform(rng, 1.0f, 80.0f), 7};
        }
        const LaneMask batched_found = query.closest(bvh, batch, active, batched);
        const LaneMask single_found = bvh.closest_hits_per_lane(batch, active, single);
        CHECK(batched_found == single_found);
        const LaneMask single_blocked = bvh.any_hits_per_lane(batch, active);
        CHECK(query.any(bvh, batch, active) == single_blocked);
        for (int lane = 0; lane < kWidth; ++lane) {
          INFO("batch " << b << " lane " << lane);
          CHECK(bits_of(batched[lane].t) == bits_of(single[lane].t));
          CHECK(batched[lane].sphere == single[lane].sphere);
          lanes += (active >> lane) & 1u;
          hits += (single_found >> lane) & 1u;
          blocked += (single_blocked >> lane) & 1u;
        }
      }
      CHECK(hits > lanes / 8);
      CHECK(blocked > lanes / 8);
    }
  }
}

TEST_CASE("same_octant", "[geometry][ray_batch]") {
  RayBatch batch;
  batch.heads_into_origin_sphere = 0;
  for (int lane = 0; lane < kWidth; ++lane) {
    Ray ray;
    ray.direction = glm::normalize(Vec3(0.1f * float(lane + 1), 1.0f, -0.5f));
    batch.set(lane, ray);
  }
  CHECK(glint::same_octant(batch, RayBatch::kAllLanes));
  batch.direction_x[3] = -0.1f;
  CHECK_FALSE(glint::same_octant(batch, RayBatch::kAllLanes));
  CHECK(glint::same_octant(batch, RayBatch::kAllLanes & ~(LaneMask(1) << 3)));
  CHECK(glint::same_octant(batch, LaneMask(1) << 3));
}

TEST_CASE("closest_hits and occluded: either side of Scene::kLinearSceneSize",
          "[geometry][ray_batch]") {
  // The same scene with every sphere but the walls scanned linearly or put in the BVH
  // (Scene::build's linear_scene_size), at the threshold's size and one past it: each answers
  // its batches as its single-ray queries, and the two agree on every ray's sphere and
  // occlusion, their t to rounding (the AVX2 scan and the BVH's scalar leaves round apart).
  constexpr auto kSize = glint::Scene::kLinearSceneSize;
  for (const std::size_t count : {kSize, kSize + 1}) {
    DYNAMIC_SECTION(count << " spheres") {
      glint::Pcg32 rng(std::uint64_t(count), 7);
      TestScene test;
      add_room(test, 30.0f, 1e5f);
      while (test.spheres.size() < count) {
        const Vec3 c(uniform(rng, -20.0f, 20.0f), uniform(rng, -20.0f, 20.0f),
                     uniform(rng, -20.0f, 20.0f));
        test.add(c, uniform(rng, 0.5f, 4.0f));
      }
      test.description.spheres = test.spheres;
      const glint::Scene linear = glint::Scene::build(test.description, count);
      const glint::Scene hierarchy = glint::Scene::build(test.description, count - 1);
      check_coverage(check_scene(linear, test.spheres, 25.0f, 300 + count, 300));
      check_coverage(check_scene(hierarchy, test.spheres, 25.0f, 300 + count, 300));
      int hits = 0;
      for (int i = 0; i < 4000; ++i) {
        Ray ray;
        ray.origin = Vec3(uniform(rng, -25.0f, 25.0f), uniform(rng, -25.0f, 25.0f),
                          uniform(rng, -25.0f, 25.0f));
        ray.direction = unit_vector(rng);
        if (i % 3 == 0) ray.t_max = uniform(rng, 0.0f, 30.0f);
        const std::optional<glint::SphereHit> a = linear.closest_hit(ray);
        const std::optional<glint::SphereHit> b = hierarchy.closest_hit(ray);
        REQUIRE(a.has_value() == b.has_value());
        REQUIRE(linear.occluded(ray) == hierarchy.occluded(ray));
        if (!a) continue;
        ++hits;
        REQUIRE(a->sphere == b->sphere);
        REQUIRE(std::abs(a->t - b->t) <= 1e-5f * (a->t + 30.0f));
      }
      CHECK(hits > 1000);
    }
  }
}
