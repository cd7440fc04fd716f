#pragma once
// The leaf kernel: rays against spheres, each ray keeping its first hit in hit order
// (accelerator.hpp). Where spheres cross, a ray's origin on one of them is decided by its
// direction (see below). The arithmetic is written once, test_lanes, over lanes that each pair a
// ray with a sphere, in the registers of Lanes1, Lanes8 or Lanes16 (simd.hpp); its formulas are
// ray_sphere.hpp's. At one lane it is test_sphere, which test_spheres runs over a run of spheres
// (SphereSet's and WallSet's scalar paths, the BVH's leaves); avx2::closest_hit and
// avx2::any_hit test one ray against eight spheres of the sets' structure-of-arrays storage
// (SphereColumns for spheres given by their centre, AnchoredColumns for anchored ones); in
// ray_batch_kernel.hpp eight or sixteen rays meet one sphere. Every operation rounds alike at
// every width, so each ray gets the same t from all of them, with or without FMA instructions.

#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_sphere.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Spheres given by centre and squared radius, addressed by index, as test_spheres reads them.
template <class S>
concept IndexedSpheres = requires(const S& s, std::size_t i) {
  { s.center(i) } -> std::convertible_to<Vec3>;
  { s.radius_squared(i) } -> std::convertible_to<float>;
  { s.id(i) } -> std::convertible_to<std::uint32_t>;
};

/// Anchored spheres (ray_sphere.hpp), addressed by index.
template <class S>
concept IndexedAnchoredSpheres = requires(const S& s, std::size_t i) {
  { s.anchored(i) } -> std::convertible_to<AnchoredSphere>;
  { s.id(i) } -> std::convertible_to<std::uint32_t>;
};

// Where spheres cross. A ray that leaves a sphere starts at a hit point rounded to float: on
// that sphere as far as the rule of Ray goes, but where another sphere crosses it there (a seam
// of two walls, the crease of two overlapping balls) only near that other one, inside it or
// outside by a rounding. Its quadratic there has a root within rounding of t = 0 whose sign is
// noise: taken at face value, a ray heading out of the room through the other wall passes
// through it, and one heading into the room meets it from inside at t ~ 1e-6, so that the path
// continues inside a wall and the pixel comes out black. So for a ray that leaves a sphere from
// its origin (t_min <= 0), an origin within about kOnSurfaceTolerance (|origin| + s) of another
// sphere's surface counts as on it (s: the radius, or for an anchored sphere the origin's
// distance from the anchor; with |origin| these scale the kernel's error in c and the rounding of
// the hit point), and its roots count as 0 and -2b: heading into the sphere (b < 0, against the
// outward normal) the ray meets it at t = 0, its origin; heading out it does not meet it. Only
// where the ray meets the sphere's line at all (a discriminant >= 0, which a point on the
// surface always has), so that what culls by the discriminant stays conservative.
//
// The tolerance, 2^-19 (32 u, u = 2^-24) of |origin| + s, is several times what the rounding of
// a hit point (a few u |origin|) and the kernel's error in c (a few u s in distance) come to, and
// covers the error of where along the ray a hit was found for rays that came from up to about ten
// times |origin| + s away (which the next ray does not know: a hit point of a camera much
// farther away may still land inside a sphere it only touches). The test is
// c^2 < 8 tol^2 r^2 (|origin|^2 + s^2), without a square root, strict so that a factor of 0
// turns it off.

/// The relative distance from a sphere's surface within which a ray's origin counts as on it.
inline constexpr float kOnSurfaceTolerance = 0x1p-19f;
/// 8 kOnSurfaceTolerance^2, the factor of the test above.
inline constexpr float kOnSurfaceFactor = 8.0f * kOnSurfaceTolerance * kOnSurfaceTolerance;

/// A ray in every lane, in registers of L (geometry/simd.hpp), with what the on-surface test
/// needs of it.
template <class L>
struct BasicRayLanes : LineLanes<L> {
  using F = typename L::F;
  using I = typename L::I;
  F t_min;
  I origin_sphere;
  /// The on-surface test's factor (kOnSurfaceFactor for a ray that leaves a sphere from its
  /// origin, else 0: no origin counts as on a surface) and that factor times |origin|^2.
  F on_surface_factor, on_surface_origin;
  bool any_on_surface_test;  ///< whether some lane's factor is not 0

  // (Inlined always: a query makes one, and GCC would otherwise call out for it.)
  [[gnu::always_inline]] explicit BasicRayLanes(const Ray& ray)
      : BasicRayLanes(L::splat(ray.origin.x), L::splat(ray.origin.y), L::splat(ray.origin.z),
                      L::splat(ray.direction.x), L::splat(ray.direction.y),
                      L::splat(ray.direction.z), L::splat(ray.t_min),
                      L::splat(static_cast<std::int32_t>(ray.origin_sphere))) {}
  /// A ray per lane (see ray_batch_kernel.hpp).
  [[gnu::always_inline]] BasicRayLanes(F ox_lanes, F oy_lanes, F oz_lanes, F dx_lanes, F dy_lanes,
                                       F dz_lanes, F t_min_lanes, I origin_sphere_lanes)
      : LineLanes<L>{ox_lanes, oy_lanes, oz_lanes, dx_lanes, dy_lanes, dz_lanes},
        t_min(t_min_lanes),
        origin_sphere(origin_sphere_lanes) {
    const typename L::M leaves_sphere =
        L::and_not(L::less_equal(t_min, L::zero()),
                   L::equal(origin_sphere, L::splat(static_cast<std::int32_t>(kNoSphere))));
    on_surface_factor = L::keep(leaves_sphere, L::splat(kOnSurfaceFactor));
    on_surface_origin = L::mul(
        on_surface_factor,
        L::fmadd(ox_lanes, ox_lanes, L::fmadd(oy_lanes, oy_lanes, L::mul(oz_lanes, oz_lanes))));
    any_on_surface_test = L::bits(leaves_sphere) != 0;
  }
};

/// A hit per lane.
template <class L>
struct BasicHitLanes {
  typename L::F t;
  typename L::I sphere;

  explicit BasicHitLanes(const SphereHit& hit)
      : t(L::splat(hit.t)), sphere(L::splat(static_cast<std::int32_t>(hit.sphere))) {}
  BasicHitLanes(typename L::F t_lanes, typename L::I sphere_lanes)
      : t(t_lanes), sphere(sphere_lanes) {}
};

/// For the ray and sphere of each lane, from their quadratic: in `ahead` whether the ray meets
/// the sphere past t_min, and in `t` where (the near root, or the far one from inside; 0 for an
/// origin on the sphere, see above). `radius_squared` and `extent_squared()` (s^2) are what the
/// on-surface test needs, the latter asked for only when some lane may be on a surface. Returns
/// false, leaving both unset, when no lane can have a root ahead of its ray.
template <class L, class ExtentSquared>
inline bool first_roots_from(const BasicRayLanes<L>& ray, const QuadraticLanes<L>& quadratic,
                             typename L::F radius_squared, ExtentSquared&& extent_squared,
                             typename L::F& t, typename L::M& ahead) {
  using F = typename L::F;
  using M = typename L::M;
  const F zero = L::zero();
  const M has_roots = L::greater_equal(quadratic.discriminant, zero);
  // One ray and one sphere: most spheres that reach the single-ray test are missed, and their
  // answer needs nothing more.
  if constexpr (L::kWidth == 1) {
    if (!has_roots) return false;
  }
  // The roots sum to -2b and multiply to c: from outside (c > 0) a sphere behind the origin
  // (b > 0) has no root ahead. Most groups hold only such spheres and misses, and skip the
  // square root and the division. (An origin on the surface has a root ahead only if b < 0.)
  const M b_negative = L::less(quadratic.b, zero);
  const M ahead_or_inside = L::either(b_negative, L::less_equal(quadratic.c, zero));
  if (L::bits(L::both(has_roots, ahead_or_inside)) == 0) return false;
  const RootLanes<L> both = roots_of(quadratic);
  t = L::select(L::greater(both.near, ray.t_min), both.near, both.far);
  ahead = L::both(has_roots, L::greater(t, ray.t_min));
  if (ray.any_on_surface_test) {
    const F tolerance = L::mul(
        radius_squared, L::fmadd(ray.on_surface_factor, extent_squared(), ray.on_surface_origin));
    const M on_surface = L::both(has_roots, L::less(L::mul(quadratic.c, quadratic.c), tolerance));
    t = L::select(on_surface, zero, t);
    ahead = L::select(on_surface, b_negative, ahead);
  }
  return true;
}

/// For the ray and sphere of each lane: in `ahead` whether the ray meets the sphere past t_min
/// (or on its origin, see above), and in `t` where. Returns false, leaving both unset, when no
/// lane can have a root ahead of its ray.
template <class L>
inline bool first_roots(const BasicRayLanes<L>& ray, const BasicSphereLanes<L>& sphere,
                        typename L::F& t, typename L::M& ahead) {
  return first_roots_from(
      ray, quadratic(ray, sphere), sphere.r2, [&] { return sphere.r2; }, t, ahead);
}

/// first_roots for anchored spheres, whose extent s is the origin's distance from the anchor.
template <class L>
inline bool first_roots(const BasicRayLanes<L>& ray, const BasicAnchoredLanes<L>& sphere,
                        typename L::F& t, typename L::M& ahead) {
  const AnchoredQuadraticLanes<L> q = quadratic(ray, sphere);
  return first_roots_from(
      ray, q, sphere.r2, [&] { return q.from_anchor_squared(); }, t, ahead);
}

/// comes_before, lane by lane (sphere ids compare unsigned, as std::uint32_t do).
template <class L>
inline typename L::M comes_before(const BasicHitLanes<L>& a, const BasicHitLanes<L>& b) {
  const typename L::M tie =
      L::and_not(L::equal(a.t, b.t), L::at_least_unsigned(a.sphere, b.sphere));
  return L::either(L::less(a.t, b.t), tie);
}

/// For the ray and sphere (of id `ids`) of each lane: if the ray meets the sphere past t_min
/// at a point that comes before the lane's `best`, makes it the best. The ray's origin sphere
/// is skipped (see Ray), and an origin on the sphere decided by the ray's direction (see
/// above). Returns the lanes whose best it changed (bit i for lane i).
template <class L, class Spheres>
inline unsigned test_lanes(const BasicRayLanes<L>& ray, const Spheres& spheres, typename L::I ids,
                           BasicHitLanes<L>& best) {
  typename L::F t;
  typename L::M ahead;
  if (!first_roots(ray, spheres, t, ahead)) return 0;
  const BasicHitLanes<L> candidate(t, ids);
  const typename L::M wins =
      L::both(L::and_not(ahead, L::equal(candidate.sphere, ray.origin_sphere)),
              comes_before(candidate, best));
  const unsigned won = L::bits(wins);
  if (won == 0) return 0;
  best.t = L::select(wins, candidate.t, best.t);
  best.sphere = L::select(wins, candidate.sphere, best.sphere);
  return won;
}

/// A ray as the single-ray kernel reads it: test_lanes at one lane.
using RayLane = BasicRayLanes<Lanes1>;

/// test_lanes for one ray and one sphere (a BasicSphereLanes<Lanes1> or
/// BasicAnchoredLanes<Lanes1>): whether sphere `id` became the best.
template <class Sphere>
inline bool test_sphere(const RayLane& ray, const Sphere& sphere, std::uint32_t id,
                        SphereHit& best) {
  const auto lane_id = static_cast<std::int32_t>(id);
  if (lane_id == ray.origin_sphere) return false;
  BasicHitLanes<Lanes1> lane(best);
  if (test_lanes(ray, sphere, lane_id, lane) == 0) return false;
  best = {lane.t, static_cast<std::uint32_t>(lane.sphere)};
  return true;
}

template <IndexedSpheres Spheres>
bool test_sphere_at(const RayLane& ray, const Spheres& spheres, std::size_t i, SphereHit& best) {
  const Vec3 center = spheres.center(i);
  return test_sphere(
      ray, BasicSphereLanes<Lanes1>{center.x, center.y, center.z, spheres.radius_squared(i)},
      spheres.id(i), best);
}

template <IndexedAnchoredSpheres Spheres>
bool test_sphere_at(const RayLane& ray, const Spheres& spheres, std::size_t i, SphereHit& best) {
  return test_sphere(ray, anchored_lane(spheres.anchored(i)), spheres.id(i), best);
}

/// test_sphere for spheres [begin, end); whether any of them became the best. With
/// `stop_at_first`, returns at the first such sphere (enough for an occlusion query).
template <class Spheres>
requires IndexedSpheres<Spheres> || IndexedAnchoredSpheres<Spheres>
bool test_spheres(const RayLane& ray, const Spheres& spheres, std::size_t begin, std::size_t end,
                  SphereHit& best, bool stop_at_first) {
  bool found = false;
  for (std::size_t i = begin; i < end; ++i) {
    if (!test_sphere_at(ray, spheres, i, best)) continue;
    found = true;
    if (stop_at_first) break;
  }
  return found;
}

/// Spheres in groups of kBatchWidth, structure-of-arrays within a group (the leaves of
/// SphereBvh): one AVX2 pass culls a group's spheres (avx2::may_meet), test_sphere decides for
/// the rest. A group holds the spheres of one leaf, or of the first or last kSize of one; its
/// lanes past them are padding, never read as spheres.
struct alignas(32) SphereGroup {
  static constexpr std::size_t kSize = kBatchWidth;
  float cx[kSize], cy[kSize], cz[kSize];
  float radius[kSize];
  std::uint32_t id[kSize];
};
static_assert(sizeof(SphereGroup) == 5 * 4 * SphereGroup::kSize);

/// SphereGroups as test_spheres reads them: sphere i is lane i % kSize of group i / kSize. The
/// centre, the radius and its square are those of the sphere as given, so that test_sphere answers
/// bit for bit as for any other storage of the same spheres.
struct GroupedSpheres {
  const SphereGroup* groups;

  Vec3 center(std::size_t i) const {
    const SphereGroup& g = groups[i / SphereGroup::kSize];
    const std::size_t lane = i % SphereGroup::kSize;
    return {g.cx[lane], g.cy[lane], g.cz[lane]};
  }
  float radius_squared(std::size_t i) const {
    const float r = groups[i / SphereGroup::kSize].radius[i % SphereGroup::kSize];
    return r * r;
  }
  std::uint32_t id(std::size_t i) const {
    return groups[i / SphereGroup::kSize].id[i % SphereGroup::kSize];
  }
};

#ifdef GLINT_AVX2
namespace avx2 {

/// Spheres in structure-of-arrays form, 32-byte aligned and padded to a multiple of
/// kBatchWidth with spheres that no ray can hit.
struct SphereColumns {
  const float* cx;
  const float* cy;
  const float* cz;
  const float* r2;
  const std::uint32_t* id;
  std::size_t size;  ///< without the padding
};

/// Anchored spheres (ray_sphere.hpp) in the same form; padding lanes have NaN anchors.
struct AnchoredColumns {
  const float* ax;
  const float* ay;
  const float* az;
  const float* mx;  ///< the offset of the anchor from the centre
  const float* my;
  const float* mz;
  const float* r2;
  const std::uint32_t* id;
  std::size_t size;  ///< without the padding
};

using RayLanes = BasicRayLanes<Lanes8>;
using SphereLanes = BasicSphereLanes<Lanes8>;
using AnchoredLanes = BasicAnchoredLanes<Lanes8>;
using HitLanes = BasicHitLanes<Lanes8>;

inline SphereLanes load_lanes(const SphereColumns& spheres, std::size_t base) {
  return {_mm256_load_ps(spheres.cx + base), _mm256_load_ps(spheres.cy + base),
          _mm256_load_ps(spheres.cz + base), _mm256_load_ps(spheres.r2 + base)};
}

/// Sphere `i` of `spheres` in every lane.
template <class L>
inline BasicSphereLanes<L> broadcast_lanes(const SphereColumns& spheres, std::size_t i) {
  return {L::splat(spheres.cx[i]), L::splat(spheres.cy[i]), L::splat(spheres.cz[i]),
          L::splat(spheres.r2[i])};
}

inline AnchoredLanes load_lanes(const AnchoredColumns& spheres, std::size_t base) {
  return {_mm256_load_ps(spheres.ax + base), _mm256_load_ps(spheres.ay + base),
          _mm256_load_ps(spheres.az + base), _mm256_load_ps(spheres.mx + base),
          _mm256_load_ps(spheres.my + base), _mm256_load_ps(spheres.mz + base),
          _mm256_load_ps(spheres.r2 + base)};
}

template <class L>
inline BasicAnchoredLanes<L> broadcast_lanes(const AnchoredColumns& spheres, std::size_t i) {
  return {L::splat(spheres.ax[i]), L::splat(spheres.ay[i]), L::splat(spheres.az[i]),
          L::splat(spheres.mx[i]), L::splat(spheres.my[i]), L::splat(spheres.mz[i]),
          L::splat(spheres.r2[i])};
}

/// test_sphere for the eight spheres at `base`, each lane keeping its own best.
template <class Columns>
inline bool test_8_spheres(const RayLanes& ray, const Columns& spheres, std::size_t base,
                           HitLanes& best) {
  return test_lanes(ray, load_lanes(spheres, base),
                    _mm256_load_si256(reinterpret_cast<const __m256i*>(spheres.id + base)),
                    best) != 0;
}

/// The first of the lanes' hits in hit order.
inline SphereHit first_in_hit_order(const HitLanes& lanes) {
  __m256 smallest = _mm256_min_ps(lanes.t, _mm256_permute_ps(lanes.t, 0b10110001));
  smallest = _mm256_min_ps(smallest, _mm256_permute_ps(smallest, 0b01001110));
  smallest = _mm256_min_ps(smallest, _mm256_permute2f128_ps(smallest, smallest, 1));
  alignas(32) std::uint32_t ids[kBatchWidth];
  _mm256_store_si256(reinterpret_cast<__m256i*>(ids), lanes.sphere);
  SphereHit first{_mm256_cvtss_f32(smallest), kNoSphere};
  const int at_smallest = _mm256_movemask_ps(_mm256_cmp_ps(lanes.t, smallest, _CMP_EQ_OQ));
  for (int mask = at_smallest; mask != 0; mask &= mask - 1) {
    const std::uint32_t id = ids[std::countr_zero(static_cast<unsigned>(mask))];
    if (id < first.sphere) first.sphere = id;
  }
  return first;
}

/// The lanes of `group` (bit i for lane i) whose sphere the ray may meet: a superset of those
/// in which test_sphere finds roots. test_sphere's own discriminant, eight spheres at once with
/// the same operations; a lane is culled only when it is below -2^-12 (|f|^2 + r^2), a margin
/// that keeps the cull conservative even in a build whose compiler contracts the single-ray
/// form's multiplications and additions differently (see -ffp-contract in CMakeLists.txt).
/// NaN keeps a lane. Most lanes of an incoherent ray's leaf are culled; the few kept cost one
/// single-ray test each.
inline unsigned may_meet(const RayLanes& ray, const SphereGroup& group) {
  const __m256 radius = _mm256_load_ps(group.radius);
  const SphereLanes spheres{_mm256_load_ps(group.cx), _mm256_load_ps(group.cy),
                            _mm256_load_ps(group.cz), _mm256_mul_ps(radius, radius)};
  const QuadraticLanes<Lanes8> q = quadratic(ray, spheres);
  // c + 2 r^2 = |f|^2 + r^2.
  const __m256 margin = _mm256_mul_ps(_mm256_fmadd_ps(_mm256_set1_ps(2.0f), spheres.r2, q.c),
                                      _mm256_set1_ps(-0x1p-12f));
  return Lanes8::bits(Lanes8::not_less(q.discriminant, margin));
}

/// test_8_spheres over all of `spheres`; with kAnyHit, stops at the first group with a hit.
template <bool kAnyHit, class Columns>
inline bool scan(const RayLanes& ray, const Columns& spheres, HitLanes& best) {
  bool found = false;
  for (std::size_t base = 0; base < spheres.size; base += std::size_t(kBatchWidth)) {
    if (!test_8_spheres(ray, spheres, base, best)) continue;
    found = true;
    if constexpr (kAnyHit) break;
  }
  return found;
}

/// The 8-wide form of glint::test_spheres over all of `sets` (SphereColumns or
/// AnchoredColumns), one after the other with one reduction at the end: a scene's walls and
/// its other spheres cost one query.
template <class... Columns>
inline bool closest_hit(const Ray& ray, SphereHit& best, const Columns&... sets) {
  const RayLanes ray_lanes(ray);
  HitLanes lanes(best);
  // Every set is scanned (no short circuit): a later set may hold a nearer hit.
  if (!(int(scan<false>(ray_lanes, sets, lanes)) | ...)) return false;
  best = first_in_hit_order(lanes);
  return true;
}

/// Whether any sphere of `sets` is hit before `bound`.
template <class... Columns>
inline bool any_hit(const Ray& ray, const SphereHit& bound, const Columns&... sets) {
  const RayLanes ray_lanes(ray);
  HitLanes lanes(bound);
  return (scan<true>(ray_lanes, sets, lanes) || ...);
}

}  // namespace avx2
#endif

/// What test_grouped_spheres reads of a ray: its lane for test_sphere and, with AVX2, the ray in
/// every lane for may_meet. Made once per ray.
struct GroupRay {
  explicit GroupRay(const Ray& ray)
      : one(ray)
#ifdef GLINT_AVX2
        ,
        every_lane(ray)
#endif
  {
  }
  RayLane one;
#ifdef GLINT_AVX2
  avx2::RayLanes every_lane;
#endif
};

/// test_spheres for spheres [first, first + count) of `groups`, `first` a multiple of
/// SphereGroup::kSize: with AVX2, a group's spheres that the ray cannot meet (avx2::may_meet)
/// are skipped before test_sphere, which decides for the others, so the answer is
/// test_spheres' bit for bit.
inline bool test_grouped_spheres(const GroupRay& ray, const SphereGroup* groups, std::size_t first,
                                 std::size_t count, SphereHit& best, bool stop_at_first) {
  const GroupedSpheres spheres{groups};
#ifdef GLINT_AVX2
  bool found = false;
  const std::size_t end = first + count;
  for (std::size_t base = first; base < end; base += SphereGroup::kSize) {
    const std::size_t size = end - base < SphereGroup::kSize ? end - base : SphereGroup::kSize;
    unsigned candidates =
        avx2::may_meet(ray.every_lane, groups[base / SphereGroup::kSize]) & ((1u << size) - 1u);
    for (; candidates != 0; candidates &= candidates - 1) {
      if (!test_sphere_at(ray.one, spheres, base + std::size_t(std::countr_zero(candidates)), best))
        continue;
      found = true;
      if (stop_at_first) return true;
    }
  }
  return found;
#else
  return test_spheres(ray.one, spheres, first, first + count, best, stop_at_first);
#endif
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
