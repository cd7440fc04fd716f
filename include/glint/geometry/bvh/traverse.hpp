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
#include "glint/geometry/simd.hpp"
#include "glint/instruction_set.hpp"

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

/// Axis-aligned boxes, one per lane of L's registers (geometry/simd.hpp).
template <class L>
struct BoxLanes {
  typename L::F lower_x, lower_y, lower_z, upper_x, upper_y, upper_z;
};

/// A ray's origin and the reciprocals of its direction's components, per lane.
template <class L>
struct SlabRayLanes {
  typename L::F ox, oy, oz, inverse_x, inverse_y, inverse_z;
};

template <class L>
struct SlabInterval {
  typename L::F near, far;
};

/// The slab test, lane by lane: the interval of t in which the lane's ray is inside the lane's
/// box, clipped to [t_min, t_max]; the ray enters the box where near <= far (NaN: not). Written
/// once for one ray and one box (Lanes1), one ray and the eight boxes of a node, and eight rays
/// and one box.
template <class L>
inline SlabInterval<L> slab_interval(const SlabRayLanes<L>& ray, const BoxLanes<L>& box,
                                     typename L::F t_min, typename L::F t_max) {
  using F = typename L::F;
  const F ax = L::mul(L::sub(box.lower_x, ray.ox), ray.inverse_x);
  const F bx = L::mul(L::sub(box.upper_x, ray.ox), ray.inverse_x);
  const F ay = L::mul(L::sub(box.lower_y, ray.oy), ray.inverse_y);
  const F by = L::mul(L::sub(box.upper_y, ray.oy), ray.inverse_y);
  const F az = L::mul(L::sub(box.lower_z, ray.oz), ray.inverse_z);
  const F bz = L::mul(L::sub(box.upper_z, ray.oz), ray.inverse_z);
  return {L::max(L::max(L::min(ax, bx), L::min(ay, by)), L::max(L::min(az, bz), t_min)),
          L::min(L::min(L::max(ax, bx), L::max(ay, by)), L::min(L::max(az, bz), t_max))};
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
  using L = avx2::Lanes8;
  const SlabRayLanes<L> ray{L::splat(origin.x),
                            L::splat(origin.y),
                            L::splat(origin.z),
                            L::splat(inverse_direction.x),
                            L::splat(inverse_direction.y),
                            L::splat(inverse_direction.z)};
  const BoxLanes<L> boxes{L::load(node.lower_x), L::load(node.lower_y), L::load(node.lower_z),
                          L::load(node.upper_x), L::load(node.upper_y), L::load(node.upper_z)};
  const SlabInterval<L> inside = slab_interval(ray, boxes, L::splat(t_min), L::splat(t_max));
  _mm256_storeu_ps(enter, inside.near);
  entered = L::bits(L::less_equal(inside.near, inside.far));
  const __m256i child = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.child));
  const __m256i count = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.count));
  empty = unsigned(
      _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(child, _mm256_set1_epi32(-1)))));
  leaves = unsigned(
      _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(count, _mm256_setzero_si256()))));
#else
  const SlabRayLanes<Lanes1> ray{
      origin.x, origin.y, origin.z, inverse_direction.x, inverse_direction.y, inverse_direction.z};
  for (int c = 0; c < kWideWidth; ++c) {
    const BoxLanes<Lanes1> box{node.lower_x[c], node.lower_y[c], node.lower_z[c],
                               node.upper_x[c], node.upper_y[c], node.upper_z[c]};
    const SlabInterval<Lanes1> inside = slab_interval(ray, box, t_min, t_max);
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
  const __m256 in_mask = _mm256_castsi256_ps(avx2::lane_vector(mask));
  const __m256 entries =
      _mm256_blendv_ps(_mm256_set1_ps(kInfinity), _mm256_loadu_ps(enter), in_mask);
  __m256 smallest = _mm256_min_ps(entries, _mm256_permute_ps(entries, 0b10110001));
  smallest = _mm256_min_ps(smallest, _mm256_permute_ps(smallest, 0b01001110));
  smallest = _mm256_min_ps(smallest, _mm256_permute2f128_ps(smallest, smallest, 1));
  const unsigned at =
      unsigned(_mm256_movemask_ps(_mm256_cmp_ps(entries, smallest, _CMP_EQ_OQ))) & mask;
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
/// Always inlined, for speed: left to itself GCC keeps it out of line, and a render of random
/// spheres then takes more instructions per ray (callgrind). The images are the same either way.
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
