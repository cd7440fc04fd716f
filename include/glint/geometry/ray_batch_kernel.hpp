#pragma once
// The ray-parallel form of the 8-wide leaf kernel: eight rays of a RayBatch, one per lane,
// against one sphere at a time, its values broadcast. Each lane pairs its ray with the sphere
// through the very arithmetic of the sphere-parallel scan (avx2::test_lanes, sphere_kernel.hpp:
// the same intrinsics, fused operations and order, the roles of broadcast and lane swapped), so
// each ray gets bit for bit the t that the single-ray AVX2 scan gives it; and since hit order
// is total, keeping the first in hit order sphere by sphere gives the answer that the scan's
// eight lanes and final reduction give. Used by Scene's batched queries for the walls and the
// linear set of small scenes.

#include <cstddef>
#include <cstdint>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"

#ifdef GLINT_AVX2
namespace glint::inline GLINT_ISA_NAMESPACE::avx2 {

/// The rays of a batch, one per lane.
inline RayLanes ray_lanes(const RayBatch& rays) {
  return RayLanes(_mm256_load_ps(rays.origin_x), _mm256_load_ps(rays.origin_y),
                  _mm256_load_ps(rays.origin_z), _mm256_load_ps(rays.direction_x),
                  _mm256_load_ps(rays.direction_y), _mm256_load_ps(rays.direction_z),
                  _mm256_load_ps(rays.t_min),
                  _mm256_load_si256(reinterpret_cast<const __m256i*>(rays.origin_sphere)));
}

/// The hits of a HitBatch, one per lane.
inline HitLanes hit_lanes(const HitBatch& hits) {
  return HitLanes(_mm256_load_ps(hits.t),
                  _mm256_load_si256(reinterpret_cast<const __m256i*>(hits.sphere)));
}

/// Copies the lanes of `mask` of `lanes` into `hits`, leaving its other lanes as they were.
inline void store_lanes(const HitLanes& lanes, LaneMask mask, HitBatch& hits) {
  const __m256i in_mask = lane_vector(mask);
  _mm256_store_ps(hits.t,
                  _mm256_blendv_ps(_mm256_load_ps(hits.t), lanes.t, _mm256_castsi256_ps(in_mask)));
  auto* sphere = reinterpret_cast<__m256i*>(hits.sphere);
  _mm256_store_si256(sphere, _mm256_blendv_epi8(_mm256_load_si256(sphere), lanes.sphere, in_mask));
}

/// test_lanes for every sphere of `spheres`, broadcast in turn; returns the lanes whose best
/// changed. With kAnyHit, stops once every lane of `pending` has a hit.
template <bool kAnyHit, class Columns>
inline LaneMask scan_rays(const RayLanes& rays, const Columns& spheres, HitLanes& best,
                          LaneMask pending) {
  LaneMask changed = 0;
  for (std::size_t i = 0; i < spheres.size; ++i) {
    changed |= LaneMask(test_lanes(rays, broadcast_lanes(spheres, i),
                                   _mm256_set1_epi32(static_cast<int>(spheres.id[i])), best));
    if constexpr (kAnyHit) {
      if ((changed & pending) == pending) break;
    }
  }
  return changed;
}

/// avx2::closest_hit for the rays of a batch over all of `sets`: each lane's `best` starts as
/// the hit its ray has to beat (hit_to_beat; t = -infinity in a lane that holds no ray, which
/// nothing beats) and ends as the first hit in hit order; returns the lanes that found one.
template <class... Columns>
inline LaneMask closest_hits(const RayLanes& rays, HitLanes& best, const Columns&... sets) {
  return (scan_rays<false>(rays, sets, best, 0) | ...);
}

/// avx2::any_hit for the lanes of `pending`, each against its own `bound`: the lanes of
/// `pending` that some sphere of `sets` blocks.
template <class... Columns>
inline LaneMask any_hits(const RayLanes& rays, HitLanes bound, LaneMask pending,
                         const Columns&... sets) {
  LaneMask blocked = 0;
  // Whether every lane is blocked, after which the other sets need no scan.
  const auto scan_set = [&](const auto& set) {
    blocked |= scan_rays<true>(rays, set, bound, pending & ~blocked) & pending;
    return blocked == pending;
  };
  (scan_set(sets) || ...);
  return blocked;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::avx2
#endif
