#pragma once
// The report's inclusion precomputation: each transparent sphere learns the refractive index
// of the medium just outside it, i.e. the index of the smallest transparent sphere containing
// it, or the scene's medium if none does. It is well defined only if any two transparent
// spheres are disjoint or nested, so this is also where that rule is enforced.
//
// Opaque spheres have no inside medium and take no part: they may overlap anything.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "glint/scene/scene_description.hpp"
#include "glint/scene/scene_error.hpp"

namespace glint {

inline constexpr std::uint32_t kNoParent = 0xffffffffu;

enum class SphereRelation { disjoint, first_inside_second, second_inside_first, overlapping };

/// Exact classification in double precision. Touching spheres (externally or internally
/// tangent) count as disjoint or nested; coincident spheres as overlapping.
inline SphereRelation classify_spheres(const SphereDescription& a, const SphereDescription& b) {
  const double dx = double(a.center.x) - b.center.x;
  const double dy = double(a.center.y) - b.center.y;
  const double dz = double(a.center.z) - b.center.z;
  const double distance = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double ra = a.radius, rb = b.radius;
  if (distance >= ra + rb) return SphereRelation::disjoint;
  if (distance == 0.0 && ra == rb) return SphereRelation::overlapping;
  if (distance + ra <= rb) return SphereRelation::first_inside_second;
  if (distance + rb <= ra) return SphereRelation::second_inside_first;
  return SphereRelation::overlapping;
}

struct InclusionTree {
  /// For every sphere of the description: the innermost transparent sphere containing it
  /// (kNoParent if none). Opaque spheres get a parent too, which tells which medium they sit in.
  std::vector<std::uint32_t> parent;
  /// Refractive index just outside each sphere.
  std::vector<float> outside_ior;
};

/// Builds the tree; throws SceneError naming both lines if two transparent spheres partially
/// overlap. Candidate pairs come from a sweep over the spheres' x extents, so scenes of spread
/// out spheres cost about n log n rather than n^2.
inline InclusionTree build_inclusion_tree(const SceneDescription& scene) {
  const auto& spheres = scene.spheres;
  const std::size_t n = spheres.size();
  InclusionTree tree;
  tree.parent.assign(n, kNoParent);
  tree.outside_ior.assign(n, scene.medium_ior);

  std::vector<std::uint32_t> by_min_x(n);
  std::iota(by_min_x.begin(), by_min_x.end(), 0u);
  const auto min_x = [&](std::uint32_t i) { return double(spheres[i].center.x) - spheres[i].radius; };
  const auto max_x = [&](std::uint32_t i) { return double(spheres[i].center.x) + spheres[i].radius; };
  std::sort(by_min_x.begin(), by_min_x.end(), [&](std::uint32_t a, std::uint32_t b) {
    return min_x(a) < min_x(b) || (min_x(a) == min_x(b) && a < b);
  });

  // Offer `container` as the medium around `inner`; keep the smallest radius (containers of one
  // sphere are nested among themselves, so the smallest is the innermost). Ties go to the lower
  // index so the result does not depend on the sweep order.
  const auto offer = [&](std::uint32_t inner, std::uint32_t container) {
    std::uint32_t& current = tree.parent[inner];
    if (current == kNoParent || spheres[container].radius < spheres[current].radius ||
        (spheres[container].radius == spheres[current].radius && container < current))
      current = container;
  };

  std::vector<std::uint32_t> active;  // spheres whose x extent may still overlap later ones
  for (const std::uint32_t i : by_min_x) {
    const double start = min_x(i);
    std::erase_if(active, [&](std::uint32_t j) { return max_x(j) < start; });
    for (const std::uint32_t j : active) {
      const SphereDescription& a = spheres[i];
      const SphereDescription& b = spheres[j];
      const bool a_glass = a.material.is_transparent(), b_glass = b.material.is_transparent();
      if (!a_glass && !b_glass) continue;
      const SphereRelation relation = classify_spheres(a, b);
      if (relation == SphereRelation::overlapping) {
        if (a_glass && b_glass) {
          const SphereDescription& first = a.line <= b.line ? a : b;
          const SphereDescription& second = a.line <= b.line ? b : a;
          throw SceneError(scene.source, second.line,
                           "transparent spheres at lines " + std::to_string(first.line) +
                               " and " + std::to_string(second.line) +
                               " partially overlap; transparent spheres must be disjoint or "
                               "nested");
        }
        continue;  // an opaque sphere may cut through glass
      }
      if (relation == SphereRelation::first_inside_second && b_glass) offer(i, j);
      if (relation == SphereRelation::second_inside_first && a_glass) offer(j, i);
    }
    active.push_back(i);
  }

  for (std::size_t i = 0; i < n; ++i)
    if (tree.parent[i] != kNoParent) tree.outside_ior[i] = spheres[tree.parent[i]].material.ior;
  return tree;
}

}  // namespace glint
