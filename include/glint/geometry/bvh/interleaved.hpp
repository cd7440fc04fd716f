#pragma once
// Interleaved traversal of the wide tree: the single-ray traversal of traverse.hpp for each of
// up to eight rays, taken one node at a time in turn, so that the memory loads of the rays
// overlap. Incoherent rays in a tree larger than the caches wait on memory for most of their
// time: each node a ray visits is a load that the next step depends on. Here, when a ray has
// chosen its next node (or the leaves of its node), it prefetches them and yields to the next
// ray; by the time its turn comes again they have arrived, while the other rays did their
// work.
//
// Each ray visits the nodes and leaves that traverse visits, in the same order, with the same
// pruning, so its answer is traverse's, bit for bit.
//
// A packet (packet.hpp) shares node visits between rays that go the same way; this shares
// nothing. SphereBvh uses it for batches of incoherent rays (RayCoherence::incoherent).

#include <bit>
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

namespace glint::inline GLINT_ISA_NAMESPACE::bvh {

/// Asks for the cache lines of `object`, to be read soon.
template <class T>
inline void prefetch(const T* object) {
  constexpr std::size_t kLine = 64;
  const char* bytes = reinterpret_cast<const char*>(object);
  for (std::size_t offset = 0; offset < sizeof(T); offset += kLine)
    __builtin_prefetch(bytes + offset);
  // An object not aligned to a line may reach one line further.
  if constexpr (alignof(T) % kLine != 0) __builtin_prefetch(bytes + sizeof(T) - 1);
}

/// Prefetches the spheres [first, first + count) of the tree's leaf spheres.
template <class F>
concept LeafPrefetch = requires(F& prefetch_leaf, std::uint32_t first, std::uint32_t count) {
  prefetch_leaf(first, count);
};

namespace detail {

/// One ray's traversal, stopped between two steps.
struct SuspendedTraversal {
  Vec3 origin;
  Vec3 inverse_direction;
  float t_min = 0.0f;
  SphereHit nearest;
  std::uint32_t node = 0;  ///< the node to visit, or whose leaves to test next
  bool testing_leaves = false;
  unsigned leaves = 0, inner = 0;  ///< of `node`, once visited
  int top = 0;
  alignas(32) float enter[kWideWidth];
  TraversalStack stack;
};

}  // namespace detail

/// traverse<kAnyHit> for each ray of `active`, interleaved (see the header comment): lane
/// `lane` traverses for rays[lane] from best[lane] (see hit_to_beat), calling
/// test_leaf(lane, first, count, best) where traverse would call its leaf test, and
/// prefetch_leaf(first, count) for the leaves it is about to test. Returns the lanes for which
/// a leaf test found a hit; best[lane] then holds it.
template <bool kAnyHit, LaneLeafTest TestLeaf, LeafPrefetch PrefetchLeaf>
inline LaneMask traverse_interleaved(const std::vector<WideNode>& nodes,
                                     const Ray (&rays)[RayBatch::kWidth], LaneMask active,
                                     SphereHit (&best)[RayBatch::kWidth], TestLeaf&& test_leaf,
                                     PrefetchLeaf&& prefetch_leaf) {
  if (nodes.empty() || active == 0) return 0;
  detail::SuspendedTraversal lanes[RayBatch::kWidth];
  for_each_lane(active, [&](int lane) {
    detail::SuspendedTraversal& s = lanes[lane];
    s.origin = rays[lane].origin;
    s.inverse_direction = 1.0f / rays[lane].direction;
    s.t_min = rays[lane].t_min;
    s.nearest = best[lane];
  });
  LaneMask live = active;
  LaneMask found = 0;
  // Ends lane's traversal.
  const auto finish = [&](int lane) {
    best[lane] = lanes[lane].nearest;
    live &= ~(LaneMask(1) << lane);
  };
  // Moves lane on to node `next`, to be visited on its next turn.
  const auto go_to = [&](detail::SuspendedTraversal& s, std::uint32_t next) {
    s.node = next;
    s.testing_leaves = false;
    prefetch(&nodes[next]);
  };
  while (live != 0) {
    for (LaneMask turn = live; turn != 0; turn &= turn - 1) {
      const int lane = std::countr_zero(turn);
      detail::SuspendedTraversal& s = lanes[lane];
      const WideNode& node = nodes[s.node];
      if (!s.testing_leaves) {
        const EnteredSlots entered =
            enter_boxes(node, s.origin, s.inverse_direction, s.t_min, s.nearest.t, s.enter);
        s.leaves = entered.leaves;
        s.inner = entered.inner;
        if (s.leaves != 0) {
          for (unsigned leaves = s.leaves; leaves != 0; leaves &= leaves - 1) {
            const int c = std::countr_zero(leaves);
            prefetch_leaf(node.child[c], node.count[c]);
          }
          s.testing_leaves = true;
          continue;
        }
      }
      const auto test_lane_leaf = [&](std::uint32_t first, std::uint32_t count, SphereHit& b) {
        return test_leaf(lane, first, count, b);
      };
      if (test_leaves_nearest_first<kAnyHit>(node, s.enter, s.leaves, s.nearest, test_lane_leaf)) {
        found |= LaneMask(1) << lane;
        if constexpr (kAnyHit) {
          finish(lane);
          continue;
        }
      }
      std::uint32_t next;
      if (next_node(node, s.enter, s.inner, s.nearest.t, s.stack, s.top, next))
        go_to(s, next);
      else
        finish(lane);
    }
  }
  return found;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::bvh
