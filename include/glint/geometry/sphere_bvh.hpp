#pragma once
// A bounding volume hierarchy over spheres, for scenes too large for a linear SIMD scan: a
// binary tree built with a binned surface area heuristic (bvh/build.hpp), collapsed into a
// wide tree for traversal (bvh/wide.hpp, bvh/traverse.hpp), whose leaves are tested by the
// leaf kernel that SphereSet uses too (sphere_kernel.hpp).

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vector_relational.hpp>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/bvh/build.hpp"
#include "glint/geometry/bvh/traverse.hpp"
#include "glint/geometry/bvh/wide.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/sphere_kernel.hpp"

namespace glint {

class SphereBvh {
 public:
  using Input = bvh::SphereInput;

  SphereBvh() = default;
  /// Built on up to `cores` cores (0: all there are), into the same tree whatever their number.
  explicit SphereBvh(std::vector<Input> spheres, std::size_t cores = 0)
      : tree_(bvh::build_binary_tree(spheres, cores)), wide_(bvh::collapse_to_wide(tree_.nodes)) {}

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
  /// The leaf spheres as the leaf kernel reads them.
  struct LeafSpheres {
    const bvh::LeafSphere* spheres;
    Vec3 center(std::size_t i) const { return spheres[i].center; }
    float radius_squared(std::size_t i) const { return spheres[i].radius * spheres[i].radius; }
    std::uint32_t id(std::size_t i) const { return spheres[i].id; }
  };

  template <bool kAnyHit>
  bool traverse(const Ray& ray, SphereHit& best) const {
    const LeafSpheres leaves{tree_.spheres.data()};
    return bvh::traverse<kAnyHit>(
        wide_, ray, best, [&](std::uint32_t first, std::uint32_t count, SphereHit& leaf_best) {
          return test_spheres(ray, leaves, first, first + count, leaf_best, kAnyHit);
        });
  }

  bvh::BinaryTree tree_;             // building and box queries
  std::vector<bvh::WideNode> wide_;  // ray traversal
};

static_assert(SphereAccelerator<SphereBvh>);

}  // namespace glint
