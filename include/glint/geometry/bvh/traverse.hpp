#pragma once
// Closest-hit and any-hit traversal of the wide tree. It knows boxes only: the spheres of a
// leaf are tested by the caller's leaf function. Leaves are tested nearest first as soon as
// their node is reached, so that their hits prune the inner children; the nearest inner child
// is visited next, and a subtree whose box starts beyond the best hit is skipped.

#include <array>
#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/bvh/build.hpp"
#include "glint/geometry/bvh/wide.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/wide.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::bvh {

/// Tests spheres [first, first + count) of the tree's leaf spheres against the ray, updating
/// `best` (see test_spheres); returns whether it did.
template <class F>
concept LeafTest = requires(F& test_leaf, std::uint32_t first, std::uint32_t count,
                            SphereHit& best) {
  { test_leaf(first, count, best) } -> std::same_as<bool>;
};

/// LeafTest for the ray of lane `lane` of a batch.
template <class F>
concept LaneLeafTest = requires(F& test_leaf, int lane, std::uint32_t first, std::uint32_t count,
                                SphereHit& best) {
  { test_leaf(lane, first, count, best) } -> std::same_as<bool>;
};

/// Axis-aligned boxes, one per lane (math/wide.hpp's numbers).
template <FloatType F>
struct BoxLanes {
  F lower_x, lower_y, lower_z, upper_x, upper_y, upper_z;
};

/// A ray's origin and the reciprocals of its direction's components, per lane.
template <FloatType F>
struct SlabRayLanes {
  F ox, oy, oz, inverse_x, inverse_y, inverse_z;
};

template <FloatType F>
struct SlabInterval {
  F near, far;
};

/// The slab test, lane by lane: the interval of t in which the lane's ray is inside the lane's
/// box, clipped to [t_min, t_max]; the ray enters the box where near <= far (NaN: not). Written
/// once for one ray and one box (float), one ray and the eight boxes of a node, and eight rays
/// and one box (Float<8>). The order of each min's and max's operands decides which one a NaN
/// gives way to (math/wide.hpp: the first operand where either is NaN).
template <FloatType F>
inline SlabInterval<F> slab_interval(const SlabRayLanes<F>& ray, const BoxLanes<F>& box, F t_min,
                                     F t_max) {
  const F ax = (box.lower_x - ray.ox) * ray.inverse_x;
  const F bx = (box.upper_x - ray.ox) * ray.inverse_x;
  const F ay = (box.lower_y - ray.oy) * ray.inverse_y;
  const F by = (box.upper_y - ray.oy) * ray.inverse_y;
  const F az = (box.lower_z - ray.oz) * ray.inverse_z;
  const F bz = (box.upper_z - ray.oz) * ray.inverse_z;
  return {max(max(t_min, min(bz, az)), max(min(by, ay), min(bx, ax))),
          min(min(t_max, max(bz, az)), min(max(by, ay), max(bx, ax)))};
}

/// The slots of a wide node that a ray enters (bit c for slot c), split by kind.
struct EnteredSlots {
  unsigned leaves = 0;
  unsigned inner = 0;
};

/// Entry distances into a wide node's boxes, and the non-empty slots whose box the ray enters
/// within [t_min, t_max]; enter[c] is meaningful for those slots only.
inline EnteredSlots enter_boxes(const WideNode& node, const Vec3& origin,
                                const Vec3& inverse_direction, float t_min, float t_max,
                                float (&enter)[kWideWidth]) {
  static_assert(kWideWidth == 8);
  unsigned entered = 0, empty = 0, leaves = 0;
#if defined(GLINT_AVX2)
  using F = Float<kWideWidth>;
  const SlabRayLanes<F> ray{splat<F>(origin.x),
                            splat<F>(origin.y),
                            splat<F>(origin.z),
                            splat<F>(inverse_direction.x),
                            splat<F>(inverse_direction.y),
                            splat<F>(inverse_direction.z)};
  const BoxLanes<F> boxes{load<F>(node.lower_x), load<F>(node.lower_y), load<F>(node.lower_z),
                          load<F>(node.upper_x), load<F>(node.upper_y), load<F>(node.upper_z)};
  const SlabInterval<F> inside = slab_interval(ray, boxes, splat<F>(t_min), splat<F>(t_max));
  store(enter, inside.near);
  entered = bits_of_mask(inside.near <= inside.far);
  using I = Int<kWideWidth>;
  empty = bits_of_mask(load<I>(node.child) == -1);
  leaves = bits_of_mask(load<I>(node.count) > 0);
#else
  const SlabRayLanes<float> ray{
      origin.x, origin.y, origin.z, inverse_direction.x, inverse_direction.y, inverse_direction.z};
  for (int c = 0; c < kWideWidth; ++c) {
    const BoxLanes<float> box{node.lower_x[c], node.lower_y[c], node.lower_z[c],
                              node.upper_x[c], node.upper_y[c], node.upper_z[c]};
    const SlabInterval<float> inside = slab_interval(ray, box, t_min, t_max);
    enter[c] = inside.near;
    entered |= unsigned(inside.near <= inside.far) << c;
    empty |= unsigned(node.child[c] == kEmptySlot) << c;
    leaves |= unsigned(node.count[c] > 0) << c;
  }
#endif
  entered &= ~empty;
  return {entered & leaves, entered & ~leaves};
}

/// The slot of `mask` (not empty) whose box the ray enters first, the lowest slot of those at
/// equal entries. Taking the leaves one at a time this way stops as soon as the next one
/// starts beyond the best hit, without sorting the others; with AVX2 it is a branch-free
/// minimum over the node's entries.
inline int nearest_slot(const float (&enter)[kWideWidth], unsigned mask) {
  if ((mask & (mask - 1)) == 0) return std::countr_zero(mask);
#if defined(GLINT_AVX2)
  using F = Float<kWideWidth>;
  const F entries =
      select(mask_of_bits<Mask<kWideWidth>>(mask), load<F>(enter), splat<F>(kInfinity));
  const unsigned at = bits_of_mask(entries == min_across_lanes(entries)) & mask;
  return std::countr_zero(at != 0 ? at : mask);
#else
  int nearest = std::countr_zero(mask);
  for (unsigned rest = mask & (mask - 1); rest != 0; rest &= rest - 1) {
    const int c = std::countr_zero(rest);
    if (enter[c] < enter[nearest]) nearest = c;
  }
  return nearest;
#endif
}

/// A node a traversal has still to visit, and where the ray enters its box.
struct PendingNode {
  std::uint32_t node;
  float enter;
};

/// The nodes a traversal has still to visit: each level pushes at most kWideWidth - 1 more
/// than it pops, and the depth is bounded.
using TraversalStack = std::array<PendingNode, (kWideWidth - 1) * (kMaxDepth + 2)>;

/// Tests the leaves `leaves` of `node` nearest first with test_leaf(first, count, nearest),
/// until one starts beyond the best hit; returns whether one found a hit. With kAnyHit it stops
/// at the first.
template <bool kAnyHit, LeafTest TestLeaf>
[[gnu::always_inline]] inline bool test_leaves_nearest_first(const WideNode& node,
                                                             const float (&enter)[kWideWidth],
                                                             unsigned leaves, SphereHit& nearest,
                                                             TestLeaf& test_leaf) {
  bool found = false;
  while (leaves != 0) {
    const int c = nearest_slot(enter, leaves);
    leaves &= ~(1u << c);
    if (enter[c] > nearest.t) break;  // and so are the farther ones
    if (!test_leaf(node.child[c], node.count[c], nearest)) continue;
    found = true;
    if constexpr (kAnyHit) break;
  }
  return found;
}

/// The node to visit after `node`'s leaves, into `next`: the nearest of the inner children
/// `inner` if the ray enters it before its best hit at `nearest_t`, without going through the
/// stack (the others so entered are pushed in slot order, unsorted: once a leaf has given a hit
/// most of them are skipped when popped whatever their order, and sorting them by entry cost
/// 14% of the instructions per ray on a lattice of spheres, callgrind, for no fewer nodes
/// visited on random scenes); else the next node on the stack entered before it. Returns false
/// when there is none: the traversal is over.
[[gnu::always_inline]] inline bool next_node(const WideNode& node, const float (&enter)[kWideWidth],
                                             unsigned inner, float nearest_t, TraversalStack& stack,
                                             int& top, std::uint32_t& next) {
  if (inner != 0 && (inner & (inner - 1)) == 0) {  // one inner child: no stack
    const int c = std::countr_zero(inner);
    if (enter[c] <= nearest_t) {
      next = node.child[c];
      return true;
    }
  } else if (inner != 0) {
    const int first = nearest_slot(enter, inner);
    if (enter[first] <= nearest_t) {
      for (unsigned rest = inner & ~(1u << first); rest != 0; rest &= rest - 1) {
        const int c = std::countr_zero(rest);
        stack[std::size_t(top)] = PendingNode{node.child[c], enter[c]};
        top += enter[c] <= nearest_t;
      }
      next = node.child[first];
      return true;
    }
  }
  while (top > 0) {
    const PendingNode pending = stack[std::size_t(--top)];
    if (pending.enter <= nearest_t) {
      next = pending.node;
      return true;
    }
  }
  return false;
}

/// Traverses `nodes` (see collapse_to_wide), calling `test_leaf` for the leaves the ray may
/// reach before `best`; returns whether any call found a hit. With kAnyHit it returns at the
/// first such hit. The next node is next_node's.
///
/// Always inlined, for speed: left to itself GCC keeps it out of line, and a render of 300
/// random spheres took 7.5% more instructions at --simd avx2 and 3.3% more at scalar
/// (callgrind, glint-render 64x64, 4 spp). The images are the same either way.
template <bool kAnyHit, LeafTest TestLeaf>
[[gnu::always_inline]] inline bool traverse(const std::vector<WideNode>& nodes, const Ray& ray,
                                            SphereHit& best, TestLeaf&& test_leaf) {
  if (nodes.empty()) return false;
  const Vec3 inverse_direction = 1.0f / ray.direction;
  // A local copy, which the compiler can keep in registers.
  SphereHit nearest = best;
  TraversalStack stack;
  int top = 0;
  std::uint32_t current = 0;
  bool found = false;
  for (;;) {
    const WideNode& node = nodes[current];
    alignas(32) float enter[kWideWidth];
    const EnteredSlots entered =
        enter_boxes(node, ray.origin, inverse_direction, ray.t_min, nearest.t, enter);
    if (test_leaves_nearest_first<kAnyHit>(node, enter, entered.leaves, nearest, test_leaf)) {
      found = true;
      if constexpr (kAnyHit) {
        best = nearest;
        return true;
      }
    }
    if (!next_node(node, enter, entered.inner, nearest.t, stack, top, current)) {
      best = nearest;
      return found;
    }
  }
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::bvh
