#pragma once
// Building the binary tree of a sphere BVH: top down, splitting each node where a binned
// surface area heuristic says, into 32-byte nodes with the left child right after its parent
// and the spheres of each leaf stored contiguously.
//
// Large trees are built on every core, into the same nodes as one core would make: the top
// levels are split until the ranges are small (the two halves of a range at once, each large
// range binned in chunks on its cores), those subtrees are built in parallel (disjoint ranges of
// the spheres, each into its own nodes), and the nodes are then laid out in the serial order,
// the subtrees spliced in with their offsets moved.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <iterator>
#include <limits>
#include <system_error>
#include <thread>
#include <vector>

#include "glint/detail/parallel_chunks.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::bvh {

/// A sphere to build the tree over; `id` is what hits report.
struct SphereInput {
  Vec3 center;
  float radius;
  std::uint32_t id;
};

/// A sphere as a leaf stores it: as given, the input reordered into the leaves' order.
using LeafSphere = SphereInput;

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
/// pay (see detail::Builder::leaf_is_cheaper). Eight, one AVX2 test of the leaf kernel, rather
/// than four: a smaller tree (265 rather than 310 bytes per sphere at 10^6) that incoherent
/// rays traverse faster in large scenes (+33% at 10^6 spheres, +22% in a dense packing) for
/// 3 to 5% less in scenes of 10^3 to 10^5 (glint-embree-compare, 2-vCPU AMD EPYC Zen 5).
inline constexpr std::uint32_t kMaxLeafSize = 8;
/// The depth below which every node is a leaf; it bounds the traversal stack.
inline constexpr int kMaxDepth = 62;

namespace detail {

/// A node's box and the box of its spheres' centres.
struct RangeBounds {
  Box box;
  Box centroids;

  void grow(const RangeBounds& b) {
    box.grow(b.box);
    centroids.grow(b.centroids);
  }
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

/// The best plane between bins (spheres in bins below `bin` go left), its SAH cost, and the
/// bounds of the two sides: the children's, taken from the bins rather than from another pass
/// over their spheres (unions of boxes, so exactly the same).
struct Split {
  int bin = -1;
  float cost = std::numeric_limits<float>::max();
  RangeBounds left, right;
};

class Builder {
 public:
  explicit Builder(std::vector<SphereInput>& spheres) : spheres_(spheres) {}

  /// Trees of fewer spheres are built on one core: below this, threads cost more than they save.
  static constexpr std::size_t kParallelBuildSize = std::size_t{1} << 16;

  /// `cores`: how many to use at most (0: all there are); the tree is the same for any.
  BinaryTree build(std::size_t cores = 0) {
    if (cores == 0) cores = std::max(1u, std::thread::hardware_concurrency());
    if (cores == 1 || spheres_.size() < kParallelBuildSize) {
      tree_.nodes.reserve(2 * spheres_.size());
      build_node(0, spheres_.size(), 0, bounds_of_range(0, spheres_.size()));
      tree_.spheres = std::move(spheres_);
      return std::move(tree_);
    }
    const RangeBounds root = bounds_of_range(0, spheres_.size(), cores);
    // Subtrees of at most this many spheres are built in parallel: several per core, so that
    // uneven ones even out.
    const std::size_t subtree_size = std::max<std::size_t>(spheres_.size() / (8 * cores), 4096);
    std::vector<Piece> pieces;
    plan(0, spheres_.size(), 0, root, subtree_size, cores, pieces);
    std::vector<Piece*> subtrees;
    for (Piece& piece : pieces)
      if (piece.kind == Piece::Kind::subtree) subtrees.push_back(&piece);
    glint::detail::parallel_chunks(
        subtrees.size(), 1, cores, [&](std::size_t first, std::size_t last) {
          for (std::size_t t = first; t < last; ++t) {
            Piece& piece = *subtrees[t];
            Builder builder(spheres_);
            builder.build_node(piece.begin, piece.end, piece.depth, piece.bounds);
            piece.tree = std::move(builder.tree_);
          }
        });
    std::size_t nodes = 0;
    for (const Piece& piece : pieces)
      nodes += piece.kind == Piece::Kind::subtree ? piece.tree.nodes.size() : 1;
    tree_.nodes.reserve(nodes);
    std::size_t next = 0;
    lay_out(pieces, next);
    tree_.spheres = std::move(spheres_);
    return std::move(tree_);
  }

 private:
  /// What a node of a range becomes: a leaf, or an inner node split at `middle` into children
  /// of bounds `left` and `right`.
  struct Decision {
    bool leaf;
    std::size_t middle;
    RangeBounds left, right;
  };

  /// The one place where a node is decided, given the bounds of its range; reorders the range's
  /// spheres for a split.
  Decision decide(std::size_t begin, std::size_t end, int depth, const RangeBounds& bounds,
                  std::size_t cores = 1) {
    const std::size_t count = end - begin;
    if (count <= kMaxLeafSize || depth >= kMaxDepth) return {true, end, {}, {}};
    const Vec3 extent = bounds.centroids.upper - bounds.centroids.lower;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    if (extent[axis] > 0.0f) {
      const Binning binning(bounds.centroids, axis);
      const Split split = best_split(binning, begin, end, cores);
      if (leaf_is_cheaper(split, bounds.box, count)) return {true, end, {}, {}};
      const std::size_t middle = partition(binning, split, begin, end);
      if (middle != begin && middle != end) return {false, middle, split.left, split.right};
    }
    // All centroids in one bin (e.g. concentric spheres): split by count instead.
    const std::size_t middle = median_split(axis, begin, end);
    return {false, middle, bounds_of_range(begin, middle), bounds_of_range(middle, end)};
  }

  std::uint32_t build_node(std::size_t begin, std::size_t end, int depth,
                           const RangeBounds& bounds) {
    const Decision decision = decide(begin, end, depth, bounds);
    if (decision.leaf) return make_leaf(begin, end, bounds.box);
    return make_inner(begin, end, decision, bounds.box, depth);
  }

  /// The top of a parallel build, in the serial build's order: its leaves and inner nodes, and
  /// the ranges left to be built as subtrees.
  struct Piece {
    enum class Kind { leaf, inner, subtree } kind;
    std::size_t begin, end;
    int depth;
    RangeBounds bounds;
    BinaryTree tree;  ///< subtree, once built
  };

  /// Splits [begin, end) in the serial build's order down to ranges of at most subtree_size
  /// spheres, appending the pieces to `pieces`. On several cores, the two halves of a range are
  /// planned at once (their spheres are disjoint), the second into its own list, appended
  /// after the first's: the same pieces in the same order.
  void plan(std::size_t begin, std::size_t end, int depth, const RangeBounds& bounds,
            std::size_t subtree_size, std::size_t cores, std::vector<Piece>& pieces) {
    if (end - begin <= subtree_size) {
      pieces.push_back({Piece::Kind::subtree, begin, end, depth, bounds, {}});
      return;
    }
    const Decision decision = decide(begin, end, depth, bounds, cores);
    if (decision.leaf) {
      pieces.push_back({Piece::Kind::leaf, begin, end, depth, bounds, {}});
      return;
    }
    pieces.push_back({Piece::Kind::inner, begin, end, depth, bounds, {}});
    const auto plan_left = [&](std::size_t left_cores) {
      plan(begin, decision.middle, depth + 1, decision.left, subtree_size, left_cores, pieces);
    };
    const auto plan_right = [&](std::size_t right_cores, std::vector<Piece>& into) {
      plan(decision.middle, end, depth + 1, decision.right, subtree_size, right_cores, into);
    };
    if (cores == 1) {
      plan_left(1);
      plan_right(1, pieces);
      return;
    }
    std::vector<Piece> right;
    std::exception_ptr right_failure;
    {
      std::jthread helper;  // declared after what it uses: joined before they go
      try {
        helper = std::jthread([&] {
          try {
            plan_right(cores / 2, right);
          } catch (...) {
            right_failure = std::current_exception();
          }
        });
      } catch (const std::system_error&) {
        // No thread: this one plans both halves.
      }
      plan_left(cores - cores / 2);
      if (!helper.joinable()) plan_right(cores / 2, right);
    }
    if (right_failure) std::rethrow_exception(right_failure);
    pieces.insert(pieces.end(), std::make_move_iterator(right.begin()),
                  std::make_move_iterator(right.end()));
  }

  /// Appends the nodes of the piece at `next` and of its descendants, as build_node would have;
  /// returns the index of its node.
  std::uint32_t lay_out(std::vector<Piece>& pieces, std::size_t& next) {
    Piece& piece = pieces[next++];
    switch (piece.kind) {
      case Piece::Kind::leaf:
        return make_leaf(piece.begin, piece.end, piece.bounds.box);
      case Piece::Kind::inner: {
        const auto index = static_cast<std::uint32_t>(tree_.nodes.size());
        tree_.nodes.push_back(Node{piece.bounds.box.lower, 0, piece.bounds.box.upper, 0});
        lay_out(pieces, next);
        tree_.nodes[index].offset = lay_out(pieces, next);
        return index;
      }
      case Piece::Kind::subtree:
        break;
    }
    const auto node_base = static_cast<std::uint32_t>(tree_.nodes.size());
    for (Node node : piece.tree.nodes) {
      if (node.count == 0) node.offset += node_base;  // leaves' offsets are already global
      tree_.nodes.push_back(node);
    }
    piece.tree = {};
    return node_base;
  }

  RangeBounds bounds_of_range(std::size_t begin, std::size_t end) const {
    RangeBounds bounds;
    for (std::size_t i = begin; i < end; ++i) {
      bounds.box.grow(bounds_of(spheres_[i]));
      bounds.centroids.grow(spheres_[i].center);
    }
    return bounds;
  }

  /// of(first, last) over [begin, end) cut into chunks, on up to `cores` cores, the results
  /// merged with merge(total, chunk): for unions and sums, which come out the same however the
  /// range is cut. A large range at the top of a parallel build is worked on this way, since it
  /// is split before the subtrees can be built in parallel.
  template <class Result, class Of, class Merge>
  static Result in_chunks(std::size_t begin, std::size_t end, std::size_t cores, const Of& of,
                          const Merge& merge) {
    constexpr std::size_t kChunk = std::size_t{1} << 14;
    if (cores == 1 || end - begin < kParallelBuildSize) return of(begin, end);
    std::vector<Result> chunks((end - begin + kChunk - 1) / kChunk);
    glint::detail::parallel_chunks(
        chunks.size(), 1, cores, [&](std::size_t first, std::size_t last) {
          for (std::size_t c = first; c < last; ++c)
            chunks[c] = of(begin + c * kChunk, std::min(end, begin + (c + 1) * kChunk));
        });
    Result total;
    for (const Result& chunk : chunks)
      merge(total, chunk);
    return total;
  }

  /// bounds_of_range on up to `cores` cores.
  RangeBounds bounds_of_range(std::size_t begin, std::size_t end, std::size_t cores) const {
    return in_chunks<RangeBounds>(
        begin, end, cores,
        [&](std::size_t first, std::size_t last) { return bounds_of_range(first, last); },
        [](RangeBounds& total, const RangeBounds& chunk) { total.grow(chunk); });
  }

  static constexpr int kBins = Binning::kBins;

  /// The bounds and sphere counts of the bins.
  struct Bins {
    std::array<RangeBounds, kBins> bounds{};
    std::array<std::size_t, kBins> counts{};

    void add(const Bins& other) {
      for (int b = 0; b < kBins; ++b) {
        bounds[b].grow(other.bounds[b]);
        counts[b] += other.counts[b];
      }
    }
  };

  Bins bin(const Binning& binning, std::size_t begin, std::size_t end) const {
    Bins bins;
    // Binning is most of the build: a bin's four corners as vectors of four floats and a
    // sphere's centre and radius read as one (SSE on any x86-64) take a quarter of the min and
    // max of Box::grow. Operands in its order (glm::min(a, b) is b < a ? b : a), so the bounds
    // are the same floats.
    using Four = float __attribute__((vector_size(16)));
    static_assert(offsetof(SphereInput, radius) == 3 * sizeof(float));
    const auto lower = [](Four value, Four bound) { return value < bound ? value : bound; };
    const auto upper = [](Four value, Four bound) { return bound < value ? value : bound; };
    struct Corners {
      Four box_lower, box_upper, centroid_lower, centroid_upper;
    };
    const Four highest = Four{} + std::numeric_limits<float>::max();
    const Four lowest = Four{} - std::numeric_limits<float>::max();
    std::array<Corners, kBins> corners;
    corners.fill({highest, lowest, highest, lowest});
    for (std::size_t i = begin; i < end; ++i) {
      const SphereInput& s = spheres_[i];
      const auto b = std::size_t(binning.bin_of(s));
      Corners& c = corners[b];
      Four center_radius;  // the radius in the last lane
      std::memcpy(&center_radius, &s.center.x, sizeof center_radius);
      const Four radius = __builtin_shufflevector(center_radius, center_radius, 3, 3, 3, 3);
      c.box_lower = lower(center_radius - radius, c.box_lower);
      c.box_upper = upper(center_radius + radius, c.box_upper);
      c.centroid_lower = lower(center_radius, c.centroid_lower);
      c.centroid_upper = upper(center_radius, c.centroid_upper);
      ++bins.counts[b];
    }
    const auto vec3 = [](Four v) { return Vec3(v[0], v[1], v[2]); };
    for (std::size_t b = 0; b < std::size_t(kBins); ++b) {
      if (bins.counts[b] == 0) continue;  // left as an empty box
      bins.bounds[b].box = {vec3(corners[b].box_lower), vec3(corners[b].box_upper)};
      bins.bounds[b].centroids = {vec3(corners[b].centroid_lower), vec3(corners[b].centroid_upper)};
    }
    return bins;
  }

  /// bin() on up to `cores` cores.
  Bins bin_range(const Binning& binning, std::size_t begin, std::size_t end,
                 std::size_t cores) const {
    return in_chunks<Bins>(
        begin, end, cores,
        [&](std::size_t first, std::size_t last) { return bin(binning, first, last); },
        [](Bins& total, const Bins& chunk) { total.add(chunk); });
  }

  /// Sweeps the bins from both ends for the plane of least SAH cost.
  Split best_split(const Binning& binning, std::size_t begin, std::size_t end,
                   std::size_t cores) const {
    const Bins binned = bin_range(binning, begin, end, cores);
    const std::array<RangeBounds, kBins>& bins = binned.bounds;
    const std::array<std::size_t, kBins>& bin_counts = binned.counts;
    // left[b]: the bounds of bins 0 .. b.
    std::array<RangeBounds, kBins - 1> left{};
    std::array<float, kBins - 1> left_cost{};
    RangeBounds running;
    std::size_t running_count = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      running.grow(bins[b]);
      running_count += bin_counts[b];
      left[b] = running;
      left_cost[b] = running.box.half_area() * static_cast<float>(running_count);
    }
    Split best;
    running = RangeBounds{};
    running_count = 0;
    for (int b = kBins - 1; b > 0; --b) {
      running.grow(bins[b]);
      running_count += bin_counts[b];
      const float cost =
          left_cost[b - 1] + running.box.half_area() * static_cast<float>(running_count);
      if (cost < best.cost) best = {b, cost, left[b - 1], running};
    }
    return best;
  }

  /// Whether a small node is cheaper as a leaf than split, testing a sphere costing about as
  /// much as testing a box.
  static bool leaf_is_cheaper(const Split& split, const Box& box, std::size_t count) {
    return count <= 2 * kMaxLeafSize &&
           split.cost >= box.half_area() * (static_cast<float>(count) - 1.0f);
  }

  /// Moves the spheres of the bins below split.bin to the front of the range; returns where
  /// the others begin. Without a branch on the side: a sphere's side is as good as random, and
  /// std::partition's mispredicted branches were a third of the build. (The order within a side
  /// differs from std::partition's, so leaves may list their spheres in another order; which
  /// spheres each node holds does not depend on it.)
  std::size_t partition(const Binning& binning, const Split& split, std::size_t begin,
                        std::size_t end) {
    // Spheres [begin, middle) go left, [middle, i) right.
    std::size_t middle = begin;
    for (std::size_t i = begin; i < end; ++i) {
      const SphereInput s = spheres_[i];
      spheres_[i] = spheres_[middle];
      spheres_[middle] = s;
      middle += std::size_t(binning.bin_of(s) < split.bin);
    }
    return middle;
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
    // Leaves come in the order of their ranges, so a leaf's spheres are where its range is: the
    // reordered input becomes the tree's spheres at the end.
    tree_.nodes.push_back(Node{box.lower, static_cast<std::uint32_t>(begin), box.upper,
                               static_cast<std::uint32_t>(end - begin)});
    return index;
  }

  std::uint32_t make_inner(std::size_t begin, std::size_t end, const Decision& split,
                           const Box& box, int depth) {
    const auto index = static_cast<std::uint32_t>(tree_.nodes.size());
    tree_.nodes.push_back(Node{box.lower, 0, box.upper, 0});
    build_node(begin, split.middle, depth + 1, split.left);
    tree_.nodes[index].offset = build_node(split.middle, end, depth + 1, split.right);
    return index;
  }

  std::vector<SphereInput>& spheres_;
  BinaryTree tree_;
};

}  // namespace detail

/// The binary tree over `spheres`, which become its leaf spheres; empty for no spheres. Built
/// on up to `cores` cores (0: all there are), into the same tree whatever their number.
inline BinaryTree build_binary_tree(std::vector<SphereInput> spheres, std::size_t cores = 0) {
  if (spheres.empty()) return {};
  return detail::Builder(spheres).build(cores);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::bvh
