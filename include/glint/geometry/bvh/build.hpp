#pragma once
// Building the binary tree of a sphere BVH: top down, splitting each node where a binned
// surface area heuristic says, into 32-byte nodes with the left child right after its parent
// and the spheres of each leaf stored contiguously.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "glint/math/vector.hpp"

namespace glint::bvh {

/// A sphere to build the tree over; `id` is what hits report.
struct SphereInput {
  Vec3 center;
  float radius;
  std::uint32_t id;
};

/// A sphere as a leaf stores it.
struct LeafSphere {
  Vec3 center;
  float radius;
  std::uint32_t id;
};

struct Box {
  Vec3 lower{std::numeric_limits<float>::max()};
  Vec3 upper{-std::numeric_limits<float>::max()};

  void grow(const Vec3& p) {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  void grow(const Box& b) {
    lower = glm::min(lower, b.lower);
    upper = glm::max(upper, b.upper);
  }
  float half_area() const {
    const Vec3 e = glm::max(upper - lower, Vec3(0.0f));
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

inline Box bounds_of(const SphereInput& s) {
  Box b;
  b.grow(s.center - Vec3(s.radius));
  b.grow(s.center + Vec3(s.radius));
  return b;
}

struct Node {
  Vec3 lower;
  std::uint32_t offset;  ///< leaf: first sphere; inner: index of the right child
  Vec3 upper;
  std::uint32_t count;  ///< leaf: number of spheres; inner: 0
};
static_assert(sizeof(Node) == 32);

struct BinaryTree {
  std::vector<Node> nodes;  ///< the root first
  std::vector<LeafSphere> spheres;
};

/// Leaves hold up to this many spheres, or up to twice as many where splitting them would not
/// pay (see detail::Builder::leaf_is_cheaper).
inline constexpr std::uint32_t kMaxLeafSize = 4;
/// The depth below which every node is a leaf; it bounds the traversal stack.
inline constexpr int kMaxDepth = 62;

namespace detail {

/// A node's box and the box of its spheres' centres.
struct RangeBounds {
  Box box;
  Box centroids;
};

/// Sorts centres along one axis into kBins equal bins over the centroid box.
struct Binning {
  static constexpr int kBins = 16;
  int axis;
  float lower;
  float scale;

  Binning(const Box& centroids, int split_axis)
      : axis(split_axis),
        lower(centroids.lower[split_axis]),
        scale(kBins / (centroids.upper - centroids.lower)[split_axis]) {}

  int bin_of(const SphereInput& s) const {
    return std::min(kBins - 1, static_cast<int>((s.center[axis] - lower) * scale));
  }
};

/// The best plane between bins (spheres in bins below `bin` go left) and its SAH cost.
struct Split {
  int bin = -1;
  float cost = std::numeric_limits<float>::max();
};

class Builder {
 public:
  explicit Builder(std::vector<SphereInput>& spheres) : spheres_(spheres) {}

  BinaryTree build() {
    tree_.nodes.reserve(2 * spheres_.size());
    tree_.spheres.reserve(spheres_.size());
    build_node(0, spheres_.size(), 0);
    return std::move(tree_);
  }

 private:
  std::uint32_t build_node(std::size_t begin, std::size_t end, int depth) {
    const RangeBounds bounds = bounds_of_range(begin, end);
    const std::size_t count = end - begin;
    if (count <= kMaxLeafSize || depth >= kMaxDepth) return make_leaf(begin, end, bounds.box);
    const Vec3 extent = bounds.centroids.upper - bounds.centroids.lower;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    std::size_t middle = begin + count / 2;
    if (extent[axis] > 0.0f) {
      const Binning binning(bounds.centroids, axis);
      const Split split = best_split(binning, begin, end);
      if (leaf_is_cheaper(split, bounds.box, count)) return make_leaf(begin, end, bounds.box);
      middle = partition(binning, split, begin, end);
    }
    // All centroids in one bin (e.g. concentric spheres): split by count instead.
    if (middle == begin || middle == end) middle = median_split(axis, begin, end);
    return make_inner(begin, middle, end, bounds.box, depth);
  }

  RangeBounds bounds_of_range(std::size_t begin, std::size_t end) const {
    RangeBounds bounds;
    for (std::size_t i = begin; i < end; ++i) {
      bounds.box.grow(bounds_of(spheres_[i]));
      bounds.centroids.grow(spheres_[i].center);
    }
    return bounds;
  }

  /// Sweeps the bins from both ends for the plane of least SAH cost.
  Split best_split(const Binning& binning, std::size_t begin, std::size_t end) const {
    constexpr int kBins = Binning::kBins;
    std::array<Box, kBins> bin_boxes{};
    std::array<std::size_t, kBins> bin_counts{};
    for (std::size_t i = begin; i < end; ++i) {
      const int b = binning.bin_of(spheres_[i]);
      bin_boxes[b].grow(bounds_of(spheres_[i]));
      ++bin_counts[b];
    }
    std::array<float, kBins - 1> left_cost{};
    Box running;
    std::size_t running_count = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      running.grow(bin_boxes[b]);
      running_count += bin_counts[b];
      left_cost[b] = running.half_area() * static_cast<float>(running_count);
    }
    Split best;
    running = Box{};
    running_count = 0;
    for (int b = kBins - 1; b > 0; --b) {
      running.grow(bin_boxes[b]);
      running_count += bin_counts[b];
      const float cost = left_cost[b - 1] + running.half_area() * static_cast<float>(running_count);
      if (cost < best.cost) best = {b, cost};
    }
    return best;
  }

  /// Whether a small node is cheaper as a leaf than split, testing a sphere costing about as
  /// much as testing a box.
  static bool leaf_is_cheaper(const Split& split, const Box& box, std::size_t count) {
    return count <= 2 * kMaxLeafSize &&
           split.cost >= box.half_area() * (static_cast<float>(count) - 1.0f);
  }

  std::size_t partition(const Binning& binning, const Split& split, std::size_t begin,
                        std::size_t end) {
    const auto middle = std::partition(
        spheres_.begin() + std::ptrdiff_t(begin), spheres_.begin() + std::ptrdiff_t(end),
        [&](const SphereInput& s) { return binning.bin_of(s) < split.bin; });
    return static_cast<std::size_t>(middle - spheres_.begin());
  }

  std::size_t median_split(int axis, std::size_t begin, std::size_t end) {
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(
        spheres_.begin() + std::ptrdiff_t(begin), spheres_.begin() + std::ptrdiff_t(middle),
        spheres_.begin() + std::ptrdiff_t(end), [&](const SphereInput& a, const SphereInput& b) {
          return a.center[axis] < b.center[axis] ||
                 (a.center[axis] == b.center[axis] && a.id < b.id);
        });
    return middle;
  }

  std::uint32_t make_leaf(std::size_t begin, std::size_t end, const Box& box) {
    const auto index = static_cast<std::uint32_t>(tree_.nodes.size());
    tree_.nodes.push_back(Node{box.lower, static_cast<std::uint32_t>(tree_.spheres.size()),
                               box.upper, static_cast<std::uint32_t>(end - begin)});
    for (std::size_t i = begin; i < end; ++i)
      tree_.spheres.push_back(LeafSphere{spheres_[i].center, spheres_[i].radius, spheres_[i].id});
    return index;
  }

  std::uint32_t make_inner(std::size_t begin, std::size_t middle, std::size_t end, const Box& box,
                           int depth) {
    const auto index = static_cast<std::uint32_t>(tree_.nodes.size());
    tree_.nodes.push_back(Node{box.lower, 0, box.upper, 0});
    build_node(begin, middle, depth + 1);
    tree_.nodes[index].offset = build_node(middle, end, depth + 1);
    return index;
  }

  std::vector<SphereInput>& spheres_;
  BinaryTree tree_;
};

}  // namespace detail

/// The binary tree over `spheres` (which it reorders); empty for no spheres.
inline BinaryTree build_binary_tree(std::vector<SphereInput>& spheres) {
  if (spheres.empty()) return {};
  return detail::Builder(spheres).build();
}

}  // namespace glint::bvh
