#pragma once
// A bounding volume hierarchy over spheres, for scenes too large for a linear SIMD scan: a
// binary tree built with a binned surface area heuristic (bvh/build.hpp), collapsed into a
// wide tree for traversal (bvh/wide.hpp, bvh/traverse.hpp), whose leaves are tested by the
// leaf kernel that SphereSet uses too (sphere_kernel.hpp). The leaves' spheres are stored in
// groups of eight (bvh/leaf_groups.hpp): a single ray culls a group with one AVX2 pass and
// runs test_sphere on the few spheres left, so its hits are test_sphere's, bit for bit.

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vector_relational.hpp>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/bvh/build.hpp"
#include "glint/geometry/bvh/interleaved.hpp"
#include "glint/geometry/bvh/leaf_groups.hpp"
#include "glint/geometry/bvh/packet.hpp"
#include "glint/geometry/bvh/traverse.hpp"
#include "glint/geometry/bvh/wide.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_batch.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class SphereBvh {
 public:
  using Input = bvh::SphereInput;

  SphereBvh() = default;
  /// Built on up to `cores` cores (0: all there are), into the same tree whatever their number.
  explicit SphereBvh(std::vector<Input> spheres, std::size_t cores = 0)
      : tree_(bvh::build_binary_tree(std::move(spheres), cores)),
        wide_(bvh::collapse_to_wide(tree_.nodes)),
        leaves_(bvh::group_leaves(wide_, tree_.spheres)),
        interleave_(traversal_bytes() > kInterleavedTraversalBytes) {}

  /// The memory that ray traversal reads: the wide nodes and the leaves' sphere groups.
  std::size_t traversal_bytes() const {
    return wide_.size() * sizeof(bvh::WideNode) + leaves_.size() * sizeof(SphereGroup);
  }

  /// From this size of traversal_bytes() on, closest_hits and any_hits interleave the
  /// traversals of batches of incoherent rays (RayCoherence::incoherent, bvh/interleaved.hpp),
  /// which pays when their nodes come from beyond the core's own caches. On 2-vCPU AMD EPYC
  /// Zen 5 (1 MiB L2), for random rays (glint-embree-compare, and a lattice of spheres of 0.1
  /// to 6.4 MB) it is 0.86-0.93x one traversal per lane at 0.4-0.8 MB, 1.2x at 4 MB, 1.3-2.1x
  /// at 2.5-38 MB. A renderer's batches are another matter: in the million-sphere scene
  /// (38 MB), the wavefront renderer was 5-10% slower with its bounce rays interleaved, since
  /// neighbouring paths keep the nodes they need in the caches; hence the hint.
  static constexpr std::size_t kInterleavedTraversalBytes = std::size_t(1) << 20;

  std::size_t size() const { return tree_.spheres.size(); }
  bool empty() const { return tree_.spheres.empty(); }
  std::size_t node_count() const { return tree_.nodes.size(); }
  std::size_t wide_node_count() const { return wide_.size(); }

  /// See SphereAccelerator.
  bool closest_hit(const Ray& ray, SphereHit& hit) const {
    SphereHit best = hit_to_beat(ray, hit);
    if (!traverse<false>(ray, best)) return false;
    hit = best;
    return true;
  }

  /// See SphereAccelerator.
  bool any_hit(const Ray& ray) const {
    SphereHit best = hit_to_beat(ray, SphereHit{});
    return traverse<true>(ray, best);
  }

  /// closest_hit for each ray of `active`, hits[lane] playing `hit`; returns the lanes for
  /// which it found a hit. Exactly closest_hit's answer lane by lane: for incoherent rays in a
  /// tree larger than kInterleavedTraversalBytes, the lanes' traversals interleaved; else a
  /// packet traversal for batches whose rays share an octant (same_octant), one traversal per
  /// lane for the others. On 2-vCPU AMD EPYC Zen 5 (glint-features-bench BM_BvhBatch, 10^4
  /// and 10^5 spheres) the packet is 1.9-2.3x as fast as eight traversals for 4x2 blocks of
  /// camera rays (2.5-2.7x for occlusion), but 0.56-0.57x for random rays (0.9-1.04x): random
  /// batches of eight almost never share an octant, camera blocks almost always do.
  LaneMask closest_hits(const RayBatch& rays, LaneMask active, SphereHit (&hits)[RayBatch::kWidth],
                        RayCoherence coherence = RayCoherence::unknown) const {
    if (coherence == RayCoherence::incoherent && interleave_)
      return closest_hits_interleaved(rays, active, hits);
#ifdef GLINT_AVX2
    if (same_octant(rays, active)) return closest_hits_packet(rays, active, hits);
#endif
    return closest_hits_per_lane(rays, active, hits);
  }

  /// any_hit for each ray of `active`: the lanes whose ray is blocked.
  LaneMask any_hits(const RayBatch& rays, LaneMask active,
                    RayCoherence coherence = RayCoherence::unknown) const {
    if (coherence == RayCoherence::incoherent && interleave_)
      return any_hits_interleaved(rays, active);
#ifdef GLINT_AVX2
    if (same_octant(rays, active)) return any_hits_packet(rays, active);
#endif
    return any_hits_per_lane(rays, active);
  }

  /// closest_hits and any_hits with one single-ray traversal per lane.
  LaneMask closest_hits_per_lane(const RayBatch& rays, LaneMask active,
                                 SphereHit (&hits)[RayBatch::kWidth]) const {
    LaneMask found = 0;
    for_each_lane(active, [&](int lane) {
      if (closest_hit(rays.get(lane), hits[lane])) found |= LaneMask(1) << lane;
    });
    return found;
  }
  LaneMask any_hits_per_lane(const RayBatch& rays, LaneMask active) const {
    LaneMask blocked = 0;
    for_each_lane(active, [&](int lane) {
      if (any_hit(rays.get(lane))) blocked |= LaneMask(1) << lane;
    });
    return blocked;
  }

  /// closest_hits and any_hits with the lanes' single-ray traversals interleaved
  /// (bvh/interleaved.hpp).
  LaneMask closest_hits_interleaved(const RayBatch& rays, LaneMask active,
                                    SphereHit (&hits)[RayBatch::kWidth]) const {
    LaneStart start(rays, active, hits);
    return start.finish(traverse_interleaved<false>(start.rays, active, start.best), hits);
  }
  LaneMask any_hits_interleaved(const RayBatch& rays, LaneMask active) const {
    LaneStart start(rays, active);
    return traverse_interleaved<true>(start.rays, active, start.best);
  }

#ifdef GLINT_AVX2
  /// closest_hits and any_hits with one packet traversal (bvh/packet.hpp) for all lanes.
  LaneMask closest_hits_packet(const RayBatch& rays, LaneMask active,
                               SphereHit (&hits)[RayBatch::kWidth]) const {
    LaneStart start(rays, active, hits);
    return start.finish(traverse_packet<false>(rays, active, start.rays, start.best), hits);
  }
  LaneMask any_hits_packet(const RayBatch& rays, LaneMask active) const {
    LaneStart start(rays, active);
    return traverse_packet<true>(rays, active, start.rays, start.best);
  }
#endif

  /// Calls visit(id) for every sphere whose bounding box overlaps the box [lower, upper]
  /// (a superset of the spheres that overlap it). For scene building, not for rendering.
  /// `pending` is scratch space: passing the same vector to every query of a loop saves an
  /// allocation per query.
  template <typename Visit>
  void for_each_near_box(const Vec3& lower, const Vec3& upper, Visit&& visit,
                         std::vector<std::uint32_t>& pending) const {
    const std::vector<bvh::Node>& nodes = tree_.nodes;
    if (nodes.empty()) return;
    pending.assign(1, 0);
    while (!pending.empty()) {
      const std::uint32_t index = pending.back();
      const bvh::Node& node = nodes[index];
      pending.pop_back();
      if (glm::any(glm::lessThan(node.upper, lower)) ||
          glm::any(glm::greaterThan(node.lower, upper)))
        continue;
      if (node.count == 0) {
        pending.push_back(index + 1);
        pending.push_back(node.offset);
        continue;
      }
      for (std::uint32_t i = node.offset; i < node.offset + node.count; ++i) {
        const bvh::LeafSphere& s = tree_.spheres[i];
        const Vec3 r(s.radius);
        if (glm::all(glm::lessThanEqual(s.center - r, upper)) &&
            glm::all(glm::greaterThanEqual(s.center + r, lower)))
          visit(s.id);
      }
    }
  }

 private:
  /// The rays of a batch's active lanes and the hits they have to beat (hit_to_beat), as the
  /// batched traversals take them.
  struct LaneStart {
    Ray rays[RayBatch::kWidth];
    SphereHit best[RayBatch::kWidth];

    /// For any_hits: no hit to beat but the rays' t_max.
    LaneStart(const RayBatch& batch, LaneMask active) {
      for_each_lane(active, [&](int lane) {
        rays[lane] = batch.get(lane);
        best[lane] = hit_to_beat(rays[lane], SphereHit{});
      });
    }
    /// For closest_hits: the caller's hits to beat.
    LaneStart(const RayBatch& batch, LaneMask active, const SphereHit (&hits)[RayBatch::kWidth]) {
      for_each_lane(active, [&](int lane) {
        rays[lane] = batch.get(lane);
        best[lane] = hit_to_beat(rays[lane], hits[lane]);
      });
    }
    /// Stores the hits of the lanes of `found` in `hits`; returns `found`.
    LaneMask finish(LaneMask found, SphereHit (&hits)[RayBatch::kWidth]) const {
      for_each_lane(found, [&](int lane) { hits[lane] = best[lane]; });
      return found;
    }
  };

  // Out of line: inlined into the batched queries, it crowds the registers of their linear
  // scans, which small scenes spend their time in.
  template <bool kAnyHit>
  [[gnu::noinline]] bool traverse(const Ray& ray, SphereHit& best) const {
    const SphereGroup* groups = leaves_.data();
    const GroupRay group_ray(ray);
    return bvh::traverse<kAnyHit>(
        wide_, ray, best, [&](std::uint32_t first, std::uint32_t count, SphereHit& leaf_best) {
          return test_grouped_spheres(group_ray, groups, first, count, leaf_best, kAnyHit);
        });
  }

  template <bool kAnyHit>
  LaneMask traverse_interleaved(const Ray (&lane_rays)[RayBatch::kWidth], LaneMask active,
                                SphereHit (&best)[RayBatch::kWidth]) const {
    const SphereGroup* groups = leaves_.data();
    const auto group_rays = per_lane<GroupRay>(lane_rays);
    return bvh::traverse_interleaved<kAnyHit>(
        wide_, lane_rays, active, best,
        [&](int lane, std::uint32_t first, std::uint32_t count, SphereHit& leaf_best) {
          return test_grouped_spheres(group_rays[lane], groups, first, count, leaf_best, kAnyHit);
        },
        [&](std::uint32_t first, std::uint32_t count) {
          const SphereGroup* group = groups + first / SphereGroup::kSize;
          for (std::uint32_t i = 0; i < count; i += SphereGroup::kSize)
            bvh::prefetch(group++);
        });
  }

#ifdef GLINT_AVX2
  template <bool kAnyHit>
  LaneMask traverse_packet(const RayBatch& rays, LaneMask active,
                           const Ray (&lane_rays)[RayBatch::kWidth],
                           SphereHit (&best)[RayBatch::kWidth]) const {
    const GroupedSpheres leaves{leaves_.data()};
    const auto lane_kernel_rays = per_lane<RayLane>(lane_rays);
    return bvh::traverse_packet<kAnyHit>(
        wide_, rays, active, best,
        [&](int lane, std::uint32_t first, std::uint32_t count, SphereHit& leaf_best) {
          return test_spheres(lane_kernel_rays[lane], leaves, first, first + count, leaf_best,
                              kAnyHit);
        });
  }
#endif

  /// What the leaf kernel reads of each lane's ray (a RayLane or a GroupRay), made once per
  /// traversal rather than at every leaf the lane enters.
  template <class KernelRay>
  static std::array<KernelRay, RayBatch::kWidth> per_lane(
      const Ray (&lane_rays)[RayBatch::kWidth]) {
    return [&]<std::size_t... lane>(std::index_sequence<lane...>) {
      return std::array<KernelRay, RayBatch::kWidth>{KernelRay(lane_rays[lane])...};
    }
    (std::make_index_sequence<RayBatch::kWidth>{});
  }

  bvh::BinaryTree tree_;             // building and box queries
  std::vector<bvh::WideNode> wide_;  // ray traversal
  std::vector<SphereGroup> leaves_;  // the wide tree's leaves (bvh/leaf_groups.hpp)
  bool interleave_ = false;          // see kInterleavedTraversalBytes
};

static_assert(SphereAccelerator<SphereBvh>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
