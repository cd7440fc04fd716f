#pragma once
// The ray-parallel form of the leaf kernel: the rays of a RayBatch (or, with AVX-512, of two
// consecutive ones), one per lane, against one sphere at a time, its values broadcast. Each
// lane pairs its ray with the sphere through the very arithmetic of the sphere-parallel scan
// (test_lanes, sphere_kernel.hpp: the same operations, fused alike and in the same order,
// the roles of broadcast and lane swapped, at eight lanes or sixteen), so each ray gets bit for
// bit the t that the single-ray AVX2 scan gives it; and since hit order is total, keeping the
// first in hit order sphere by sphere gives the answer that the scan's eight lanes and final
// reduction give. Used by Scene's batched queries for the walls and the linear set of small
// scenes.

#include <cstddef>
#include <cstdint>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"

#ifdef GLINT_AVX2
namespace glint::inline GLINT_ISA_NAMESPACE::avx2 {

/// The values of `column` of L::kWidth / kBatchWidth consecutive batches from `batches` on
/// (one batch for Lanes8, two for Lanes16), lane i from lane i % 8 of batch i / 8.
template <class L, class Batch>
inline typename L::F column_lanes(const Batch* batches, const float (Batch::*column)[kBatchWidth]) {
  if constexpr (L::kWidth == kBatchWidth)
    return L::load(batches[0].*column);
  else
    return L::join(batches[0].*column, batches[1].*column);
}
template <class L, class Batch>
inline typename L::I column_lanes(const Batch* batches,
                                  const std::uint32_t (Batch::*column)[kBatchWidth]) {
  if constexpr (L::kWidth == kBatchWidth)
    return L::load(batches[0].*column);
  else
    return L::join(batches[0].*column, batches[1].*column);
}

/// The rays of the batches from `batches` on, one per lane.
template <class L = Lanes8>
inline BasicRayLanes<L> ray_lanes(const RayBatch* batches) {
  return BasicRayLanes<L>(
      column_lanes<L>(batches, &RayBatch::origin_x), column_lanes<L>(batches, &RayBatch::origin_y),
      column_lanes<L>(batches, &RayBatch::origin_z),
      column_lanes<L>(batches, &RayBatch::direction_x),
      column_lanes<L>(batches, &RayBatch::direction_y),
      column_lanes<L>(batches, &RayBatch::direction_z), column_lanes<L>(batches, &RayBatch::t_min),
      column_lanes<L>(batches, &RayBatch::origin_sphere));
}
inline RayLanes ray_lanes(const RayBatch& rays) {
  return ray_lanes<Lanes8>(&rays);
}

/// The hits of the HitBatches from `batches` on, one per lane.
template <class L = Lanes8>
inline BasicHitLanes<L> hit_lanes(const HitBatch* batches) {
  return BasicHitLanes<L>(column_lanes<L>(batches, &HitBatch::t),
                          column_lanes<L>(batches, &HitBatch::sphere));
}

/// Copies the lanes of `mask` of `lanes` into `hits`, leaving its other lanes as they were.
inline void store_lanes(const HitLanes& lanes, LaneMask mask, HitBatch* hits) {
  const __m256i in_mask = lane_vector(mask);
  _mm256_store_ps(hits->t,
                  _mm256_blendv_ps(_mm256_load_ps(hits->t), lanes.t, _mm256_castsi256_ps(in_mask)));
  auto* sphere = reinterpret_cast<__m256i*>(hits->sphere);
  _mm256_store_si256(sphere, _mm256_blendv_epi8(_mm256_load_si256(sphere), lanes.sphere, in_mask));
}

#ifdef GLINT_AVX512
/// store_lanes for sixteen lanes: 0-7 into hits[0], 8-15 into hits[1].
inline void store_lanes(const BasicHitLanes<Lanes16>& lanes, LaneMask mask, HitBatch* hits) {
  const auto low = __mmask8(mask & 0xffu);
  const auto high = __mmask8(mask >> kBatchWidth);
  _mm256_mask_store_ps(hits[0].t, low, _mm512_extractf32x8_ps(lanes.t, 0));
  _mm256_mask_store_ps(hits[1].t, high, _mm512_extractf32x8_ps(lanes.t, 1));
  _mm256_mask_store_epi32(hits[0].sphere, low, _mm512_extracti32x8_epi32(lanes.sphere, 0));
  _mm256_mask_store_epi32(hits[1].sphere, high, _mm512_extracti32x8_epi32(lanes.sphere, 1));
}
#endif

/// test_lanes for every sphere of `spheres`, broadcast in turn; returns the lanes whose best
/// changed. With kAnyHit, stops once every lane of `pending` has a hit.
template <bool kAnyHit, class L, class Columns>
inline LaneMask scan_rays(const BasicRayLanes<L>& rays, const Columns& spheres,
                          BasicHitLanes<L>& best, LaneMask pending) {
  LaneMask changed = 0;
  for (std::size_t i = 0; i < spheres.size; ++i) {
    changed |= LaneMask(test_lanes(rays, broadcast_lanes<L>(spheres, i),
                                   L::splat(static_cast<std::int32_t>(spheres.id[i])), best));
    if constexpr (kAnyHit) {
      if ((changed & pending) == pending) break;
    }
  }
  return changed;
}

/// avx2::closest_hit for the rays of a batch over all of `sets`: each lane's `best` starts as
/// the hit its ray has to beat (hit_to_beat; t = -infinity in a lane that holds no ray, which
/// nothing beats) and ends as the first hit in hit order; returns the lanes that found one.
template <class L, class... Columns>
inline LaneMask closest_hits(const BasicRayLanes<L>& rays, BasicHitLanes<L>& best,
                             const Columns&... sets) {
  return (scan_rays<false>(rays, sets, best, 0) | ...);
}

/// avx2::any_hit for the lanes of `pending`, each against its own `bound`: the lanes of
/// `pending` that some sphere of `sets` blocks.
template <class L, class... Columns>
inline LaneMask any_hits(const BasicRayLanes<L>& rays, BasicHitLanes<L> bound, LaneMask pending,
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
