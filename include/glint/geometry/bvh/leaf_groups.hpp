#pragma once
// The leaves of the wide tree as SphereGroups (sphere_kernel.hpp): each leaf's spheres moved
// into groups of their own, so that one AVX2 pass culls a group and the spheres a leaf test
// reads lie in two or three cache lines per eight spheres.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/geometry/bvh/build.hpp"
#include "glint/geometry/bvh/wide.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::bvh {

/// The leaf spheres of `wide` in SphereGroups, in the order of the leaves in `wide` (node by
/// node, slot by slot); each leaf slot's child becomes the index of its first sphere there (a
/// multiple of SphereGroup::kSize, see GroupedSpheres). `spheres`: the binary tree's leaf
/// spheres, which the slots index on entry.
inline std::vector<SphereGroup> group_leaves(std::vector<WideNode>& wide,
                                             const std::vector<LeafSphere>& spheres) {
  constexpr std::size_t kSize = SphereGroup::kSize;
  std::size_t group_count = 0;
  for (const WideNode& node : wide)
    for (int c = 0; c < kWideWidth; ++c)
      group_count += (node.count[c] + kSize - 1) / kSize;
  std::vector<SphereGroup> groups;
  groups.reserve(group_count);
  for (WideNode& node : wide)
    for (int c = 0; c < kWideWidth; ++c) {
      if (node.count[c] == 0) continue;
      const std::uint32_t first = node.child[c];
      node.child[c] = static_cast<std::uint32_t>(groups.size() * kSize);
      for (std::uint32_t i = 0; i < node.count[c]; ++i) {
        if (i % kSize == 0) {
          SphereGroup& padding = groups.emplace_back();
          for (std::size_t lane = 0; lane < kSize; ++lane) {
            padding.cx[lane] = padding.cy[lane] = padding.cz[lane] = 0.0f;
            padding.radius[lane] = 0.0f;
            padding.id[lane] = kNoSphere;
          }
        }
        const LeafSphere& s = spheres[first + i];
        SphereGroup& group = groups.back();
        const std::size_t lane = i % kSize;
        group.cx[lane] = s.center.x;
        group.cy[lane] = s.center.y;
        group.cz[lane] = s.center.z;
        group.radius[lane] = s.radius;
        group.id[lane] = s.id;
      }
    }
  return groups;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::bvh
