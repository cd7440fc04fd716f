#pragma once
// The report's inclusion precomputation: each transparent sphere learns the refractive index
// of the medium just outside it, i.e. the index of the smallest transparent sphere containing
// it, or the scene's medium if none does. It is well defined only if any two transparent
// spheres are disjoint or nested, so this is also where that rule is enforced.
//
// Opaque spheres have no inside medium and take no part: they may overlap anything.
//
// Two builders give the same tree: build_inclusion_tree_reference classifies every pair of
// spheres whose boxes meet (n^2/2 pairs for concentric shells), and build_inclusion_tree, which
// does the same while the pairs are few and otherwise files the spheres in a grid of nested
// chains (detail/nesting_grid.hpp), O(n log n) whatever the nesting depth.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "glint/detail/parallel_chunks.hpp"
#include "glint/geometry/sphere_bvh.hpp"
#include "glint/instruction_set.hpp"
#include "glint/scene/detail/nesting_grid.hpp"
#include "glint/scene/scene_description.hpp"
#include "glint/scene/scene_error.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

inline constexpr std::uint32_t kNoParent = 0xffffffffu;

enum class SphereRelation { disjoint, first_inside_second, second_inside_first, overlapping };

/// How far two spheres may overlap and still count as touching: four float ulps of the largest
/// magnitude among their centres' coordinates and radii (2^-21 of it). A scene's decimals are
/// rounded to float, each by up to half an ulp of its own magnitude, so spheres that touch as
/// written (87.4 + 12.6 inside 100) may overlap by a few ulps once read: the distance of the
/// centres carries up to about two ulps of error, each radius half of one.
inline double touching_tolerance(const SphereDescription& a, const SphereDescription& b) {
  const auto largest = [](const SphereDescription& s) {
    return std::max({std::abs(double(s.center.x)), std::abs(double(s.center.y)),
                     std::abs(double(s.center.z)), double(s.radius)});
  };
  return std::ldexp(std::max(largest(a), largest(b)), -21);
}

/// Classification in double precision of the spheres as read. Touching spheres (externally or
/// internally tangent, up to touching_tolerance) count as disjoint or nested; coincident
/// spheres (to the same tolerance) as overlapping.
inline SphereRelation classify_spheres(const SphereDescription& a, const SphereDescription& b) {
  const double dx = double(a.center.x) - b.center.x;
  const double dy = double(a.center.y) - b.center.y;
  const double dz = double(a.center.z) - b.center.z;
  const double distance = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double ra = a.radius, rb = b.radius;
  const double tolerance = touching_tolerance(a, b);
  if (distance <= tolerance && std::abs(ra - rb) <= tolerance) return SphereRelation::overlapping;
  if (distance >= ra + rb - tolerance) return SphereRelation::disjoint;
  if (distance + ra <= rb + tolerance) return SphereRelation::first_inside_second;
  if (distance + rb <= ra + tolerance) return SphereRelation::second_inside_first;
  return SphereRelation::overlapping;
}

struct InclusionTree {
  /// For every sphere of the description: the innermost transparent sphere containing it
  /// (kNoParent if none). Opaque spheres get a parent too, which tells which medium they sit in.
  std::vector<std::uint32_t> parent;
  /// Refractive index just outside each sphere.
  std::vector<float> outside_ior;
};

namespace detail {

/// The spheres' indices in the Z order of their centres (a Morton code of 10 bits per axis) over
/// the box that holds most of them: from the 1st to the 99th percentile of a sample, per axis,
/// so that a few distant centres (a room's walls of radius 1e5) do not squeeze every other
/// sphere into a few cells. Ties in index order.
inline std::vector<std::uint32_t> morton_order(const std::vector<SphereDescription>& spheres) {
  constexpr std::size_t kSample = 4096;
  const std::size_t stride = std::max<std::size_t>(1, spheres.size() / kSample);
  glm::dvec3 lower(0.0), upper(0.0);
  std::vector<float> sample;
  for (int axis = 0; axis < 3; ++axis) {
    sample.clear();
    for (std::size_t i = 0; i < spheres.size(); i += stride)
      sample.push_back(spheres[i].center[axis]);
    std::sort(sample.begin(), sample.end());
    lower[axis] = sample[sample.size() / 100];
    upper[axis] = sample[sample.size() - 1 - sample.size() / 100];
  }
  const glm::dvec3 scale = 1023.0 / glm::max(upper - lower, 1e-30);
  const auto spread = [](std::uint64_t v) {  // 10 bits to every third of 30
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    return (v | (v << 2)) & 0x09249249u;
  };
  std::vector<std::uint64_t> keys(spheres.size());
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const glm::dvec3 cell =
        glm::clamp((glm::dvec3(spheres[i].center) - lower) * scale, 0.0, 1023.0);
    const std::uint64_t code = spread(std::uint64_t(cell.x)) | spread(std::uint64_t(cell.y)) << 1 |
                               spread(std::uint64_t(cell.z)) << 2;
    keys[i] = code << 32 | i;
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> order(spheres.size());
  for (std::size_t i = 0; i < keys.size(); ++i)
    order[i] = static_cast<std::uint32_t>(keys[i]);
  return order;
}

/// Every sphere without a parent, in the scene's medium: where both builders start.
inline InclusionTree unnested_tree(const SceneDescription& scene) {
  InclusionTree tree;
  tree.parent.assign(scene.spheres.size(), kNoParent);
  tree.outside_ior.assign(scene.spheres.size(), scene.medium_ior);
  return tree;
}

/// The reference builder's work, given up (nullopt) once it has met more than `budget` pairs,
/// which is checked before each sphere: so it costs at most the budget plus a sphere's pairs per
/// core. The spheres are independent (each looks for its own containers and overlaps), so they
/// are shared among the cores; the first overlap in sphere order is the one reported, as a loop
/// in order would find it.
inline std::optional<InclusionTree> build_inclusion_tree_pairwise(const SceneDescription& scene,
                                                                  std::size_t budget) {
  const auto& spheres = scene.spheres;
  const std::size_t n = spheres.size();
  InclusionTree tree = unnested_tree(scene);

  std::vector<SphereBvh::Input> glass;
  for (std::size_t i = 0; i < n; ++i)
    if (spheres[i].material.is_transparent())
      glass.push_back({spheres[i].center, spheres[i].radius, static_cast<std::uint32_t>(i)});
  if (glass.empty()) return tree;
  const SphereBvh hierarchy(std::move(glass));

  // For each sphere, the first transparent sphere it partially overlaps, if any.
  std::vector<std::uint32_t> overlap(n, kNoParent);
  // Spheres near each other in space are queried one after the other, so that the nodes they
  // visit are still in the cache: the order changes nothing else, each query being independent.
  const std::vector<std::uint32_t> order = morton_order(spheres);
  std::atomic<std::size_t> met{0};
  std::atomic<bool> gave_up{false};
  parallel_chunks(n, 1024, 0, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t> pending;
    for (std::size_t at = begin; at < end; ++at) {
      if (met.load(std::memory_order_relaxed) > budget) {
        gave_up.store(true, std::memory_order_relaxed);
        return;
      }
      const std::uint32_t i = order[at];
      const SphereDescription& inner = spheres[i];
      // A transparent sphere must meet every glass sphere its box overlaps, to find partial
      // overlaps. An opaque one only needs its containers (it may cut through glass), and the
      // box of a container holds its centre: a point query, which keeps each wall of radius 1e5
      // from visiting every glass sphere of the scene.
      const Vec3 reach(inner.material.is_transparent() ? inner.radius : 0.0f);
      std::uint32_t& parent = tree.parent[i];
      std::size_t pairs = 0;
      const auto visit = [&](std::uint32_t j) {
        ++pairs;
        if (j == i) return;
        const SphereDescription& outer = spheres[j];
        switch (classify_spheres(inner, outer)) {
          case SphereRelation::first_inside_second:
            // Containers of one sphere are nested among themselves, so the smallest is the
            // innermost; ties (equal radii can only be coincident spheres, rejected below)
            // aside.
            if (parent == kNoParent || outer.radius < spheres[parent].radius ||
                (outer.radius == spheres[parent].radius && j < parent))
              parent = j;
            return;
          case SphereRelation::overlapping:
            // Opaque spheres may cut through glass.
            if (inner.material.is_transparent() && overlap[i] == kNoParent) overlap[i] = j;
            return;
          default:
            return;
        }
      };
      hierarchy.for_each_near_box(inner.center - reach, inner.center + reach, visit, pending);
      met.fetch_add(pairs, std::memory_order_relaxed);
    }
  });
  if (gave_up.load()) return std::nullopt;

  for (std::size_t i = 0; i < n; ++i)
    if (overlap[i] != kNoParent) {
      const SphereDescription& inner = spheres[i];
      const SphereDescription& outer = spheres[overlap[i]];
      const SphereDescription& first = inner.line <= outer.line ? inner : outer;
      const SphereDescription& second = inner.line <= outer.line ? outer : inner;
      throw SceneError(scene.source, second.line,
                       "transparent spheres at lines " + std::to_string(first.line) + " and " +
                           std::to_string(second.line) +
                           " partially overlap; transparent spheres must be disjoint or nested");
    }
  for (std::size_t i = 0; i < n; ++i)
    if (tree.parent[i] != kNoParent) tree.outside_ior[i] = spheres[tree.parent[i]].material.ior;
  return tree;
}

}  // namespace detail

/// The reference builder, and the first implementation: every pair of spheres whose boxes meet,
/// found with a bounding volume hierarchy over the transparent spheres, so the cost is about
/// n log n plus the number of nested or touching pairs: n^2/2 for concentric shells. It defines
/// the result (and, where two transparent spheres partially overlap, the SceneError) that
/// build_inclusion_tree must reproduce; that one falls back on it where it cannot vouch for its
/// own arithmetic, and the tests compare the two.
inline InclusionTree build_inclusion_tree_reference(const SceneDescription& scene) {
  return *detail::build_inclusion_tree_pairwise(scene, std::numeric_limits<std::size_t>::max());
}

namespace detail {

/// How the reference sees a transparent sphere q from sphere s: it meets q only where q's box
/// overlaps s's box in float (for an opaque s, where q's box holds s's centre), then asks
/// classify_spheres. `container`: q is one of s's containers; `clear`: q is disjoint from s;
/// `other`: anything else (an overlap, or a containment that rounding made odd).
enum class Seen { container, clear, other };

/// True where classify_spheres would find the spheres disjoint because they are far apart along
/// one axis (its distance is at least that axis's, up to a relative 1e-15): most pairs a query
/// meets, told apart without a square root.
inline bool far_apart(const Vec3& a, float ra, const Vec3& b, float rb) {
  const double far = (double(ra) + rb) * (1.0 + 1e-9);
  return std::abs(double(a.x) - b.x) > far || std::abs(double(a.y) - b.y) > far ||
         std::abs(double(a.z) - b.z) > far;
}

inline Seen seen_from(const SphereDescription& s, const SphereDescription& q) {
  if (far_apart(s.center, s.radius, q.center, q.radius)) return Seen::clear;
  const SphereRelation relation = classify_spheres(s, q);
  if (relation == SphereRelation::disjoint) return Seen::clear;
  if (relation != SphereRelation::first_inside_second) return Seen::other;
  const Vec3 reach(s.material.is_transparent() ? s.radius : 0.0f);
  const Vec3 lower = s.center - reach, upper = s.center + reach;
  const Vec3 r(q.radius);
  const bool meets = glm::all(glm::lessThanEqual(q.center - r, upper)) &&
                     glm::all(glm::greaterThanEqual(q.center + r, lower));
  return meets ? Seen::container : Seen::other;
}

/// The fast builder, or nullopt where it leaves the answer to the reference: two transparent
/// spheres that partially overlap (so that the SceneError names the same pair), and arithmetic
/// at its limits (coordinates far beyond the radii, equal radii nested by rounding), where its
/// reasoning, which takes containment as transitive, could differ from the reference by a
/// rounding.
///
/// Transparent spheres are taken from the largest down, each finding its parent among the ones
/// already filed (all at least as large) and then filed itself in a NestingGrid. The parent of s
/// is its smallest container, and in a valid scene containers are nested, so the first level of
/// the grid (from s's own up) that holds one holds the parent: in the cell of s's centre, each
/// chain's containers are a prefix, whose end the jump pointers find. The same pass checks the
/// nesting rule: a sphere filed before s (so no smaller) that meets s without containing it
/// either is in that cell at a level up to the parent's, or meets the parent without containing
/// it, which was checked when it was filed; and in a chain it is either the first sphere past the
/// containers or inside that one, which then meets s too. So looking at that single sphere per
/// chain suffices. Opaque spheres look up their parent the same way once every transparent
/// sphere is filed.
///
/// Cost, for a valid scene: one cell per level between a sphere's own and its parent's, a number
/// of chains per cell bounded by packing, and O(log n) per chain holding containers: O(n (log n +
/// log(r_max / r_min))) after the sort, whatever the nesting depth.
inline std::optional<InclusionTree> build_inclusion_tree_fast(const SceneDescription& scene) {
  const auto& spheres = scene.spheres;
  const std::size_t n = spheres.size();
  InclusionTree tree = unnested_tree(scene);

  std::vector<std::uint32_t> glass;
  for (std::size_t i = 0; i < n; ++i) {
    const SphereDescription& s = spheres[i];
    if (!(s.radius > 0.0f) || !std::isfinite(s.radius) || !std::isfinite(s.center.x) ||
        !std::isfinite(s.center.y) || !std::isfinite(s.center.z))
      return std::nullopt;  // never in a validated scene; the levels need positive radii
    if (s.material.is_transparent()) glass.push_back(static_cast<std::uint32_t>(i));
  }
  if (glass.empty()) return tree;

  // The reference's choice among containers: the smallest, then the first listed.
  const auto before = [&](std::uint32_t a, std::uint32_t b) {
    return b == kNoParent || spheres[a].radius < spheres[b].radius ||
           (spheres[a].radius == spheres[b].radius && a < b);
  };
  {
    // Sorted as (radius, index) pairs: the comparisons then read one array, not the scene.
    std::vector<std::pair<float, std::uint32_t>> order;
    order.reserve(glass.size());
    for (const std::uint32_t g : glass)
      order.emplace_back(spheres[g].radius, g);
    std::sort(order.begin(), order.end(), std::greater<>());  // the largest (and last) first
    for (std::size_t k = 0; k < glass.size(); ++k)
      glass[k] = order[k].second;
  }
  std::vector<int> levels;
  for (const std::uint32_t g : glass)
    levels.push_back(NestingGrid::level_of(spheres[g].radius));
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());

  constexpr std::uint32_t kGiveUp = kNoParent - 1;  // sphere indices stay below it (checked)
  if (n >= kGiveUp) return std::nullopt;
  std::vector<NestingGrid::Sphere> geometry;  // of glass[k], in the same order
  geometry.reserve(glass.size());
  for (const std::uint32_t g : glass)
    geometry.push_back({spheres[g].center, spheres[g].radius});
  NestingGrid grid;
  if (!grid.prepare(geometry)) return std::nullopt;

  // The parent of sphere s among the filed spheres, kNoParent if none, kGiveUp to give up.
  const auto find_parent = [&](std::uint32_t s) -> std::uint32_t {
    const SphereDescription& inner = spheres[s];
    const bool transparent = inner.material.is_transparent();
    const auto contains = [&](std::uint32_t q) {
      return seen_from(inner, spheres[q]) == Seen::container;
    };
    const int own_level = NestingGrid::level_of(inner.radius);
    for (auto level = std::lower_bound(levels.begin(), levels.end(), own_level);
         level != levels.end(); ++level) {
      const std::uint32_t cell = grid.cell_at(inner.center, *level);
      if (cell == NestingGrid::kNone) continue;
      std::uint32_t parent = kNoParent;
      for (const NestingGrid::Entry* e = grid.begin(cell); e != grid.end(cell); ++e) {
        if (far_apart(inner.center, inner.radius, e->head_center, e->head_radius)) continue;
        const NestingGrid::Chain& chain = grid.chain(e->chain);
        const std::uint32_t head = grid.node(chain.head).sphere;
        const Seen head_seen = seen_from(inner, spheres[head]);
        if (head_seen != Seen::container) {
          // Nothing in the chain contains s. An opaque s may cut through any of it; a
          // transparent one must be clear of the head, and so of all it holds.
          if (transparent && head_seen != Seen::clear) return kGiveUp;
          continue;
        }
        const auto [deepest, past] = grid.deepest(chain, contains);
        if (transparent && past != NestingGrid::kNone &&
            seen_from(inner, spheres[grid.node(past).sphere]) != Seen::clear)
          return kGiveUp;
        const std::uint32_t candidate = grid.node(deepest).sphere;
        if (transparent && spheres[candidate].radius == inner.radius) return kGiveUp;
        if (before(candidate, parent)) parent = candidate;
      }
      // Containers are nested, so any on a higher level is larger; and a sphere there that
      // meets s meets this parent too, so it contains it: the filed spheres are pairwise
      // disjoint or nested, each pair checked when the smaller one was filed.
      if (parent != kNoParent) return parent;
    }
    return kNoParent;
  };

  for (std::size_t k = 0; k < glass.size(); ++k) {
    const std::uint32_t s = glass[k];
    const std::uint32_t parent = find_parent(s);
    if (parent == kGiveUp) return std::nullopt;
    tree.parent[s] = parent;
    // File s in every cell of its level near it, after the innermost chain tail containing it
    // (which keeps the chains of a cell as few as its innermost spheres).
    const SphereDescription& inner = spheres[s];
    grid.for_each_cell_of(geometry[k], [&](std::uint32_t cell) {
      std::uint32_t after = NestingGrid::kNone, tail = kNoParent;
      for (const NestingGrid::Entry* e = grid.begin(cell); e != grid.end(cell); ++e) {
        if (far_apart(inner.center, inner.radius, e->head_center, e->head_radius)) continue;
        const std::uint32_t t = grid.node(grid.chain(e->chain).tail).sphere;
        if (before(t, tail) && seen_from(inner, spheres[t]) == Seen::container) {
          after = e->chain;
          tail = t;
        }
      }
      grid.append(cell, after, s, geometry[k]);
    });
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (spheres[i].material.is_transparent()) continue;
    const std::uint32_t parent = find_parent(static_cast<std::uint32_t>(i));
    if (parent == kGiveUp) return std::nullopt;
    tree.parent[i] = parent;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (tree.parent[i] != kNoParent) tree.outside_ior[i] = spheres[tree.parent[i]].material.ior;
  return tree;
}

}  // namespace detail

/// The pairs per sphere the reference's loop may meet in build_inclusion_tree before it turns to
/// the fast builder: random scenes need one or two.
inline constexpr std::size_t kPairsPerSphere = 16;

/// Builds the tree; throws SceneError naming both lines if two transparent spheres partially
/// overlap. The result, and the error, are those of build_inclusion_tree_reference, in
/// O(n log n) for concentric shells as for disjoint spheres (see
/// detail::build_inclusion_tree_fast); an invalid scene may cost what the reference costs.
inline InclusionTree build_inclusion_tree(const SceneDescription& scene) {
  // Where nesting is shallow (most scenes) the pairs are few and the reference's own loop is
  // the quickest; it gives up after a few pairs per sphere, which bounds the time it can waste.
  const std::size_t budget = kPairsPerSphere * scene.spheres.size() + 4096;
  if (std::optional<InclusionTree> tree = detail::build_inclusion_tree_pairwise(scene, budget))
    return std::move(*tree);
  if (std::optional<InclusionTree> tree = detail::build_inclusion_tree_fast(scene))
    return std::move(*tree);
  return build_inclusion_tree_reference(scene);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
