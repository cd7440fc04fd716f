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

#include "glint/geometry/sphere_bvh.hpp"
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
/// overlap. Candidate pairs come from a bounding volume hierarchy over the transparent spheres,
/// so the cost is about n log n plus the number of nested or touching pairs, not n^2.
inline InclusionTree build_inclusion_tree(const SceneDescription& scene) {
  const auto& spheres = scene.spheres;
  const std::size_t n = spheres.size();
  InclusionTree tree;
  tree.parent.assign(n, kNoParent);
  tree.outside_ior.assign(n, scene.medium_ior);

  std::vector<SphereBvh::Input> glass;
  for (std::size_t i = 0; i < n; ++i)
    if (spheres[i].material.is_transparent())
      glass.push_back({spheres[i].center, spheres[i].radius, static_cast<std::uint32_t>(i)});
  if (glass.empty()) return tree;
  const SphereBvh hierarchy(std::move(glass));

  std::vector<std::uint32_t> pending;
  for (std::size_t index = 0; index < n; ++index) {
    const auto i = static_cast<std::uint32_t>(index);
    const SphereDescription& inner = spheres[i];
    // A transparent sphere must meet every glass sphere its box overlaps, to find partial
    // overlaps. An opaque one only needs its containers (it may cut through glass), and the box
    // of a container holds its centre: a point query, which keeps each wall of radius 1e5 from
    // visiting every glass sphere of the scene.
    const Vec3 reach(inner.material.is_transparent() ? inner.radius : 0.0f);
    std::uint32_t& parent = tree.parent[i];
    const auto visit = [&](std::uint32_t j) {
      if (j == i) return;
      const SphereDescription& outer = spheres[j];
      switch (classify_spheres(inner, outer)) {
        case SphereRelation::first_inside_second:
          // Containers of one sphere are nested among themselves, so the smallest is the
          // innermost; ties (equal radii can only be coincident spheres, rejected below) aside.
          if (parent == kNoParent || outer.radius < spheres[parent].radius ||
              (outer.radius == spheres[parent].radius && j < parent))
            parent = j;
          return;
        case SphereRelation::overlapping:
          if (!inner.material.is_transparent()) return;  // opaque spheres may cut through glass
          {
            const SphereDescription& first = inner.line <= outer.line ? inner : outer;
            const SphereDescription& second = inner.line <= outer.line ? outer : inner;
            throw SceneError(scene.source, second.line,
                             "transparent spheres at lines " + std::to_string(first.line) +
                                 " and " + std::to_string(second.line) +
                                 " partially overlap; transparent spheres must be disjoint or "
                                 "nested");
          }
        default:
          return;
      }
    };
    hierarchy.for_each_near_box(inner.center - reach, inner.center + reach, visit, pending);
  }

  for (std::size_t i = 0; i < n; ++i)
    if (tree.parent[i] != kNoParent) tree.outside_ior[i] = spheres[tree.parent[i]].material.ior;
  return tree;
}

}  // namespace glint
