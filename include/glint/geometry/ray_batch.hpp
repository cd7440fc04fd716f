#pragma once
// A batch of rays (kBatchWidth, geometry/simd.hpp) and their hits in structure-of-arrays form,
// for the batched queries of the scene's accelerators (closest hit and occlusion for a batch at
// once) that the wavefront renderer uses. A lane mask says which lanes hold a ray: bit i set means
// lane i is active. The batched queries answer exactly what the single-ray queries answer for each
// active lane, bit for bit; those stay the reference.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Bit i is lane i of a batch.
using LaneMask = std::uint32_t;
static_assert(kBatchWidth < 32,
              "a LaneMask holds a bit per lane of a batch, and kAllLanes one more");

/// What a caller of the batched queries knows of its rays: a hint for the traversal, which
/// changes only its speed, never an answer (like Embree's coherent and incoherent contexts).
enum class RayCoherence {
  /// Batches of a renderer: the rays of a batch may go different ways, but consecutive batches
  /// come from neighbouring paths and reuse what the last ones brought into the caches. A
  /// BVH takes batches in one octant as a packet, the others ray by ray.
  unknown,
  /// Rays with nothing in common from one batch to the next (queries scattered over a scene):
  /// the traversals of a batch's rays in a BVH larger than the caches are interleaved, so that they
  /// wait
  /// on memory together (SphereBvh::kInterleavedTraversalBytes).
  incoherent,
};

struct alignas(32) RayBatch {
  static constexpr int kWidth = kBatchWidth;
  static constexpr LaneMask kAllLanes = (LaneMask(1) << kWidth) - 1;

  float origin_x[kWidth];
  float origin_y[kWidth];
  float origin_z[kWidth];
  float direction_x[kWidth];
  float direction_y[kWidth];
  float direction_z[kWidth];
  float t_min[kWidth];
  float t_max[kWidth];
  std::uint32_t origin_sphere[kWidth];
  /// Ray::heads_into_origin_sphere, one bit per lane.
  LaneMask heads_into_origin_sphere = 0;

  void set(int lane, const Ray& ray) {
    origin_x[lane] = ray.origin.x;
    origin_y[lane] = ray.origin.y;
    origin_z[lane] = ray.origin.z;
    direction_x[lane] = ray.direction.x;
    direction_y[lane] = ray.direction.y;
    direction_z[lane] = ray.direction.z;
    t_min[lane] = ray.t_min;
    t_max[lane] = ray.t_max;
    origin_sphere[lane] = ray.origin_sphere;
    const LaneMask bit = LaneMask(1) << lane;
    heads_into_origin_sphere = ray.heads_into_origin_sphere ? (heads_into_origin_sphere | bit)
                                                            : (heads_into_origin_sphere & ~bit);
  }

  Ray get(int lane) const {
    Ray ray;
    ray.origin = {origin_x[lane], origin_y[lane], origin_z[lane]};
    ray.direction = {direction_x[lane], direction_y[lane], direction_z[lane]};
    ray.t_min = t_min[lane];
    ray.t_max = t_max[lane];
    ray.origin_sphere = origin_sphere[lane];
    ray.heads_into_origin_sphere = (heads_into_origin_sphere >> lane) & 1u;
    return ray;
  }
};

/// A closest-hit answer per lane: the hit, or t = kInfinity and kNoSphere where there is none
/// (as every lane starts).
struct alignas(32) HitBatch {
  float t[RayBatch::kWidth];
  std::uint32_t sphere[RayBatch::kWidth];

  HitBatch() {
    std::fill(std::begin(t), std::end(t), kInfinity);
    std::fill(std::begin(sphere), std::end(sphere), kNoSphere);
  }

  SphereHit get(int lane) const { return {t[lane], sphere[lane]}; }
  void set(int lane, const SphereHit& hit) {
    t[lane] = hit.t;
    sphere[lane] = hit.sphere;
  }
};

/// Whether the directions of the rays of `mask` lie in one octant, a cheap test of coherence
/// (the rays of a pixel block, shadow rays towards a distant light); true for one ray.
inline bool same_octant(const RayBatch& rays, LaneMask mask) {
  const float* const columns[3] = {rays.direction_x, rays.direction_y, rays.direction_z};
  for (const float* column : columns) {
    LaneMask negative = 0;
    for (int lane = 0; lane < RayBatch::kWidth; ++lane)
      negative |= LaneMask(std::signbit(column[lane])) << lane;
    negative &= mask;
    if (negative != 0 && negative != mask) return false;
  }
  return true;
}

/// Calls visit(lane) for each lane of `mask`, lowest first.
template <typename Visit>
void for_each_lane(LaneMask mask, Visit&& visit) {
  for (; mask != 0; mask &= mask - 1)
    visit(std::countr_zero(mask));
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
