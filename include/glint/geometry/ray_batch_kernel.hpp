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

#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"

#ifdef GLINT_AVX2
namespace glint::inline GLINT_ISA_NAMESPACE::simd {

/// The values of `column` of kLanesOf<F> / kBatchWidth consecutive batches from `batches` on
/// (one batch at Float<8>, two at Float<16>), lane i from lane i % 8 of batch i / 8.
template <FloatType F, class Batch, class T>
inline auto column_lanes(const Batch* batches, const T (Batch::*column)[kBatchWidth]) {
  using Lanes = std::conditional_t<std::is_same_v<T, float>, F, UIntFor<F>>;
  using Half = std::conditional_t<std::is_same_v<T, float>, Float<kBatchWidth>, UInt<kBatchWidth>>;
  if constexpr (kLanesOf<F> == kBatchWidth)
    return load<Lanes>(batches[0].*column);
  else
    return join(load<Half>(batches[0].*column), load<Half>(batches[1].*column));
}

/// The rays of the batches from `batches` on, one per lane.
template <FloatType F = GroupFloat>
inline SphereTestRays<F> ray_lanes(const RayBatch* batches) {
  return SphereTestRays<F>(
      column_lanes<F>(batches, &RayBatch::origin_x), column_lanes<F>(batches, &RayBatch::origin_y),
      column_lanes<F>(batches, &RayBatch::origin_z),
      column_lanes<F>(batches, &RayBatch::direction_x),
      column_lanes<F>(batches, &RayBatch::direction_y),
      column_lanes<F>(batches, &RayBatch::direction_z), column_lanes<F>(batches, &RayBatch::t_min),
      column_lanes<F>(batches, &RayBatch::origin_sphere));
}
inline SphereTestRays<GroupFloat> ray_lanes(const RayBatch& rays) {
  return ray_lanes<GroupFloat>(&rays);
}

/// The hits of the HitBatches from `batches` on, one per lane.
template <FloatType F = GroupFloat>
inline HitLanes<F> hit_lanes(const HitBatch* batches) {
  return HitLanes<F>(column_lanes<F>(batches, &HitBatch::t),
                     column_lanes<F>(batches, &HitBatch::sphere));
}

/// Copies the lanes of `mask` of `lanes` into `hits` (lanes 8-15 into hits[1]), leaving its
/// other lanes as they were.
template <FloatType F>
inline void store_lanes(const HitLanes<F>& lanes, LaneMask mask, HitBatch* hits) {
  if constexpr (kLanesOf<F> == kBatchWidth) {
    const MaskFor<F> in_mask = mask_of_bits<MaskFor<F>>(mask);
    store(hits->t, select(in_mask, lanes.t, load<F>(hits->t)));
    store(hits->sphere, select(in_mask, lanes.sphere, load<UIntFor<F>>(hits->sphere)));
  } else {
#ifdef GLINT_AVX512
    // Masked stores of each half, where the width-8 form would load, blend and store.
    const auto low = __mmask8(mask & 0xffu);
    const auto high = __mmask8(mask >> kBatchWidth);
    const __m512 t = std::bit_cast<__m512>(lanes.t);
    const __m512i sphere = std::bit_cast<__m512i>(lanes.sphere);
    _mm256_mask_store_ps(hits[0].t, low, _mm512_extractf32x8_ps(t, 0));
    _mm256_mask_store_ps(hits[1].t, high, _mm512_extractf32x8_ps(t, 1));
    _mm256_mask_store_epi32(hits[0].sphere, low, _mm512_extracti32x8_epi32(sphere, 0));
    _mm256_mask_store_epi32(hits[1].sphere, high, _mm512_extracti32x8_epi32(sphere, 1));
#else
    store_lanes(HitLanes<GroupFloat>(low_half(lanes.t), low_half(lanes.sphere)), mask & 0xffu,
                hits);
    store_lanes(HitLanes<GroupFloat>(high_half(lanes.t), high_half(lanes.sphere)),
                mask >> kBatchWidth, hits + 1);
#endif
  }
}

/// test_lanes for every sphere of `spheres`, broadcast in turn; returns the lanes whose best
/// changed. With kAnyHit, stops once every lane of `pending` has a hit.
template <bool kAnyHit, FloatType F, class Columns>
inline LaneMask scan_rays(const SphereTestRays<F>& rays, const Columns& spheres, HitLanes<F>& best,
                          LaneMask pending) {
  LaneMask changed = 0;
  for (std::size_t i = 0; i < spheres.size; ++i) {
    changed |= LaneMask(
        test_lanes(rays, broadcast_lanes<F>(spheres, i), splat<UIntFor<F>>(spheres.id[i]), best));
    if constexpr (kAnyHit) {
      if ((changed & pending) == pending) break;
    }
  }
  return changed;
}

/// simd::closest_hit for the rays of a batch over all of `sets`: each lane's `best` starts as
/// the hit its ray has to beat (hit_to_beat; t = -infinity in a lane that holds no ray, which
/// nothing beats) and ends as the first hit in hit order; returns the lanes that found one.
template <FloatType F, class... Columns>
inline LaneMask closest_hits(const SphereTestRays<F>& rays, HitLanes<F>& best,
                             const Columns&... sets) {
  return (scan_rays<false>(rays, sets, best, 0) | ...);
}

/// simd::any_hit for the lanes of `pending`, each against its own `bound`: the lanes of
/// `pending` that some sphere of `sets` blocks.
template <FloatType F, class... Columns>
inline LaneMask any_hits(const SphereTestRays<F>& rays, HitLanes<F> bound, LaneMask pending,
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

}  // namespace glint::inline GLINT_ISA_NAMESPACE::simd
#endif
