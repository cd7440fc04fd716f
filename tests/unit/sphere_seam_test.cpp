// Where two spheres cross: a ray that leaves one of them at a point of the crossing (a hit point
// rounded to float, so inside the other sphere or outside it by a rounding) meets the other at its
// origin, t = 0, exactly when it heads into it (against its outward normal, worked out in long
// double from the exact crossing point), and does not meet it otherwise: in every kernel and
// structure (SphereSet's scalar and AVX2 scans, WallSet's, SphereBvh's leaves, Scene's single-ray
// and batched queries, closest hit and occlusion alike), for two ordinary spheres, two walls of
// radius 1e5 and a ball sunk into such a floor, near the world's origin and far from it.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/sphere_bvh.hpp"
#include "glint/geometry/sphere_set.hpp"
#include "glint/geometry/wall_set.hpp"
#include "glint/math/random.hpp"
#include "glint/scene/scene.hpp"
#include "random_vectors.hpp"

using glint::Vec3;
using glint::test::random_unit_vector;

namespace {

using Long = long double;
struct Vec3L {
  Long x, y, z;
};

Vec3L operator-(const Vec3L& a, const Vec3L& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3L operator+(const Vec3L& a, const Vec3L& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3L operator*(Long s, const Vec3L& a) {
  return {s * a.x, s * a.y, s * a.z};
}
Long dot(const Vec3L& a, const Vec3L& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3L to_long(const Vec3& v) {
  return {v.x, v.y, v.z};
}

struct Ball {
  Vec3 center;
  float radius;
};

/// The point where spheres a and b cross nearest `guess`: alternating projections onto the two
/// spheres, in long double.
Vec3L crossing_point(const Ball& a, const Ball& b, Vec3L point) {
  for (int i = 0; i < 200; ++i) {
    for (const Ball& s : {a, b}) {
      const Vec3L f = point - to_long(s.center);
      point = to_long(s.center) + (Long(s.radius) / std::sqrt(dot(f, f))) * f;
    }
  }
  return point;
}

/// The outward unit normal of sphere s at `point`.
Vec3L outward(const Ball& s, const Vec3L& point) {
  const Vec3L f = point - to_long(s.center);
  return (1 / std::sqrt(dot(f, f))) * f;
}

/// Two crossing spheres, A (id 0) and B (id 1), and where to look for their crossing.
struct Crossing {
  std::string name;
  Ball a, b;
  Vec3L guess;       ///< a point near the crossing
  Vec3L axis;        ///< the crossing circle goes round this line through `guess`
  Long spread;       ///< how far from `guess` the crossing points are sought
  Vec3 reference{};  ///< where walls are anchored (the camera)
};

std::vector<Crossing> crossings() {
  std::vector<Crossing> list;
  list.push_back({"two balls",
                  {{-0.6f, 0.0f, 0.0f}, 1.0f},
                  {{0.6f, 0.0f, 0.0f}, 1.0f},
                  {0, 0, 0.8L},
                  {1, 0, 0},
                  0.7L,
                  Vec3(0.0f, 0.0f, 6.0f)});
  list.push_back({"two balls of different sizes far from the origin",
                  {{1000.0f, -500.0f, 250.0f}, 3.0f},
                  {{1004.0f, -500.5f, 250.25f}, 2.0f},
                  {1002.5L, -500.3L, 251.6L},
                  {1, 0, 0},
                  1.5L,
                  Vec3(1000.0f, -500.0f, 300.0f)});
  list.push_back({"two walls meeting at right angles",
                  {{-100040.0f, 0.0f, 0.0f}, 1e5f},
                  {{0.0f, 100040.0f, 0.0f}, 1e5f},
                  {-40, 40, 0},
                  {0, 0, 1},
                  30,
                  Vec3(0.0f, 0.0f, 95.0f)});
  list.push_back({"a ball sunk into a floor",
                  {{0.0f, -100040.0f, 0.0f}, 1e5f},
                  {{3.0f, -35.0f, -2.0f}, 10.0f},
                  {3, -40, 6.7L},
                  {0, 1, 0},
                  6,
                  Vec3(0.0f, 0.0f, 95.0f)});
  return list;
}

/// What a ray leaving A at a crossing point should meet of B.
struct SeamRay {
  glint::Ray ray;
  bool enters_b;
};

/// Rays leaving A at points of its crossing with B, in random directions away from both
/// tangent planes (by at least 0.05 in cosine, where the exact answer cannot be in doubt).
std::vector<SeamRay> seam_rays(const Crossing& c, glint::Pcg32& rng, int count) {
  std::vector<SeamRay> rays;
  while (int(rays.size()) < count) {
    const Vec3 offset = random_unit_vector(rng);
    const Vec3L guess = c.guess + c.spread * to_long(offset);
    const Vec3L exact = crossing_point(c.a, c.b, guess);
    const Vec3L n_a = outward(c.a, exact), n_b = outward(c.b, exact);
    const Vec3 d = random_unit_vector(rng);
    const Long cos_a = dot(to_long(d), n_a), cos_b = dot(to_long(d), n_b);
    if (std::abs(cos_a) < 0.05L || std::abs(cos_b) < 0.05L) continue;
    const Vec3 point(float(exact.x), float(exact.y), float(exact.z));
    const Vec3 normal(float(n_a.x), float(n_a.y), float(n_a.z));
    rays.push_back({glint::ray_leaving_sphere(point, d, 0, normal), cos_b < 0});
  }
  return rays;
}

/// The answer of a structure holding A and B (skipping the origin sphere A): B at t = 0 where
/// the ray enters B, nothing otherwise.
void check_structure_answer(const SeamRay& seam, bool found, const glint::SphereHit& hit) {
  if (seam.enters_b) {
    REQUIRE(found);
    CHECK(hit.sphere == 1u);
    CHECK(hit.t == 0.0f);
  } else {
    CHECK_FALSE(found);
  }
}

glint::SceneDescription scene_of(const Crossing& c, int fillers) {
  glint::SceneDescription scene;
  scene.camera.position = c.reference;
  scene.camera.look_at = c.b.center;
  for (const Ball& s : {c.a, c.b}) {
    glint::SphereDescription sphere;
    sphere.center = s.center;
    sphere.radius = s.radius;
    scene.spheres.push_back(sphere);
  }
  // Small spheres far away, which the rays never meet: past 64 spheres the two ordinary ones
  // go to the hierarchy.
  for (int i = 0; i < fillers; ++i) {
    glint::SphereDescription sphere;
    sphere.center = Vec3(2e4f + 2.0f * float(i), 2e4f, 2e4f);
    sphere.radius = 0.5f;
    scene.spheres.push_back(sphere);
  }
  return scene;
}

}  // namespace

TEST_CASE("Where spheres cross, a ray leaving one meets the other at its origin iff it enters it",
          "[geometry][sphere_set][wall_set][bvh]") {
  glint::Pcg32 rng(32, 7);
  for (const Crossing& c : crossings()) {
    const bool walls = c.a.radius > 1e4f;
    const std::vector<SeamRay> rays = seam_rays(c, rng, 400);
    int entering = 0;
    for (const SeamRay& seam : rays)
      entering += seam.enters_b ? 1 : 0;
    INFO(c.name);
    // Both answers are exercised, and the rounded origins lie on both sides of B's surface.
    CHECK(entering > 100);
    CHECK(entering < 300);

    // The linear sets and the hierarchy, with A and B alone (ids 0 and 1).
    glint::SphereSet set;
    glint::WallSet wall_set;
    std::vector<glint::SphereBvh::Input> inputs;
    std::uint32_t id = 0;
    for (const Ball& s : {c.a, c.b}) {
      set.add(s.center, s.radius, id);
      wall_set.add(s.center, s.radius, id, c.reference);
      inputs.push_back({s.center, s.radius, id});
      ++id;
    }
    const glint::SphereBvh bvh(std::move(inputs));
    int inside_b = 0;
    for (const SeamRay& seam : rays) {
      const glint::Ray& ray = seam.ray;
      const Vec3L f = to_long(ray.origin) - to_long(c.b.center);
      if (std::sqrt(dot(f, f)) < Long(c.b.radius)) ++inside_b;
      INFO("from (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") towards ("
                    << ray.direction.x << ", " << ray.direction.y << ", " << ray.direction.z
                    << "), " << (seam.enters_b ? "entering" : "leaving") << " B");
      glint::SphereHit hit;
      if (!walls) {
        hit = {};
        check_structure_answer(seam, set.closest_hit_scalar(ray, hit), hit);
        CHECK(set.any_hit_scalar(ray) == seam.enters_b);
#ifdef GLINT_AVX2
        hit = {};
        check_structure_answer(seam, set.closest_hit_avx2(ray, hit), hit);
        CHECK(set.any_hit_avx2(ray) == seam.enters_b);
#endif
        hit = {};
        check_structure_answer(seam, bvh.closest_hit(ray, hit), hit);
        CHECK(bvh.any_hit(ray) == seam.enters_b);
      }
      hit = {};
      check_structure_answer(seam, wall_set.closest_hit_scalar(ray, hit), hit);
      CHECK(wall_set.any_hit_scalar(ray) == seam.enters_b);
#ifdef GLINT_AVX2
      hit = {};
      check_structure_answer(seam, wall_set.closest_hit_avx2(ray, hit), hit);
      CHECK(wall_set.any_hit_avx2(ray) == seam.enters_b);
#endif
    }
    // Rounding puts the origins on both sides of B's surface (for walls anchored at the camera
    // the kernel's own sphere, not the described one, decides, so this is checked for balls).
    if (!walls) {
      CHECK(inside_b > 40);
      CHECK(inside_b < 360);
    }

    // The scene, with its origin-sphere rule for A: single rays and batches of eight, with the
    // two spheres in the linear sets (or the walls' set) and, past 64 spheres, in the hierarchy.
    for (const int fillers : {0, 80}) {
      const glint::Scene scene = glint::Scene::build(scene_of(c, fillers));
      INFO(fillers << " other spheres");
      const auto check_scene_answer = [&](const SeamRay& seam, bool found,
                                          const glint::SphereHit& hit, bool blocked) {
        if (seam.enters_b) {
          REQUIRE(found);
          CHECK(hit.sphere == 1u);
          CHECK(hit.t == 0.0f);
          CHECK(blocked);
        } else if (seam.ray.heads_into_origin_sphere) {
          REQUIRE(found);  // A's far side
          CHECK(hit.sphere == 0u);
          CHECK(hit.t > 0.0f);
        } else {
          CHECK_FALSE(found);
          CHECK_FALSE(blocked);
        }
      };
      for (const SeamRay& seam : rays) {
        const std::optional<glint::SphereHit> hit = scene.closest_hit(seam.ray);
        check_scene_answer(seam, hit.has_value(), hit.value_or(glint::SphereHit{}),
                           scene.occluded(seam.ray));
      }
      // Batches in rays' order (directions in any octant: one traversal per lane in the
      // hierarchy), then sorted by octant (a packet traversal).
      std::vector<SeamRay> by_octant = rays;
      std::stable_sort(by_octant.begin(), by_octant.end(), [](const SeamRay& x, const SeamRay& y) {
        const auto octant = [](const Vec3& d) {
          return int(std::signbit(d.x)) + 2 * int(std::signbit(d.y)) + 4 * int(std::signbit(d.z));
        };
        return octant(x.ray.direction) < octant(y.ray.direction);
      });
      for (const std::vector<SeamRay>* order : {&std::as_const(rays), &std::as_const(by_octant)}) {
        for (std::size_t base = 0; base + 8 <= order->size(); base += 8) {
          glint::RayBatch batch;
          for (int lane = 0; lane < 8; ++lane)
            batch.set(lane, (*order)[base + std::size_t(lane)].ray);
          glint::HitBatch hits;
          const glint::LaneMask found = scene.closest_hits(batch, glint::RayBatch::kAllLanes, hits);
          const glint::LaneMask blocked = scene.occluded(batch, glint::RayBatch::kAllLanes);
          for (int lane = 0; lane < 8; ++lane) {
            INFO("batch lane " << lane);
            check_scene_answer((*order)[base + std::size_t(lane)], (found >> lane) & 1u,
                               hits.get(lane), (blocked >> lane) & 1u);
          }
        }
      }
    }
  }
}
