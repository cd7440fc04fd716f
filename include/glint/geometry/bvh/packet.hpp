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
#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"

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
  using F = Float<RayBatch::kWidth>;
  using M = Mask<RayBatch::kWidth>;
  if (nodes.empty() || active == 0) return 0;
  // 1.0f / direction, as the single-ray traversal computes it.
  const SlabRayLanes<F> rays_inverse{
      load<F>(rays.origin_x),           load<F>(rays.origin_y),
      load<F>(rays.origin_z),           1.0f / load<F>(rays.direction_x),
      1.0f / load<F>(rays.direction_y), 1.0f / load<F>(rays.direction_z)};
  const F t_min = load<F>(rays.t_min);
  const F infinity = splat<F>(kInfinity);
  // Each lane's best t, the far bound of its box tests; lanes without a ray never enter.
  float nearest[RayBatch::kWidth];
  for (int lane = 0; lane < RayBatch::kWidth; ++lane)
    nearest[lane] = (active >> lane) & 1u ? best[lane].t : -kInfinity;
  F nearest_t = load<F>(nearest);
  LaneMask live = active;
  LaneMask found = 0;

  struct Pending {
    F enter;  ///< per lane; +infinity in the lanes that do not enter the node
    std::uint32_t node;
  };
  // As in traverse: each level pushes at most kWideWidth - 1 more nodes than it pops.
  std::array<Pending, (kWideWidth - 1) * (kMaxDepth + 2)> stack;
  int top = 0;
  stack[std::size_t(top++)] = Pending{select(mask_of_bits<M>(active), t_min, infinity), 0};
  while (top > 0) {
    const Pending pending = stack[std::size_t(--top)];
    const LaneMask lanes = bits_of_mask(pending.enter <= nearest_t) & live;
    if (lanes == 0) continue;
    const M lane_ok = mask_of_bits<M>(lanes);
    const WideNode& node = nodes[pending.node];
    // The children some lane enters, with each lane's entry and the nearest entry among them.
    F enter[kWideWidth];
    float order_key[kWideWidth];
    int order[kWideWidth];
    int count = 0;
    for (int c = 0; c < kWideWidth; ++c) {
      if (node.child[c] == kEmptySlot) continue;
      const BoxLanes<F> box{splat<F>(node.lower_x[c]), splat<F>(node.lower_y[c]),
                            splat<F>(node.lower_z[c]), splat<F>(node.upper_x[c]),
                            splat<F>(node.upper_y[c]), splat<F>(node.upper_z[c])};
      const SlabInterval<F> inside = slab_interval(rays_inverse, box, t_min, nearest_t);
      const M enters = (inside.near <= inside.far) & lane_ok;
      if (!any(enters)) continue;
      const F entry = select(enters, inside.near, infinity);
      // The nearest entry among the lanes orders the children.
      const float key = min_across_lanes(entry)[0];
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
      const LaneMask reach = bits_of_mask(enter[c] <= nearest_t) & live;
      if (reach == 0) continue;
      LaneMask hit = 0;
      for_each_lane(reach, [&](int lane) {
        if (!test_leaf(lane, node.child[c], node.count[c], best[lane])) return;
        hit |= LaneMask(1) << lane;
        nearest[lane] = kAnyHit ? -kInfinity : best[lane].t;
      });
      if (hit == 0) continue;
      found |= hit;
      nearest_t = load<F>(nearest);
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
