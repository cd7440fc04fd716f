#pragma once
// Packet traversal of the wide tree: the eight rays of a RayBatch down one stack, a node
// visited when any live lane's ray enters its box before that lane's best hit, each lane
// keeping its own bounds. Box tests are those of traverse.hpp with ray and box swapped (one
// box broadcast, a ray per lane); leaves are tested lane by lane by the caller's function, so
// that each lane gets the single-ray leaf test's answers. Like traverse, it visits leaves
// nearest first (by the nearest entry among
// the lanes) as soon as their node is reached, and skips a subtree that every lane enters
// beyond its best hit.
//
// A packet pays for the lanes that a node does not concern: for rays of one pixel block
// (camera rays, shadow rays towards one light) it shares node loads and box tests between the
// lanes; for incoherent rays it visits the union of eight traversals. SphereBvh decides which
// to use per batch (SphereBvh::closest_hits).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/bvh/build.hpp"
#include "glint/geometry/bvh/traverse.hpp"
#include "glint/geometry/bvh/wide.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/instruction_set.hpp"

#ifdef GLINT_AVX2
namespace glint::inline GLINT_ISA_NAMESPACE::bvh {

/// Traverses `nodes` for the lanes of `active`, each starting from the hit in `best` it has to
/// beat (see hit_to_beat; best[lane].t <= the ray's t_max) and calling `test_leaf` for the
/// leaves its ray may reach before it; returns the lanes for which a call found a hit. With
/// kAnyHit a lane stops at its first such hit.
template <bool kAnyHit, LaneLeafTest TestLeaf>
inline LaneMask traverse_packet(const std::vector<WideNode>& nodes, const RayBatch& rays,
                                LaneMask active, SphereHit (&best)[RayBatch::kWidth],
                                TestLeaf&& test_leaf) {
  static_assert(kWideWidth == 8 && RayBatch::kWidth == 8);
  if (nodes.empty() || active == 0) return 0;
  const __m256 ox = _mm256_load_ps(rays.origin_x), oy = _mm256_load_ps(rays.origin_y),
               oz = _mm256_load_ps(rays.origin_z);
  // 1.0f / direction, as the single-ray traversal computes it.
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 ix = _mm256_div_ps(one, _mm256_load_ps(rays.direction_x)),
               iy = _mm256_div_ps(one, _mm256_load_ps(rays.direction_y)),
               iz = _mm256_div_ps(one, _mm256_load_ps(rays.direction_z));
  const SlabRayLanes<avx2::Lanes8> rays_inverse{ox, oy, oz, ix, iy, iz};
  const __m256 t_min = _mm256_load_ps(rays.t_min);
  const __m256 infinity = _mm256_set1_ps(kInfinity);
  // Each lane's best t, the far bound of its box tests; lanes without a ray never enter.
  alignas(32) float nearest[RayBatch::kWidth];
  for (int lane = 0; lane < RayBatch::kWidth; ++lane)
    nearest[lane] = (active >> lane) & 1u ? best[lane].t : -kInfinity;
  __m256 nearest_t = _mm256_load_ps(nearest);
  LaneMask live = active;
  LaneMask found = 0;

  struct alignas(32) Pending {
    __m256 enter;  ///< per lane; +infinity in the lanes that do not enter the node
    std::uint32_t node;
  };
  // As in traverse: each level pushes at most kWideWidth - 1 more nodes than it pops.
  std::array<Pending, (kWideWidth - 1) * (kMaxDepth + 2)> stack;
  int top = 0;
  stack[std::size_t(top++)] =
      Pending{_mm256_blendv_ps(infinity, t_min, _mm256_castsi256_ps(avx2::lane_vector(active))), 0};
  while (top > 0) {
    const Pending pending = stack[std::size_t(--top)];
    const LaneMask lanes =
        LaneMask(_mm256_movemask_ps(_mm256_cmp_ps(pending.enter, nearest_t, _CMP_LE_OQ))) & live;
    if (lanes == 0) continue;
    const __m256 lane_ok = _mm256_castsi256_ps(avx2::lane_vector(lanes));
    const WideNode& node = nodes[pending.node];
    // The children some lane enters, with each lane's entry and the nearest entry among them.
    __m256 enter[kWideWidth];
    float order_key[kWideWidth];
    int order[kWideWidth];
    int count = 0;
    for (int c = 0; c < kWideWidth; ++c) {
      if (node.child[c] == kEmptySlot) continue;
      using L = avx2::Lanes8;
      const BoxLanes<L> box{L::splat(node.lower_x[c]), L::splat(node.lower_y[c]),
                            L::splat(node.lower_z[c]), L::splat(node.upper_x[c]),
                            L::splat(node.upper_y[c]), L::splat(node.upper_z[c])};
      const SlabInterval<L> inside = slab_interval(rays_inverse, box, t_min, nearest_t);
      const __m256 near = inside.near;
      const __m256 enters = _mm256_and_ps(L::less_equal(near, inside.far), lane_ok);
      if (_mm256_movemask_ps(enters) == 0) continue;
      const __m256 entry = _mm256_blendv_ps(infinity, near, enters);
      // The nearest entry among the lanes orders the children.
      __m256 smallest = _mm256_min_ps(entry, _mm256_permute_ps(entry, 0b10110001));
      smallest = _mm256_min_ps(smallest, _mm256_permute_ps(smallest, 0b01001110));
      smallest = _mm256_min_ps(smallest, _mm256_permute2f128_ps(smallest, smallest, 1));
      const float key = _mm256_cvtss_f32(smallest);
      int k = count++;
      while (k > 0 && order_key[k - 1] > key) {
        order_key[k] = order_key[k - 1];
        order[k] = order[k - 1];
        --k;
      }
      order_key[k] = key;
      order[k] = c;
      enter[c] = entry;
    }
    for (int k = 0; k < count; ++k) {
      const int c = order[k];
      if (node.count[c] == 0) continue;
      // The lanes that enter the leaf before their best hit (which earlier leaves may have
      // brought nearer), as the single-ray traversal checks.
      const LaneMask reach =
          LaneMask(_mm256_movemask_ps(_mm256_cmp_ps(enter[c], nearest_t, _CMP_LE_OQ))) & live;
      if (reach == 0) continue;
      LaneMask hit = 0;
      for_each_lane(reach, [&](int lane) {
        if (!test_leaf(lane, node.child[c], node.count[c], best[lane])) return;
        hit |= LaneMask(1) << lane;
        nearest[lane] = kAnyHit ? -kInfinity : best[lane].t;
      });
      if (hit == 0) continue;
      found |= hit;
      nearest_t = _mm256_load_ps(nearest);
      if constexpr (kAnyHit) {
        live &= ~hit;
        if (live == 0) return found;
      }
    }
    // Farthest pushed first, so that the nearest is popped next.
    for (int k = count - 1; k >= 0; --k) {
      const int c = order[k];
      if (node.count[c] == 0) stack[std::size_t(top++)] = Pending{enter[c], node.child[c]};
    }
  }
  return found;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::bvh
#endif
