// Ray/sphere intersection: hand-computed roots, accuracy in float for the 1e5-radius wall
// spheres of smallpt against a long double solution, and the closest-hit / any-hit queries of
// SphereSet (scalar and AVX2 kernels), SphereBvh and Scene (which adds the origin-sphere rule)
// against a brute-force loop over intersect_sphere.

#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_sphere.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_bvh.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/geometry/sphere_set.hpp"
#include "glint/math/random.hpp"
#include "glint/scene/scene.hpp"
#include "random_vectors.hpp"

using glint::Vec3;

namespace {

constexpr double kUnitRoundoff = 0x1p-24;  // float's unit roundoff

using glint::test::random_unit_vector;
using glint::test::uniform;

glint::SphereRoots roots_of(const Vec3& origin, const Vec3& direction, const Vec3& center,
                            float radius) {
  glint::SphereRoots roots{};
  REQUIRE(glint::intersect_sphere(origin, direction, center, radius, roots));
  return roots;
}

/// The ray/sphere roots solved in long double from the (float) inputs, so that only the
/// inputs' rounding is shared with the code under test; also the cosine of the angle of
/// incidence at either root (half chord / radius).
struct ExactRoots {
  bool hit = false;
  long double near = 0, far = 0;
  double cos_incidence = 0;
};

ExactRoots exact_roots(const Vec3& o, const Vec3& d, const Vec3& c, float radius) {
  using L = long double;
  const L fx = L(o.x) - L(c.x), fy = L(o.y) - L(c.y), fz = L(o.z) - L(c.z);
  const L dx = d.x, dy = d.y, dz = d.z;
  const L dd = dx * dx + dy * dy + dz * dz;  // |d| is 1 only up to rounding
  const L b = (fx * dx + fy * dy + fz * dz) / dd;
  const L px = fx - b * dx, py = fy - b * dy, pz = fz - b * dz;
  const L r = radius;
  const L discriminant = r * r - (px * px + py * py + pz * pz);
  ExactRoots result;
  if (discriminant < 0) return result;
  const L half_chord = std::sqrt(discriminant);
  const L length = std::sqrt(dd);
  result.hit = true;
  result.near = (-b * length - half_chord) / length;
  result.far = (-b * length + half_chord) / length;
  result.cos_incidence = double(half_chord / r);
  return result;
}

}  // namespace

TEST_CASE("intersect_sphere: hand-computed roots", "[geometry][ray_sphere]") {
  const Vec3 z(0.0f, 0.0f, 1.0f);
  SECTION("from outside, through the centre") {
    const auto roots = roots_of({0.0f, 0.0f, -5.0f}, z, Vec3(0.0f), 1.0f);
    CHECK(roots.near == 4.0f);
    CHECK(roots.far == 6.0f);
  }
  SECTION("from outside, off-centre: a 0.6-0.8-1 triangle") {
    const auto roots = roots_of({0.0f, 0.6f, -5.0f}, z, Vec3(0.0f), 1.0f);
    CHECK(roots.near == Approx(4.2).epsilon(1e-6));
    CHECK(roots.far == Approx(5.8).epsilon(1e-6));
  }
  SECTION("oblique direction: a 3-4-5 triangle") {
    // Centre at distance 10 along (0.6, 0.8, 0); radius 5: hits at 5 and 15.
    const auto roots = roots_of(Vec3(0.0f), {0.6f, 0.8f, 0.0f}, {6.0f, 8.0f, 0.0f}, 5.0f);
    CHECK(roots.near == Approx(5.0).epsilon(1e-6));
    CHECK(roots.far == Approx(15.0).epsilon(1e-6));
  }
  SECTION("from inside: one root behind, one ahead") {
    const auto roots = roots_of({1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, Vec3(0.0f), 2.0f);
    CHECK(roots.near == -3.0f);
    CHECK(roots.far == 1.0f);
  }
  SECTION("sphere behind the ray: both roots negative") {
    const auto roots = roots_of({0.0f, 0.0f, 5.0f}, z, Vec3(0.0f), 1.0f);
    CHECK(roots.near == -6.0f);
    CHECK(roots.far == -4.0f);
  }
  SECTION("tangent: a double root") {
    const auto roots = roots_of({0.0f, 1.0f, -5.0f}, z, Vec3(0.0f), 1.0f);
    CHECK(roots.near == 5.0f);
    CHECK(roots.far == 5.0f);
  }
  SECTION("misses, just outside the tangent") {
    glint::SphereRoots roots{};
    CHECK_FALSE(glint::intersect_sphere({0.0f, 1.001f, -5.0f}, z, Vec3(0.0f), 1.0f, roots));
    CHECK_FALSE(
        glint::intersect_sphere({0.0f, 0.0f, -5.0f}, {0.0f, 1.0f, 0.0f}, Vec3(0.0f), 1.0f, roots));
  }
}

TEST_CASE("intersect_sphere: small sphere far away keeps its chord", "[geometry][ray_sphere]") {
  // The textbook discriminant b^2 - c cancels catastrophically here (at distance 1e5, b^2 ~
  // 1e10 carries an absolute error of hundreds while the discriminant is below 1);
  // r^2 - |perpendicular|^2 does not.
  for (const float distance : {1e3f, 1e4f, 1e5f}) {
    for (const float offset : {0.0f, 0.5f, 0.9f}) {
      const Vec3 origin(offset, 0.0f, distance);
      const auto roots = roots_of(origin, {0.0f, 0.0f, -1.0f}, Vec3(0.0f), 1.0f);
      const double half_chord = std::sqrt(1.0 - double(offset) * offset);
      INFO("distance " << distance << ", offset " << offset);
      // Each root is a float near `distance`: within a few ulps of it.
      const double ulp = double(distance) * kUnitRoundoff * 2.0;
      CHECK(std::abs(roots.near - (distance - half_chord)) <= 2.0 * ulp);
      CHECK(std::abs(roots.far - (distance + half_chord)) <= 2.0 * ulp);
    }
  }
}

TEST_CASE("far_side_distance: the chord from a point on the surface", "[geometry][ray_sphere]") {
  // Chord length 2 r cos(theta), theta the angle between the direction and the inward normal.
  const Vec3 center(1.0f, 2.0f, 3.0f);
  const float radius = 3.0f;
  const Vec3 on_surface = center + Vec3(0.0f, 0.0f, radius);
  CHECK(glint::far_side_distance(on_surface, {0.0f, 0.0f, -1.0f}, center) == 6.0f);
  const Vec3 diagonal = glm::normalize(Vec3(-1.0f, 0.0f, -1.0f));
  CHECK(glint::far_side_distance(on_surface, diagonal, center) ==
        Approx(2.0 * 3.0 / std::sqrt(2.0)).epsilon(1e-6));
  // Tangent direction: zero; outward: negative (behind).
  CHECK(glint::far_side_distance(on_surface, {1.0f, 0.0f, 0.0f}, center) == 0.0f);
  CHECK(glint::far_side_distance(on_surface, {0.0f, 0.0f, 1.0f}, center) == -6.0f);

  SECTION("random chords: 2 r cos(theta) up to the rounding of the surface point") {
    glint::Pcg32 rng(11, 3);
    for (int i = 0; i < 2000; ++i) {
      const float r = uniform(rng, 0.1f, 50.0f);
      const Vec3 c(uniform(rng, -20.0f, 20.0f), uniform(rng, -20.0f, 20.0f),
                   uniform(rng, -20.0f, 20.0f));
      const Vec3 n = random_unit_vector(rng);
      Vec3 d = random_unit_vector(rng);
      if (glm::dot(d, n) > 0.0f) d = -d;
      const double cosine = -(double(d.x) * n.x + double(d.y) * n.y + double(d.z) * n.z);
      // c + r n is rounded to float: an error of a few ulps of |c| + r in each component.
      const double allowed = 8.0 * kUnitRoundoff * (glm::length(c) + r);
      CHECK(std::abs(glint::far_side_distance(c + r * n, d, c) - 2.0 * r * cosine) <= allowed);
    }
  }
}

TEST_CASE("intersect_sphere: smallpt-sized walls in float", "[geometry][ray_sphere]") {
  // A wall of radius 1e5 whose centre is 1e5 + 50 away: the surface is 50 units ahead.
  const float radius = 1e5f;
  const Vec3 center(0.0f, 0.0f, -(1e5f + 50.0f));

  SECTION("head on and oblique, from an exact origin: within 1e-2") {
    const auto axis = roots_of(Vec3(0.0f), {0.0f, 0.0f, -1.0f}, center, radius);
    CHECK(std::abs(axis.near - 50.0) <= 1e-2);
    CHECK(std::abs(axis.far - (50.0 + 2e5)) <= 2e5 * 4.0 * kUnitRoundoff);
    glint::Pcg32 rng(5, 1);
    for (int i = 0; i < 20000; ++i) {
      Vec3 d = random_unit_vector(rng);
      d.z = -std::abs(d.z);
      if (-d.z < 0.5f) continue;  // within 60 degrees of the wall's normal
      const ExactRoots exact = exact_roots(Vec3(0.0f), d, center, radius);
      REQUIRE(exact.hit);
      glint::SphereRoots roots{};
      REQUIRE(glint::intersect_sphere(Vec3(0.0f), d, center, radius, roots));
      CHECK(std::abs(roots.near - double(exact.near)) <= 1e-2);
    }
  }

  SECTION("every smallpt wall from random points in the room, grazing rays included") {
    // The walls of smallpt's Cornell box; the room is inside each of them, so the hit is the
    // positive root (computed as c / q, the one that would cancel in the textbook formula).
    const Vec3 centers[] = {{1e5f + 1.0f, 40.8f, 81.6f}, {-1e5f + 99.0f, 40.8f, 81.6f},
                            {50.0f, 40.8f, 1e5f},        {50.0f, 40.8f, -1e5f + 170.0f},
                            {50.0f, 1e5f, 81.6f},        {50.0f, -1e5f + 81.6f, 81.6f}};
    // Error model: f = origin - centre is rounded to ulp(1e5)/2 per component and the
    // discriminant r^2 - |p|^2 to about 2 u r^2; either moves the hit by ~u r / cos(incidence)
    // (u = 2^-24), so 3 u r = 0.018 at normal incidence: an origin that is not exactly
    // representable relative to the centre already costs ~0.004 per axis. Near tangency
    // (cos^2 ~ u) hit or miss itself is undecidable in float.
    glint::Pcg32 rng(7, 2);
    int hits = 0, grazing_hits = 0;
    double worst_ratio = 0.0;
    for (int i = 0; i < 40000; ++i) {
      const Vec3 origin(uniform(rng, 2.0f, 98.0f), uniform(rng, 1.0f, 80.0f),
                        uniform(rng, 1.0f, 169.0f));
      const Vec3 d = random_unit_vector(rng);
      for (const Vec3& c : centers) {
        const ExactRoots exact = exact_roots(origin, d, c, radius);
        glint::SphereRoots roots{};
        const bool hit = glint::intersect_sphere(origin, d, c, radius, roots);
        if (hit != exact.hit) {
          INFO("hit/miss disagree with cos(incidence) " << exact.cos_incidence);
          CHECK(exact.cos_incidence < 1e-3);
          continue;
        }
        if (!hit) continue;
        REQUIRE(exact.near < 0);  // origin inside the wall sphere
        ++hits;
        if (exact.cos_incidence < 0.05) ++grazing_hits;
        const double t = double(exact.far);
        const double error = std::abs(roots.far - t);
        // Plus a few ulps of t itself, for the far side of a wall seen across the room.
        const double allowed =
            3.0 * kUnitRoundoff * radius / exact.cos_incidence + 4.0 * kUnitRoundoff * t;
        worst_ratio = std::max(worst_ratio, error / allowed);
        INFO("t = " << t << ", cos(incidence) " << exact.cos_incidence);
        CHECK(error <= allowed);
      }
    }
    CHECK(hits > 10000);
    CHECK(grazing_hits > 20);  // the grazing regime was exercised
    CHECK(worst_ratio <= 1.0);
  }

  SECTION("grazing rays from the brief's configuration") {
    // Rays leaving the origin at a shallow angle alpha below the horizon: tangency is at
    // cos(alpha) = r / (r + 50), about 1.81 degrees.
    glint::Pcg32 rng(9, 4);
    for (const double degrees : {60.0, 30.0, 10.0, 5.0, 3.0, 2.0, 1.9, 1.85}) {
      const double alpha = degrees * M_PI / 180.0;
      for (int i = 0; i < 500; ++i) {
        const double phi = uniform(rng, 0.0f, 2.0f * glint::kPi);
        const Vec3 d =
            glm::normalize(Vec3(float(std::cos(alpha) * std::cos(phi)),
                                float(std::cos(alpha) * std::sin(phi)), float(-std::sin(alpha))));
        const ExactRoots exact = exact_roots(Vec3(0.0f), d, center, radius);
        REQUIRE(exact.hit);
        glint::SphereRoots roots{};
        REQUIRE(glint::intersect_sphere(Vec3(0.0f), d, center, radius, roots));
        INFO(degrees << " degrees: t = " << double(exact.near) << ", cos(incidence) "
                     << exact.cos_incidence);
        CHECK(std::abs(roots.near - double(exact.near)) <=
              3.0 * kUnitRoundoff * radius / exact.cos_incidence);
      }
    }
  }
}

namespace {

// ---- SphereSet, SphereBvh and Scene against a brute-force reference -----------------------

struct TestSphere {
  Vec3 center;
  float radius;
  std::uint32_t id;  ///< what the structure under test reports (and Ray::origin_sphere names)
};

/// One sphere's answer for a ray, from intersect_sphere (or far_side_distance for the origin
/// sphere). `marginal` marks answers that rounding may legitimately flip: near-tangent rays
/// and hits at the very ends of (t_min, t_max).
struct Candidate {
  std::uint32_t sphere;
  float t;
  float tolerance;
  bool marginal;
};

struct Reference {
  std::vector<Candidate> candidates;  // every sphere that is, or may be, hit in range
  float best = glint::kInfinity;      // nearest non-marginal hit
};

enum class OnSurface { no, yes, marginal };

/// Whether the origin of `ray` counts as on the sphere (center, radius) for the kernels' rule
/// where spheres cross (sphere_kernel.hpp): for a ray leaving another sphere from its origin,
/// |c| = | |f|^2 - r^2 | below 2 sqrt(2) tol r sqrt(|origin|^2 + r^2), here in long double;
/// marginal within an eighth of that bound, where the kernels' rounding decides. For a sphere
/// that a Scene keeps among its walls (`anchored_at`: the camera), the bound has the origin's
/// distance from the anchor (the surface point nearest the camera) in place of r.
OnSurface on_surface(const glint::Ray& ray, const Vec3& center, float radius,
                     const std::optional<Vec3>& anchored_at) {
  if (ray.origin_sphere == glint::kNoSphere || ray.t_min > 0.0f) return OnSurface::no;
  using L = long double;
  const L fx = L(ray.origin.x) - L(center.x), fy = L(ray.origin.y) - L(center.y),
          fz = L(ray.origin.z) - L(center.z);
  const L r = radius;
  const L c = std::abs(fx * fx + fy * fy + fz * fz - r * r);
  const L origin2 = L(ray.origin.x) * ray.origin.x + L(ray.origin.y) * ray.origin.y +
                    L(ray.origin.z) * ray.origin.z;
  L extent2 = r * r;
  if (anchored_at) {
    const glm::dvec3 to_camera = glm::dvec3(*anchored_at) - glm::dvec3(center);
    const glm::dvec3 anchor = glm::dvec3(center) + double(radius) * glm::normalize(to_camera);
    const glm::dvec3 g = glm::dvec3(ray.origin) - anchor;
    extent2 = glm::dot(g, g);
  }
  const L bound =
      2 * std::sqrt(L(2)) * L(glint::kOnSurfaceTolerance) * r * std::sqrt(origin2 + extent2);
  if (c < bound * L(7) / 8) return OnSurface::yes;
  if (c < bound * L(9) / 8) return OnSurface::marginal;
  return OnSurface::no;
}

/// The brute-force loop. With `apply_origin_rule` the ray's origin sphere is hit on its far
/// side when the ray heads into it (what Scene does); without, it is skipped altogether (what
/// the acceleration structures do, leaving the rule to their caller).
Reference brute_force(const std::vector<TestSphere>& spheres, const glint::Ray& ray,
                      bool apply_origin_rule) {
  Reference ref;
  for (const TestSphere& s : spheres) {
    const float scale = 1.0f + glm::length(ray.origin - s.center) + s.radius;
    const float slack = 1e-5f * scale;
    if (s.id == ray.origin_sphere) {
      if (!apply_origin_rule || !ray.heads_into_origin_sphere) continue;
      const float t = glint::far_side_distance(ray.origin, ray.direction, s.center);
      const bool marginal = std::abs(t - ray.t_min) < slack || std::abs(t - ray.t_max) < slack ||
                            t < 1e-3f * s.radius;  // nearly tangent: the chord is tiny
      if (t > ray.t_min - slack && t < ray.t_max + slack) {
        ref.candidates.push_back({s.id, t, slack, marginal});
        if (!marginal) ref.best = std::min(ref.best, t);
      }
      continue;
    }
    const Vec3 f = ray.origin - s.center;
    const float b = glm::dot(f, ray.direction);
    const Vec3 perpendicular = f - b * ray.direction;
    const float discriminant = s.radius * s.radius - glm::dot(perpendicular, perpendicular);
    bool near_tangent = std::abs(discriminant) < 1e-3f * s.radius * s.radius;
    // A ray leaving a sphere from an origin that counts as on this one (sphere_kernel.hpp)
    // meets it at t = 0 if it heads into it, else not at all; near the bound either way.
    // A Scene keeps the walls among its anchored spheres (anchored at its camera).
    const bool anchored = apply_origin_rule && s.radius > 1e4f;
    const OnSurface on =
        on_surface(ray, s.center, s.radius,
                   anchored ? std::optional(glint::CameraDescription{}.position) : std::nullopt);
    if (on != OnSurface::no) {
      const bool marginal = on == OnSurface::marginal || near_tangent;
      if (b < 0.0f && ray.t_max > 0.0f) {
        ref.candidates.push_back({s.id, 0.0f, slack, marginal});
        if (!marginal) ref.best = 0.0f;
      }
      if (!marginal) continue;
      near_tangent = true;  // the roots below are in doubt too
    }
    glint::SphereRoots roots{};
    if (!glint::intersect_sphere(ray.origin, ray.direction, s.center, s.radius, roots)) {
      if (near_tangent && -b > ray.t_min && -b < ray.t_max)
        ref.candidates.push_back({s.id, -b, slack, true});
      continue;
    }
    // Half chord / radius is the cosine of incidence; the error grows as its inverse.
    const float cosine = std::sqrt(std::max(0.0f, discriminant)) / s.radius;
    const float tolerance =
        slack + 4.0f * float(kUnitRoundoff) * s.radius / std::max(cosine, 1e-3f);
    for (const float t : {roots.near, roots.far}) {
      const bool at_end =
          std::abs(t - ray.t_min) < tolerance || std::abs(t - ray.t_max) < tolerance;
      if (t > ray.t_min - tolerance && t < ray.t_max + tolerance) {
        const bool marginal = near_tangent || at_end;
        ref.candidates.push_back({s.id, t, tolerance, marginal});
        if (!marginal) ref.best = std::min(ref.best, t);
        if (!at_end) break;  // the far root only matters if the near one is in doubt
      }
    }
  }
  return ref;
}

/// Whether (found, hit) is an acceptable closest hit for the reference.
bool acceptable(const Reference& ref, bool found, const glint::SphereHit& hit) {
  if (!found) return ref.best == glint::kInfinity;
  for (const Candidate& c : ref.candidates) {
    if (c.sphere != hit.sphere) continue;
    const bool same_t = std::abs(hit.t - c.t) <= c.tolerance;
    if ((same_t || c.marginal) && hit.t <= ref.best + c.tolerance) return true;
  }
  return false;
}

/// Whether an any-hit answer is acceptable.
bool acceptable_any(const Reference& ref, bool blocked) {
  if (ref.best < glint::kInfinity) return blocked;
  if (!blocked) return true;
  return !ref.candidates.empty();  // only marginal candidates: either answer is fine
}

[[maybe_unused]] float tolerance_for(const Reference& ref, std::uint32_t sphere) {
  float tolerance = 0.0f;
  for (const Candidate& c : ref.candidates)
    if (c.sphere == sphere) tolerance = std::max(tolerance, c.tolerance);
  return tolerance;
}

/// Spheres all over a box, sizes spread over two decades, some overlapping or nested; a
/// quarter of the sets also contain two 1e5-radius walls. Ids are scrambled unless
/// `ids_are_indices` (as a Scene numbers its spheres).
std::vector<TestSphere> random_spheres(glint::Pcg32& rng, int count, bool ids_are_indices) {
  std::vector<TestSphere> spheres;
  const bool with_walls = rng.next_u32() % 4 == 0;
  for (int i = 0; i < count; ++i) {
    const auto id = ids_are_indices ? std::uint32_t(i) : std::uint32_t(7919 * i % 10007 + 3);
    if (with_walls && i < 2) {
      const float side = i == 0 ? 1.0f : -1.0f;
      spheres.push_back({Vec3(side * (1e5f + 20.0f), 0.0f, 0.0f), 1e5f, id});
      continue;
    }
    const float extent = 10.0f + 0.5f * float(count);  // larger sets spread wider
    const Vec3 c(uniform(rng, -extent, extent), uniform(rng, -10.0f, 10.0f),
                 uniform(rng, -10.0f, 10.0f));
    spheres.push_back({c, 0.2f * std::pow(20.0f, rng.next_float()), id});
  }
  return spheres;
}

/// A random ray: from a random point (sometimes inside spheres), or leaving the surface of one
/// of the spheres inwards or outwards; with a random t_min and t_max some of the time.
glint::Ray random_ray(glint::Pcg32& rng, const std::vector<TestSphere>& spheres) {
  glint::Ray ray;
  const std::uint32_t kind = rng.next_u32() % 3;
  const TestSphere& s = spheres[rng.next_u32() % spheres.size()];
  // Rays leave the surface of ordinary spheres only: a point on a wall carries a rounding
  // error of ulp(1e5) that the tolerances here are not meant for.
  if (kind == 0 || s.radius > 1e4f) {
    ray.origin =
        Vec3(uniform(rng, -15.0f, 15.0f), uniform(rng, -15.0f, 15.0f), uniform(rng, -15.0f, 15.0f));
    ray.direction = random_unit_vector(rng);
  } else {
    const Vec3 normal = random_unit_vector(rng);
    Vec3 direction = random_unit_vector(rng);
    // kind 1: inwards, kind 2: outwards.
    if ((glm::dot(direction, normal) < 0.0f) != (kind == 1)) direction = -direction;
    ray = glint::ray_leaving_sphere(s.center + s.radius * normal, direction, s.id, normal);
  }
  if (rng.next_u32() % 4 == 0) ray.t_min = uniform(rng, 0.0f, 5.0f);
  if (rng.next_u32() % 3 == 0) ray.t_max = ray.t_min + uniform(rng, 0.0f, 25.0f);
  return ray;
}

glint::SphereSet make_set(const std::vector<TestSphere>& spheres) {
  glint::SphereSet set;
  for (const TestSphere& s : spheres)
    set.add(s.center, s.radius, s.id);
  return set;
}

glint::SphereBvh make_bvh(const std::vector<TestSphere>& spheres) {
  std::vector<glint::SphereBvh::Input> inputs;
  for (const TestSphere& s : spheres)
    inputs.push_back({s.center, s.radius, s.id});
  return glint::SphereBvh(std::move(inputs));
}

glint::Scene make_scene(const std::vector<TestSphere>& spheres) {
  glint::SceneDescription description;
  for (const TestSphere& s : spheres) {
    glint::SphereDescription sphere;
    sphere.center = s.center;
    sphere.radius = s.radius;
    description.spheres.push_back(sphere);  // opaque: any overlap is allowed
  }
  return glint::Scene::build(description);
}

std::string describe(const glint::Ray& ray, const Reference& ref) {
  std::string text = "ray from (" + std::to_string(ray.origin.x) + ", " +
                     std::to_string(ray.origin.y) + ", " + std::to_string(ray.origin.z) +
                     "), t in (" + std::to_string(ray.t_min) + ", " + std::to_string(ray.t_max) +
                     "), origin sphere " + std::to_string(int(ray.origin_sphere)) +
                     (ray.heads_into_origin_sphere ? " (inwards)" : "") + "; candidates:";
  for (const Candidate& c : ref.candidates)
    text += " [" + std::to_string(c.sphere) + " t=" + std::to_string(c.t) +
            (c.marginal ? " marginal]" : "]");
  return text;
}

/// Set sizes 1..37 exercise every amount of SIMD padding; the larger ones the hierarchy.
std::vector<int> set_sizes() {
  std::vector<int> sizes;
  for (int n = 1; n <= 37; ++n)
    sizes.push_back(n);
  for (const int n : {64, 65, 100, 250})
    sizes.push_back(n);
  return sizes;
}

struct Tally {
  int checked = 0, hits = 0, origin_sphere_hits = 0;
  void count(bool found, const glint::SphereHit& hit, const glint::Ray& ray) {
    ++checked;
    if (found) ++hits;
    if (found && hit.sphere == ray.origin_sphere) ++origin_sphere_hits;
  }
  /// The random rays exercised both outcomes.
  void check_coverage() const {
    CHECK(hits > checked / 8);
    CHECK(hits < checked - checked / 8);
  }
};

}  // namespace

TEST_CASE("Scene: origin-sphere rule, by hand", "[geometry][sphere_set]") {
  const std::vector<TestSphere> spheres = {
      {Vec3(0.0f), 2.0f, 0},            // the origin sphere
      {Vec3(0.0f), 0.5f, 1},            // inside it
      {{10.0f, 0.0f, 0.0f}, 1.0f, 2}};  // outside, to the right
  const glint::Scene scene = make_scene(spheres);
  const glint::Scene alone = make_scene({spheres[0]});
  const Vec3 outward(1.0f, 0.0f, 0.0f);
  const Vec3 on_surface(2.0f, 0.0f, 0.0f);

  SECTION("leaving outwards: the origin sphere is never hit") {
    const auto ray = glint::ray_leaving_sphere(on_surface, outward, 0, outward);
    const std::optional<glint::SphereHit> hit = scene.closest_hit(ray);
    REQUIRE(hit);
    CHECK(hit->sphere == 2u);
    CHECK(hit->t == Approx(7.0));
    CHECK_FALSE(alone.closest_hit(ray));
    CHECK_FALSE(alone.occluded(ray));
  }
  SECTION("a tangent direction counts as outwards") {
    const auto ray = glint::ray_leaving_sphere(on_surface, {0.0f, 1.0f, 0.0f}, 0, outward);
    CHECK_FALSE(ray.heads_into_origin_sphere);
    CHECK_FALSE(scene.closest_hit(ray));
    CHECK_FALSE(scene.occluded(ray));
  }
  SECTION("heading inwards: nearer spheres first, then only the far side") {
    const auto ray = glint::ray_leaving_sphere(on_surface, -outward, 0, outward);
    const std::optional<glint::SphereHit> hit = scene.closest_hit(ray);
    REQUIRE(hit);
    CHECK(hit->sphere == 1u);
    CHECK(hit->t == Approx(1.5));
    const std::optional<glint::SphereHit> far = alone.closest_hit(ray);
    REQUIRE(far);
    CHECK(far->sphere == 0u);
    CHECK(far->t == 4.0f);
    // Shadow rays: the far side at 4 blocks only a light beyond it.
    auto shadow = ray;
    shadow.t_max = 3.0f;
    CHECK_FALSE(alone.occluded(shadow));
    shadow.t_max = 5.0f;
    CHECK(alone.occluded(shadow));
    shadow.t_max = 1.0f;
    CHECK_FALSE(scene.occluded(shadow));  // the inner sphere is at 1.5
    shadow.t_max = 1.6f;
    CHECK(scene.occluded(shadow));
  }
  SECTION("the acceleration structures skip the origin sphere; a closer hit is kept") {
    const glint::SphereSet set = make_set(spheres);
    const auto ray = glint::ray_leaving_sphere(on_surface, -outward, 0, outward);
    glint::SphereHit hit;
    REQUIRE(set.closest_hit(ray, hit));
    CHECK(hit.sphere == 1u);
    const auto outwards = glint::ray_leaving_sphere(on_surface, outward, 1, outward);
    glint::SphereHit from_inner;  // "leaving" sphere 1: sphere 0 is hit from inside at t = 0
    CHECK_FALSE(make_set({spheres[1]}).closest_hit(outwards, from_inner));
    glint::SphereHit kept;
    kept.t = 1.0f;
    kept.sphere = 42;
    CHECK_FALSE(set.closest_hit(ray, kept));
    CHECK(kept.t == 1.0f);
    CHECK(kept.sphere == 42u);
  }
}

TEST_CASE("Scene: self-intersection is impossible on random surface points",
          "[geometry][sphere_set]") {
  // Without the origin rule a ray leaving a point rounded onto the surface would hit its own
  // sphere again at t ~ 1e-6 (or miss its far side): here it never does.
  glint::Pcg32 rng(21, 8);
  for (int trial = 0; trial < 1000; ++trial) {
    const Vec3 c(uniform(rng, -100.0f, 100.0f), uniform(rng, -100.0f, 100.0f),
                 uniform(rng, -100.0f, 100.0f));
    const float r = 0.01f * std::pow(1e4f, rng.next_float());
    const glint::Scene scene = make_scene({{c, r, 0}});
    const Vec3 n = random_unit_vector(rng);
    const Vec3 d = random_unit_vector(rng);
    const Vec3 out = glm::dot(d, n) > 0.0f ? d : -d;
    const auto outwards = glint::ray_leaving_sphere(c + r * n, out, 0, n);
    CHECK_FALSE(scene.closest_hit(outwards));
    CHECK_FALSE(scene.occluded(outwards));
    const auto inwards = glint::ray_leaving_sphere(c + r * n, -out, 0, n);
    if (glm::dot(-out, n) > -1e-3f) continue;  // nearly tangent: the chord is ~0
    const std::optional<glint::SphereHit> far = scene.closest_hit(inwards);
    REQUIRE(far);
    CHECK(far->sphere == 0u);
    const double chord = -2.0 * double(r) * glm::dot(-out, n);
    CHECK(std::abs(far->t - chord) <= 8.0 * kUnitRoundoff * (glm::length(c) + r));
  }
}

TEST_CASE("SphereSet, SphereBvh and Scene match a brute-force loop over intersect_sphere",
          "[geometry][sphere_set]") {
  glint::Pcg32 rng(1234, 5);
  Tally set_tally, bvh_tally, scene_tally;
  for (const int count : set_sizes()) {
    for (int set_index = 0; set_index < 3; ++set_index) {
      const std::vector<TestSphere> scrambled = random_spheres(rng, count, false);
      const glint::SphereSet set = make_set(scrambled);
      const glint::SphereBvh bvh = make_bvh(scrambled);
      REQUIRE(set.size() == scrambled.size());
      const std::vector<TestSphere> indexed = random_spheres(rng, count, true);
      const glint::Scene scene = make_scene(indexed);
      for (int r = 0; r < 50; ++r) {
        {
          const glint::Ray ray = random_ray(rng, scrambled);
          const Reference ref = brute_force(scrambled, ray, /*apply_origin_rule=*/false);
          glint::SphereHit set_hit, bvh_hit;
          const bool in_set = set.closest_hit(ray, set_hit);
          const bool in_bvh = bvh.closest_hit(ray, bvh_hit);
          INFO(count << " spheres; " << describe(ray, ref) << "; set " << in_set << " sphere "
                     << int(set_hit.sphere) << " t=" << set_hit.t << "; bvh " << in_bvh
                     << " sphere " << int(bvh_hit.sphere) << " t=" << bvh_hit.t);
          CHECK(acceptable(ref, in_set, set_hit));
          CHECK(acceptable(ref, in_bvh, bvh_hit));
          CHECK(acceptable_any(ref, set.any_hit(ray)));
          CHECK(acceptable_any(ref, bvh.any_hit(ray)));
          set_tally.count(in_set, set_hit, ray);
          bvh_tally.count(in_bvh, bvh_hit, ray);
        }
        {
          const glint::Ray ray = random_ray(rng, indexed);
          const Reference ref = brute_force(indexed, ray, /*apply_origin_rule=*/true);
          const std::optional<glint::SphereHit> closest = scene.closest_hit(ray);
          const bool found = closest.has_value();
          const glint::SphereHit hit = closest.value_or(glint::SphereHit{});
          INFO(count << " spheres in a scene; " << describe(ray, ref) << "; got " << found
                     << " sphere " << int(hit.sphere) << " t=" << hit.t);
          CHECK(acceptable(ref, found, hit));
          CHECK(acceptable_any(ref, scene.occluded(ray)));
          scene_tally.count(found, hit, ray);
        }
      }
    }
  }
  set_tally.check_coverage();
  bvh_tally.check_coverage();
  scene_tally.check_coverage();
  CHECK(set_tally.origin_sphere_hits == 0);
  CHECK(bvh_tally.origin_sphere_hits == 0);
  CHECK(scene_tally.origin_sphere_hits > scene_tally.checked / 50);
}

TEST_CASE("SphereSet: the SIMD kernel answers as the scalar kernel, bit for bit",
          "[geometry][sphere_set]") {
#ifdef GLINT_AVX2
  // Both round alike (sphere_kernel.hpp), so that an image does not depend on which kernel, or
  // which CPU, tested a sphere: the same hit, the same t to the bit, on every ray, the rays
  // that leave a sphere from its surface included.
  glint::Pcg32 rng(99, 6);
  int compared = 0, hits = 0;
  for (const int count : set_sizes()) {
    for (int set_index = 0; set_index < 3; ++set_index) {
      const std::vector<TestSphere> spheres = random_spheres(rng, count, true);
      const glint::SphereSet set = make_set(spheres);
      for (int r = 0; r < 50; ++r) {
        const glint::Ray ray = random_ray(rng, spheres);
        glint::SphereHit scalar_hit, simd_hit;
        const bool scalar = set.closest_hit_scalar(ray, scalar_hit);
        const bool simd = set.closest_hit_avx2(ray, simd_hit);
        INFO(count << " spheres; scalar " << scalar << " " << int(scalar_hit.sphere)
                   << " t=" << scalar_hit.t << ", simd " << simd << " " << int(simd_hit.sphere)
                   << " t=" << simd_hit.t);
        CHECK(simd == scalar);
        CHECK(simd_hit.sphere == scalar_hit.sphere);
        CHECK(std::bit_cast<std::uint32_t>(simd_hit.t) ==
              std::bit_cast<std::uint32_t>(scalar_hit.t));
        CHECK(set.any_hit_avx2(ray) == set.any_hit_scalar(ray));
        ++compared;
        hits += scalar ? 1 : 0;
      }
    }
  }
  CHECK(hits > compared / 4);
#else
  WARN("built without AVX2: only the scalar kernel exists");
  SUCCEED();
#endif
}

TEST_CASE("SphereSet: padding lanes are never hit", "[geometry][sphere_set]") {
  // Padding holds spheres of squared radius -1 at the origin: a ray through the origin must
  // still miss when the set is not a multiple of the SIMD width.
  for (std::uint32_t count = 1; count <= 9; ++count) {
    glint::SphereSet set;
    for (std::uint32_t i = 0; i < count; ++i)
      set.add({100.0f + 10.0f * float(i), 0.0f, 0.0f}, 1.0f, i);
    glint::Ray ray;
    ray.origin = {0.0f, 0.0f, -5.0f};
    ray.direction = {0.0f, 0.0f, 1.0f};
    glint::SphereHit hit;
    CHECK_FALSE(set.closest_hit(ray, hit));
    CHECK_FALSE(set.any_hit(ray));
  }
}

// ---- One tie rule: nearest t, then the lowest sphere id ------------------------------------

namespace {

/// Spheres off the z axis, which the rays below never meet; ids from `first_id` up.
std::vector<TestSphere> spheres_off_axis(int count, std::uint32_t first_id) {
  std::vector<TestSphere> spheres;
  for (int i = 0; i < count; ++i)
    spheres.push_back({Vec3(3.0f * float(i), 100.0f, 0.0f), 1.0f, first_id + std::uint32_t(i)});
  return spheres;
}

glint::Ray ray_along_z() {
  glint::Ray ray;
  ray.origin = Vec3(0.0f);
  ray.direction = Vec3(0.0f, 0.0f, 1.0f);
  return ray;
}

}  // namespace

TEST_CASE("SphereSet and SphereBvh: coincident spheres go to the lowest id",
          "[geometry][sphere_set][bvh]") {
  // Coincident copies of one sphere on the ray, scattered over SIMD lanes, groups and leaves,
  // with ids in no particular order; every structure and kernel must report the lowest.
  const std::uint32_t copy_ids[] = {700, 41, 9000, 42, 513};
  for (const int filler : {0, 3, 13, 40, 200}) {
    std::vector<TestSphere> spheres = spheres_off_axis(filler, 1000);
    for (std::size_t k = 0; k < std::size(copy_ids); ++k) {
      const auto at = std::min(spheres.size(), k * std::size_t(filler + 7) / 3);
      spheres.insert(spheres.begin() + std::ptrdiff_t(at),
                     TestSphere{Vec3(0.0f, 0.0f, 10.0f), 1.0f, copy_ids[k]});
    }
    const glint::SphereSet set = make_set(spheres);
    const glint::SphereBvh bvh = make_bvh(spheres);
    const glint::Ray ray = ray_along_z();
    INFO(spheres.size() << " spheres");

    glint::SphereHit scalar, bvh_hit;
    REQUIRE(set.closest_hit_scalar(ray, scalar));
    REQUIRE(bvh.closest_hit(ray, bvh_hit));
    CHECK(scalar.sphere == 41u);
    CHECK(scalar.t == 9.0f);
    CHECK(bvh_hit.sphere == 41u);
    CHECK(bvh_hit.t == 9.0f);
#ifdef GLINT_AVX2
    glint::SphereHit simd;
    REQUIRE(set.closest_hit_avx2(ray, simd));
    CHECK(simd.sphere == 41u);
    CHECK(simd.t == 9.0f);
#endif

    // A caller's hit at the same t competes by id too: a higher id loses, a lower one wins.
    for (const std::uint32_t caller_id : {40u, 41u, 43u}) {
      const glint::SphereHit caller{9.0f, caller_id};
      const bool replaced = caller_id > 41u;
      glint::SphereHit in_set = caller, in_bvh = caller;
      CHECK(set.closest_hit(ray, in_set) == replaced);
      CHECK(bvh.closest_hit(ray, in_bvh) == replaced);
      CHECK(in_set.sphere == (replaced ? 41u : caller_id));
      CHECK(in_bvh.sphere == (replaced ? 41u : caller_id));
    }

    // t_max is an open bound: a hit exactly there does not count, whatever its id.
    glint::Ray short_ray = ray;
    short_ray.t_max = 9.0f;
    glint::SphereHit none_in_set, none_in_bvh;
    CHECK_FALSE(set.closest_hit(short_ray, none_in_set));
    CHECK_FALSE(bvh.closest_hit(short_ray, none_in_bvh));
    CHECK_FALSE(set.any_hit(short_ray));
    CHECK_FALSE(bvh.any_hit(short_ray));
    short_ray.t_max = std::nextafter(9.0f, 10.0f);
    CHECK(set.any_hit(short_ray));
    CHECK(bvh.any_hit(short_ray));
  }
}

TEST_CASE("Scene: equal distances go to the lowest index, across its accelerators",
          "[geometry][sphere_set][bvh]") {
  const glint::Ray ray = ray_along_z();
  SECTION("coincident spheres in the linear set and in the hierarchy") {
    for (const int filler : {2, 80}) {  // up to 64 spheres the scene is one SphereSet
      std::vector<TestSphere> spheres = spheres_off_axis(filler, 0);
      spheres.insert(spheres.begin() + 1, TestSphere{Vec3(0.0f, 0.0f, 10.0f), 1.0f, 0});
      spheres.push_back(TestSphere{Vec3(0.0f, 0.0f, 10.0f), 1.0f, 0});
      const glint::Scene scene = make_scene(spheres);
      const std::optional<glint::SphereHit> hit = scene.closest_hit(ray);
      REQUIRE(hit);
      CHECK(hit->sphere == 1u);
      CHECK(hit->t == 9.0f);
    }
  }
  SECTION("a wall in the linear set and a sphere in the hierarchy, met at the same t") {
    // Both meet the ray at exactly t = 9 (every step is exact in float): the small sphere of
    // radius 1 at z = 10, and a sphere of radius 1024 at z = 1033, which the scene keeps out
    // of its hierarchy (more than 100 times the median radius).
    const TestSphere wall{Vec3(0.0f, 0.0f, 1033.0f), 1024.0f, 0};
    const TestSphere small{Vec3(0.0f, 0.0f, 10.0f), 1.0f, 0};
    for (const bool wall_first : {true, false}) {
      std::vector<TestSphere> spheres = {wall_first ? wall : small, wall_first ? small : wall};
      for (const TestSphere& s : spheres_off_axis(80, 0))
        spheres.push_back(s);
      const glint::Scene scene = make_scene(spheres);
      const std::optional<glint::SphereHit> hit = scene.closest_hit(ray);
      REQUIRE(hit);
      CHECK(hit->sphere == 0u);
      CHECK(hit->t == 9.0f);
    }
  }
}
