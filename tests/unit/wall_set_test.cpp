// The anchored ray/sphere kernel and WallSet (geometry/ray_sphere.hpp, wall_set.hpp) against a
// long double solution for the same anchored spheres: walls of radius 1e2 to 1e10 in any
// orientation, rays from the camera (the anchor's reference point), from near it, from far away
// (Haines's form of the discriminant), grazing rays and rays leaving a wall; the scalar and the
// AVX2 kernel; padding lanes; equal distances going to the lower id.

#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_sphere.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/geometry/wall_set.hpp"
#include "glint/math/random.hpp"
#include "random_vectors.hpp"

using glint::Vec3;

namespace {

using Long = long double;
constexpr double kUnitRoundoff = 0x1p-24;  // float's unit roundoff

using glint::test::random_unit_vector;
using glint::test::uniform;

float log_uniform(glint::Pcg32& rng, float lo_exponent, float hi_exponent) {
  return std::pow(10.0f, uniform(rng, lo_exponent, hi_exponent));
}

Long dot(const Long a[3], const Long b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// One wall's answer for a ray, solved in long double from the anchored sphere's floats (the
/// sphere the kernel is given), with the first root past t_min = 0 and the tolerance the
/// kernel's float arithmetic is held to. `marginal`: rounding may decide hit or miss (nearly
/// tangent), or which root comes first (the origin on the surface).
struct Answer {
  bool hit = false;
  bool marginal = false;
  double t = 0.0;
  double tolerance = 0.0;
};

Answer solve(const glint::AnchoredSphere& s, const glint::Ray& ray) {
  const Long g[3] = {Long(ray.origin.x) - s.anchor.x, Long(ray.origin.y) - s.anchor.y,
                     Long(ray.origin.z) - s.anchor.z};
  const Long m[3] = {s.offset.x, s.offset.y, s.offset.z};
  const Long d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const Long radius_squared = dot(m, m);
  const double r = std::sqrt(double(radius_squared));
  const Long dd = dot(d, d);  // 1 only up to rounding
  const Long b = dot(g, d) + dot(m, d);
  const Long c = dot(g, g) + 2 * dot(g, m);  // |f|^2 - |m|^2, without cancellation
  const Long discriminant = b * b - dd * c;
  const double g_length = std::sqrt(double(dot(g, g)));
  const bool far_form = std::abs(c) > radius_squared;
  // What the kernel's discriminant may be off by: its terms' rounding, b's error of about
  // u (|g| + r) (n.d is rounded to u absolute), and Haines's u R^2 in the far form.
  const double discriminant_error = double(std::abs(b * b) + std::abs(c)) +
                                    4.0 * std::abs(double(b)) * (g_length + double(r)) +
                                    (far_form ? 4.0 * double(radius_squared) : 0.0);
  Answer answer;
  answer.marginal = std::abs(double(discriminant)) <= 64.0 * kUnitRoundoff * discriminant_error;
  // A ray leaving another sphere from an origin that counts as on this one (the kernels' rule
  // where spheres cross, sphere_kernel.hpp: |c| below 2 sqrt(2) tol r sqrt(|origin|^2 + |g|^2))
  // meets it at t = 0 if it heads into it (b < 0), else not at all; rounding decides within an
  // eighth of the bound.
  if (ray.origin_sphere != glint::kNoSphere && ray.t_min <= 0.0f) {
    const Long o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    const Long bound = 2 * std::sqrt(Long(2)) * Long(glint::kOnSurfaceTolerance) *
                       std::sqrt(radius_squared) * std::sqrt(dot(o, o) + dot(g, g));
    if (std::abs(c) < bound * Long(9) / 8) {
      answer.marginal = answer.marginal || std::abs(c) > bound * Long(7) / 8;
      answer.hit = b < 0;
      answer.t = 0.0;
      if (!answer.marginal) return answer;
      answer.hit = true;  // either answer: this t = 0 or the roots below
    }
  }
  if (discriminant < 0) return answer;
  const Long root = std::sqrt(discriminant);
  const Long q = -(b + std::copysign(root, b));
  const Long t0 = c / q, t1 = q / dd;
  const Long near = std::min(t0, t1), far = std::max(t0, t1);
  const double cosine = std::max(double(root / std::sqrt(dd)) / r, 1e-7);
  const Long t = near > 0 ? near : far;
  if (!(t > 0)) return answer;
  answer.hit = true;
  answer.t = double(t);
  // The error model of ray_sphere.hpp: about u (t + |g|) / cos(incidence) near the anchor, plus
  // u r / cos(incidence) in Haines's form.
  answer.tolerance = 16.0 * kUnitRoundoff * (answer.t + g_length) / cosine +
                     (far_form ? 8.0 * kUnitRoundoff * r / cosine : 0.0);
  if (near > 0 ? double(near) < answer.tolerance : double(far) < answer.tolerance)
    answer.marginal = true;  // the origin is on the surface, up to rounding
  if (near <= 0 && double(-near) < answer.tolerance) answer.marginal = true;
  return answer;
}

/// A wall around a camera at `camera`: radius 1e2 to 1e10, any orientation, its surface
/// 1e-3 to 1e3 from the camera, on either side.
glint::AnchoredSphere random_wall(glint::Pcg32& rng, const Vec3& camera, float& radius,
                                  Vec3& center) {
  radius = log_uniform(rng, 2.0f, 10.0f);
  const Vec3 m = random_unit_vector(rng);
  const double height = double(log_uniform(rng, -3.0f, 3.0f)) * (rng.next_u32() % 4 ? 1 : -1);
  const glm::dvec3 c = glm::dvec3(camera) - (double(radius) + height) * glm::dvec3(m);
  center = Vec3(c);
  return glint::anchor_sphere(center, radius, camera);
}

/// A ray from the camera, from near it, or from far away (up to a few radii), in a random
/// direction or grazing the wall's surface at the anchor.
glint::Ray random_ray(glint::Pcg32& rng, const Vec3& camera, const glint::AnchoredSphere& wall) {
  glint::Ray ray;
  switch (rng.next_u32() % 4) {
    case 0:
      ray.origin = camera;
      break;
    case 1:
    case 2:
      ray.origin = camera + log_uniform(rng, -3.0f, 2.0f) * random_unit_vector(rng);
      break;
    default:
      ray.origin = camera + std::sqrt(wall.radius_squared) * uniform(rng, 0.5f, 3.0f) *
                                random_unit_vector(rng);
  }
  if (rng.next_u32() % 3 == 0) {
    // Grazing: nearly tangent to the surface at the anchor, slightly into or out of it.
    const Vec3 normal = glm::normalize(wall.offset);
    const Vec3 tangent = glm::normalize(glm::cross(normal, random_unit_vector(rng)));
    const float tilt = log_uniform(rng, -7.0f, -1.0f) * (rng.next_u32() % 2 ? 1.0f : -1.0f);
    ray.direction = glm::normalize(tangent + tilt * normal);
  } else {
    ray.direction = random_unit_vector(rng);
  }
  return ray;
}

struct TestWall {
  glint::AnchoredSphere sphere;
  std::uint32_t id;
};

/// Whether (found, hit) is an acceptable closest hit among `walls` for the ray (t_min = 0,
/// no t_max), the ray's origin wall skipped.
bool acceptable(const std::vector<TestWall>& walls, const glint::Ray& ray, bool found,
                const glint::SphereHit& hit, std::string& why) {
  double best = glint::kInfinity;
  std::vector<std::pair<TestWall, Answer>> answers;
  for (const TestWall& w : walls) {
    if (w.id == ray.origin_sphere) continue;
    const Answer a = solve(w.sphere, ray);
    answers.push_back({w, a});
    if (a.hit && !a.marginal) best = std::min(best, a.t);
  }
  why = "best " + std::to_string(best) + "; got " + (found ? "" : "no hit ") +
        "t=" + std::to_string(hit.t) + " id " + std::to_string(hit.sphere);
  if (!found) {
    for (const auto& [w, a] : answers)
      if (a.hit && !a.marginal) return false;
    return true;
  }
  for (const auto& [w, a] : answers) {
    if (w.id != hit.sphere) continue;
    why += "; its answer t=" + std::to_string(a.t) + " +- " + std::to_string(a.tolerance) +
           (a.marginal ? " marginal" : "") + (a.hit ? "" : " miss");
    if (a.marginal && (!a.hit || hit.t <= best + a.tolerance)) return true;
    if (a.hit && std::abs(hit.t - a.t) <= a.tolerance && hit.t <= best + a.tolerance) return true;
  }
  return false;
}

glint::WallSet make_set(const std::vector<TestWall>& walls) {
  glint::WallSet set;
  for (const TestWall& w : walls)
    set.add(w.sphere, w.id);
  return set;
}

}  // namespace

TEST_CASE("anchor_sphere: the anchor lies on the sphere, nearest the reference point",
          "[geometry][wall_set]") {
  glint::Pcg32 rng(3, 17);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 camera(uniform(rng, -100.0f, 100.0f), uniform(rng, -100.0f, 100.0f),
                      uniform(rng, -100.0f, 100.0f));
    float radius;
    Vec3 center;
    const glint::AnchoredSphere s = random_wall(rng, camera, radius, center);
    const glm::dvec3 anchor(s.anchor), c(center);
    INFO("radius " << radius);
    // On the described sphere up to the rounding of the anchor (u |anchor|) and of the
    // centre's offset (u r): what a float scene can say about where the surface is.
    CHECK(std::abs(glm::length(anchor - c) - radius) <=
          2.0 * kUnitRoundoff * (glm::length(anchor) + radius));
    // The offset: the radius, pointing from the centre at the reference point.
    const glm::dvec3 offset(s.offset);
    CHECK(std::abs(glm::length(offset) - radius) <= 2.0 * kUnitRoundoff * radius);
    CHECK(glm::length(glm::normalize(glm::dvec3(camera) - c) - offset / glm::length(offset)) <=
          2.0 * kUnitRoundoff);
    CHECK(std::abs(s.radius_squared - glm::dot(offset, offset)) <=
          kUnitRoundoff * glm::dot(offset, offset));
  }
  // A reference at the centre: any anchor on the surface will do.
  const glint::AnchoredSphere centred = glint::anchor_sphere(Vec3(1.0f), 2.0f, Vec3(1.0f));
  CHECK(centred.anchor == Vec3(1.0f, 3.0f, 1.0f));
  CHECK(centred.radius_squared == 4.0f);
}

TEST_CASE("intersect_anchored_sphere matches a long double solution", "[geometry][wall_set]") {
  glint::Pcg32 rng(41, 7);
  int hits = 0, near_camera_hits = 0, far_form_hits = 0, grazing_hits = 0, disagreements = 0;
  double worst_ratio = 0.0;
  for (int trial = 0; trial < 40000; ++trial) {
    const Vec3 camera(uniform(rng, -50.0f, 50.0f), uniform(rng, -50.0f, 50.0f),
                      uniform(rng, -50.0f, 50.0f));
    float radius;
    Vec3 center;
    const glint::AnchoredSphere wall = random_wall(rng, camera, radius, center);
    const glint::Ray ray = random_ray(rng, camera, wall);
    const Answer exact = solve(wall, ray);
    glint::SphereRoots roots{};
    const bool hit = glint::intersect_anchored_sphere(ray.origin, ray.direction, wall, roots);
    const float t = roots.near > 0.0f ? roots.near : roots.far;
    const bool hit_ahead = hit && t > 0.0f;
    if (exact.marginal) continue;
    INFO("radius " << radius << ", origin " << glm::length(ray.origin - wall.anchor)
                   << " from the anchor, exact t " << exact.t << " +- " << exact.tolerance
                   << ", got " << hit_ahead << " t " << t);
    if (hit_ahead != exact.hit) {
      ++disagreements;
      CHECK(hit_ahead == exact.hit);
      continue;
    }
    if (!exact.hit) continue;
    ++hits;
    const double g = glm::length(glm::dvec3(ray.origin) - glm::dvec3(wall.anchor));
    if (g < 1e2) ++near_camera_hits;
    if (g > radius) ++far_form_hits;
    if (std::abs(glm::dot(ray.direction, glm::normalize(wall.offset))) < 1e-3f) ++grazing_hits;
    worst_ratio = std::max(worst_ratio, std::abs(t - exact.t) / exact.tolerance);
    CHECK(std::abs(t - exact.t) <= exact.tolerance);
  }
  CHECK(disagreements == 0);
  CHECK(hits > 15000);
  CHECK(near_camera_hits > 5000);
  CHECK(far_form_hits > 1000);
  CHECK(grazing_hits > 500);
  WARN("worst error / tolerance: " << worst_ratio);
}

TEST_CASE("WallSet: closest and any hit, scalar and AVX2, against the long double solution",
          "[geometry][wall_set]") {
  glint::Pcg32 rng(77, 9);
  int checked = 0, found_count = 0, leaving = 0;
  for (int count = 1; count <= 20; ++count) {
    for (int set_index = 0; set_index < 6; ++set_index) {
      const Vec3 camera(uniform(rng, -50.0f, 50.0f), uniform(rng, -50.0f, 50.0f),
                        uniform(rng, -50.0f, 50.0f));
      std::vector<TestWall> walls;
      for (int i = 0; i < count; ++i) {
        float radius;
        Vec3 center;
        walls.push_back(
            {random_wall(rng, camera, radius, center), std::uint32_t(7919 * i % 10007 + 3)});
      }
      const glint::WallSet set = make_set(walls);
      REQUIRE(set.size() == walls.size());
      for (int r = 0; r < 60; ++r) {
        glint::Ray ray = random_ray(rng, camera, walls[rng.next_u32() % walls.size()].sphere);
        if (r % 4 == 0) {
          // Leave one of the walls: from its surface point on a ray from the camera.
          const TestWall& from = walls[rng.next_u32() % walls.size()];
          glint::Ray to_wall;
          to_wall.origin = camera;
          to_wall.direction = random_unit_vector(rng);
          const Answer a = solve(from.sphere, to_wall);
          if (a.hit && !a.marginal) {
            ray.origin = to_wall.at(float(a.t));
            ray.origin_sphere = from.id;
            ++leaving;
          }
        }
        std::string why;
        glint::SphereHit scalar_hit;
        const bool scalar = set.closest_hit_scalar(ray, scalar_hit);
        INFO(count << " walls; ray from " << glm::length(ray.origin - camera)
                   << " from the camera");
        const bool ok = acceptable(walls, ray, scalar, scalar_hit, why);
        INFO("scalar: " << why);
        CHECK(ok);
        if (scalar) CHECK(scalar_hit.sphere != ray.origin_sphere);
        CHECK(set.any_hit_scalar(ray) == scalar);
        ++checked;
        if (scalar) ++found_count;
#ifdef GLINT_AVX2
        glint::SphereHit simd_hit;
        const bool simd = set.closest_hit_avx2(ray, simd_hit);
        const bool simd_ok = acceptable(walls, ray, simd, simd_hit, why);
        INFO("avx2: " << why);
        CHECK(simd_ok);
        CHECK(set.any_hit_avx2(ray) == simd);
        // The same answer bit for bit: the kernels round alike (sphere_kernel.hpp).
        CHECK(simd == scalar);
        CHECK(simd_hit.sphere == scalar_hit.sphere);
        CHECK(std::bit_cast<std::uint32_t>(simd_hit.t) ==
              std::bit_cast<std::uint32_t>(scalar_hit.t));
#endif
      }
    }
  }
  CHECK(found_count > checked / 3);
  CHECK(found_count < checked);
  CHECK(leaving > 500);
}

TEST_CASE("WallSet: padding lanes are never hit", "[geometry][wall_set]") {
  // Padding lanes hold NaN anchors and a zero offset: rays in any direction, through the
  // origin among others, must still miss when the set is not a multiple of the SIMD width.
  glint::Pcg32 rng(5, 5);
  for (std::uint32_t count = 1; count <= 17; ++count) {
    glint::WallSet set;
    for (std::uint32_t i = 0; i < count; ++i)  // floors far below, facing up
      set.add({0.0f, -1e6f - 1e5f * float(i), 0.0f}, 1e5f, i, Vec3(0.0f));
    for (int r = 0; r < 50; ++r) {
      glint::Ray ray;
      ray.direction = random_unit_vector(rng);
      ray.direction.y = std::abs(ray.direction.y);  // upwards: misses every floor
      ray.origin = -3.0f * ray.direction;           // passes through the origin
      glint::SphereHit hit;
      CHECK_FALSE(set.closest_hit(ray, hit));
      CHECK_FALSE(set.any_hit(ray));
      CHECK_FALSE(set.closest_hit_scalar(ray, hit));
#ifdef GLINT_AVX2
      CHECK_FALSE(set.closest_hit_avx2(ray, hit));
      CHECK_FALSE(set.any_hit_avx2(ray));
#endif
    }
  }
}

TEST_CASE("WallSet: equal distances go to the lowest id, in every lane and group",
          "[geometry][wall_set]") {
  // Copies of one floor (y = -1) with ids in no order, among other walls the ray misses.
  const glint::AnchoredSphere floor =
      glint::anchor_sphere({0.0f, -1e5f - 1.0f, 0.0f}, 1e5f, Vec3(0.0f));
  const std::uint32_t copy_ids[] = {700, 41, 9000, 42, 513};
  for (const int filler : {0, 3, 7, 13, 20}) {
    glint::WallSet set;
    std::size_t next_copy = 0;
    for (int i = 0; i < filler + 5; ++i) {
      if (next_copy < std::size(copy_ids) && i % (filler / 5 + 1) == 0) {
        set.add(floor, copy_ids[next_copy++]);
        continue;
      }
      // A ceiling at y = 1: behind the downward ray.
      set.add({0.0f, 1e5f + 1.0f, 0.0f}, 1e5f, 2000u + std::uint32_t(i), Vec3(0.0f));
    }
    while (next_copy < std::size(copy_ids))
      set.add(floor, copy_ids[next_copy++]);
    glint::Ray ray;
    ray.direction = {0.0f, -1.0f, 0.0f};
    INFO(set.size() << " walls");
    glint::SphereHit scalar;
    REQUIRE(set.closest_hit_scalar(ray, scalar));
    CHECK(scalar.sphere == 41u);
    CHECK(scalar.t == 1.0f);
#ifdef GLINT_AVX2
    glint::SphereHit simd;
    REQUIRE(set.closest_hit_avx2(ray, simd));
    CHECK(simd.sphere == 41u);
    CHECK(simd.t == 1.0f);
#endif
    // A caller's hit at the same t competes by id too; t_max is an open bound.
    for (const std::uint32_t caller_id : {40u, 41u, 43u}) {
      glint::SphereHit hit{1.0f, caller_id};
      CHECK(set.closest_hit(ray, hit) == (caller_id > 41u));
      CHECK(hit.sphere == std::min(caller_id, 41u));
    }
    glint::Ray short_ray = ray;
    short_ray.t_max = 1.0f;
    glint::SphereHit none;
    CHECK_FALSE(set.closest_hit(short_ray, none));
    CHECK_FALSE(set.any_hit(short_ray));
  }
}
