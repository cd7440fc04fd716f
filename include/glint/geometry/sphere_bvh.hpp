#pragma once
// A bounding volume hierarchy over spheres, for scenes too large for a linear SIMD scan.
// Built top-down as a binary tree with a binned surface-area heuristic (32-byte nodes, the
// left child right after its parent), then collapsed into a 4-wide tree whose nodes hold their
// children's boxes in structure-of-arrays form, so one SSE pass tests all four. Leaf spheres
// are stored contiguously, so a leaf is one short linear scan. Traversal tests leaves nearest
// first, visits inner children nearest first, and skips any subtree whose box starts beyond
// the closest hit found so far.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include <glm/vector_relational.hpp>

#if defined(__SSE4_1__)
#include <smmintrin.h>
#endif

#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_sphere.hpp"
#include "glint/geometry/sphere_set.hpp"

namespace glint {

class SphereBvh {
 public:
  struct Input {
    Vec3 center;
    float radius;
    std::uint32_t id;
  };

  SphereBvh() = default;
  explicit SphereBvh(std::vector<Input> spheres) { build(std::move(spheres)); }

  std::size_t size() const { return spheres_.size(); }
  std::size_t node_count() const { return nodes_.size(); }
  std::size_t wide_node_count() const { return wide_.size(); }
  bool empty() const { return spheres_.empty(); }

  /// Nearest hit with t in (ray.t_min, min(ray.t_max, hit.t)), skipping the ray's origin
  /// sphere (the caller handles it); updates `hit`.
  bool closest_hit(const Ray& ray, SphereHit& hit) const { return traverse<false>(ray, hit); }

  bool any_hit(const Ray& ray) const {
    SphereHit hit;
    hit.t = ray.t_max;
    return traverse<true>(ray, hit);
  }

  /// Calls visit(id) for every sphere whose bounding box overlaps the box [lower, upper]
  /// (a superset of the spheres that overlap it). For scene building, not for rendering.
  /// `pending` is scratch space: passing the same vector to every query of a loop saves an
  /// allocation per query.
  template <typename Visit>
  void for_each_near_box(const Vec3& lower, const Vec3& upper, Visit&& visit,
                         std::vector<std::uint32_t>& pending) const {
    if (nodes_.empty()) return;
    pending.assign(1, 0);
    while (!pending.empty()) {
      const Node& node = nodes_[pending.back()];
      const std::uint32_t index = pending.back();
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
        const LeafSphere& s = spheres_[i];
        const Vec3 r(s.radius);
        if (glm::all(glm::lessThanEqual(s.center - r, upper)) &&
            glm::all(glm::greaterThanEqual(s.center + r, lower)))
          visit(s.id);
      }
    }
  }

 private:
  struct Node {
    Vec3 lower;
    std::uint32_t offset;  ///< leaf: first sphere; inner: index of the right child
    Vec3 upper;
    std::uint32_t count;  ///< leaf: number of spheres; inner: 0
  };
  static_assert(sizeof(Node) == 32);

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

  /// Four children: inner (count 0; child = wide node index), leaf (count > 0; child = first
  /// sphere) or empty (child = kEmptySlot).
  struct alignas(16) WideNode {
    float lower_x[4], lower_y[4], lower_z[4];
    float upper_x[4], upper_y[4], upper_z[4];
    std::uint32_t child[4];
    std::uint32_t count[4];
  };

  struct LeafSphere {
    Vec3 center;
    float radius;
    std::uint32_t id;
  };

  static constexpr std::uint32_t kMaxLeafSize = 4;
  static constexpr std::uint32_t kEmptySlot = 0xffffffffu;
  static constexpr int kBins = 16;
  static constexpr int kStackSize = 64;

  void build(std::vector<Input> spheres) {
    nodes_.clear();
    spheres_.clear();
    if (spheres.empty()) return;
    nodes_.reserve(2 * spheres.size() / 2 + 1);
    spheres_.reserve(spheres.size());
    build_node(spheres, 0, spheres.size(), 0);
    wide_.clear();
    wide_.reserve(nodes_.size() / 2 + 1);
    collapse(0);
  }

  /// Turns the binary subtree at `binary` into a wide node: its children are the binary
  /// node's, repeatedly replacing the largest inner child by its two children until there
  /// are four (pulling up the largest boxes first keeps the tree's surface area low).
  std::uint32_t collapse(std::uint32_t binary) {
    std::array<std::uint32_t, 4> children{};
    int count = 0;
    if (nodes_[binary].count > 0) {
      children[count++] = binary;  // a tree that is a single leaf
    } else {
      children[count++] = binary + 1;
      children[count++] = nodes_[binary].offset;
      while (count < 4) {
        int widest = -1;
        float widest_area = -1.0f;
        for (int c = 0; c < count; ++c) {
          const Node& n = nodes_[children[std::size_t(c)]];
          const float area = Box{n.lower, n.upper}.half_area();
          if (n.count == 0 && area > widest_area) {
            widest = c;
            widest_area = area;
          }
        }
        if (widest < 0) break;
        const std::uint32_t expanded = children[std::size_t(widest)];
        children[std::size_t(widest)] = expanded + 1;
        children[std::size_t(count++)] = nodes_[expanded].offset;
      }
    }
    const auto index = static_cast<std::uint32_t>(wide_.size());
    wide_.emplace_back();
    for (int c = 0; c < 4; ++c) {
      WideNode& w = wide_[index];
      if (c >= count) {
        w.lower_x[c] = w.lower_y[c] = w.lower_z[c] = std::numeric_limits<float>::max();
        w.upper_x[c] = w.upper_y[c] = w.upper_z[c] = -std::numeric_limits<float>::max();
        w.child[c] = kEmptySlot;
        w.count[c] = 0;
        continue;
      }
      const Node& n = nodes_[children[std::size_t(c)]];
      w.lower_x[c] = n.lower.x;
      w.lower_y[c] = n.lower.y;
      w.lower_z[c] = n.lower.z;
      w.upper_x[c] = n.upper.x;
      w.upper_y[c] = n.upper.y;
      w.upper_z[c] = n.upper.z;
      w.count[c] = n.count;
      w.child[c] = n.count > 0 ? n.offset : 0;
    }
    // Recurse after filling the slots: emplace_back may move wide_.
    for (int c = 0; c < count; ++c) {
      const Node& n = nodes_[children[std::size_t(c)]];
      if (n.count == 0) {
        const std::uint32_t child = collapse(children[std::size_t(c)]);
        wide_[index].child[c] = child;
      }
    }
    return index;
  }

  static Box bounds_of(const Input& s) {
    Box b;
    b.grow(s.center - Vec3(s.radius));
    b.grow(s.center + Vec3(s.radius));
    return b;
  }

  std::uint32_t make_leaf(std::vector<Input>& spheres, std::size_t begin, std::size_t end,
                          const Box& box) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back(Node{box.lower, static_cast<std::uint32_t>(spheres_.size()), box.upper,
                          static_cast<std::uint32_t>(end - begin)});
    for (std::size_t i = begin; i < end; ++i)
      spheres_.push_back(LeafSphere{spheres[i].center, spheres[i].radius, spheres[i].id});
    return index;
  }

  std::uint32_t build_node(std::vector<Input>& spheres, std::size_t begin, std::size_t end,
                           int depth) {
    Box box, centroids;
    for (std::size_t i = begin; i < end; ++i) {
      box.grow(bounds_of(spheres[i]));
      centroids.grow(spheres[i].center);
    }
    const std::size_t count = end - begin;
    // Depth is capped so traversal's fixed stack can never overflow.
    if (count <= kMaxLeafSize || depth >= kStackSize - 2)
      return make_leaf(spheres, begin, end, box);

    // Binned SAH over the widest centroid axis.
    const Vec3 extent = centroids.upper - centroids.lower;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    std::size_t middle = begin + count / 2;
    if (extent[axis] > 0.0f) {
      std::array<Box, kBins> bin_boxes{};
      std::array<std::size_t, kBins> bin_counts{};
      const float scale = kBins / extent[axis];
      const auto bin_of = [&](const Input& s) {
        return std::min(kBins - 1,
                        static_cast<int>((s.center[axis] - centroids.lower[axis]) * scale));
      };
      for (std::size_t i = begin; i < end; ++i) {
        const int b = bin_of(spheres[i]);
        bin_boxes[b].grow(bounds_of(spheres[i]));
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
      float best_cost = std::numeric_limits<float>::max();
      int best_split = -1;
      running = Box{};
      running_count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        running.grow(bin_boxes[b]);
        running_count += bin_counts[b];
        const float cost =
            left_cost[b - 1] + running.half_area() * static_cast<float>(running_count);
        if (cost < best_cost) {
          best_cost = cost;
          best_split = b;
        }
      }
      // Leaf if splitting costs more than testing every sphere (intersection cost ~ 1 box).
      if (count <= 2 * kMaxLeafSize &&
          best_cost >= box.half_area() * (static_cast<float>(count) - 1.0f))
        return make_leaf(spheres, begin, end, box);
      const auto split = std::partition(spheres.begin() + std::ptrdiff_t(begin),
                                        spheres.begin() + std::ptrdiff_t(end),
                                        [&](const Input& s) { return bin_of(s) < best_split; });
      middle = static_cast<std::size_t>(split - spheres.begin());
    }
    if (middle == begin || middle == end) {
      // All centroids in one bin (e.g. concentric spheres): split by count instead.
      middle = begin + count / 2;
      std::nth_element(spheres.begin() + std::ptrdiff_t(begin),
                       spheres.begin() + std::ptrdiff_t(middle),
                       spheres.begin() + std::ptrdiff_t(end), [&](const Input& a, const Input& b) {
                         return a.center[axis] < b.center[axis] ||
                                (a.center[axis] == b.center[axis] && a.id < b.id);
                       });
    }
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back(Node{box.lower, 0, box.upper, 0});
    build_node(spheres, begin, middle, depth + 1);
    nodes_[index].offset = build_node(spheres, middle, end, depth + 1);
    return index;
  }

  /// Entry distances into a wide node's four boxes; +infinity where the ray misses the box
  /// within [t_min, t_max].
  static void enter_boxes(const WideNode& node, const Vec3& origin, const Vec3& inverse_direction,
                          float t_min, float t_max, float (&enter)[4]) {
#if defined(__SSE4_1__)
    const __m128 ox = _mm_set1_ps(origin.x), oy = _mm_set1_ps(origin.y), oz = _mm_set1_ps(origin.z);
    const __m128 ix = _mm_set1_ps(inverse_direction.x), iy = _mm_set1_ps(inverse_direction.y),
                 iz = _mm_set1_ps(inverse_direction.z);
    const __m128 ax = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.lower_x), ox), ix);
    const __m128 bx = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.upper_x), ox), ix);
    const __m128 ay = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.lower_y), oy), iy);
    const __m128 by = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.upper_y), oy), iy);
    const __m128 az = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.lower_z), oz), iz);
    const __m128 bz = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.upper_z), oz), iz);
    const __m128 near = _mm_max_ps(_mm_max_ps(_mm_min_ps(ax, bx), _mm_min_ps(ay, by)),
                                   _mm_max_ps(_mm_min_ps(az, bz), _mm_set1_ps(t_min)));
    const __m128 far = _mm_min_ps(_mm_min_ps(_mm_max_ps(ax, bx), _mm_max_ps(ay, by)),
                                  _mm_min_ps(_mm_max_ps(az, bz), _mm_set1_ps(t_max)));
    _mm_storeu_ps(enter, _mm_blendv_ps(_mm_set1_ps(kInfinity), near, _mm_cmple_ps(near, far)));
#else
    for (int c = 0; c < 4; ++c) {
      const float ax = (node.lower_x[c] - origin.x) * inverse_direction.x;
      const float bx = (node.upper_x[c] - origin.x) * inverse_direction.x;
      const float ay = (node.lower_y[c] - origin.y) * inverse_direction.y;
      const float by = (node.upper_y[c] - origin.y) * inverse_direction.y;
      const float az = (node.lower_z[c] - origin.z) * inverse_direction.z;
      const float bz = (node.upper_z[c] - origin.z) * inverse_direction.z;
      const float near =
          max_of(max_of(min_of(ax, bx), min_of(ay, by)), max_of(min_of(az, bz), t_min));
      const float far =
          min_of(min_of(max_of(ax, bx), max_of(ay, by)), min_of(max_of(az, bz), t_max));
      enter[c] = near <= far ? near : kInfinity;
    }
#endif
  }

  template <bool kAnyHit>
  bool traverse(const Ray& ray, SphereHit& hit) const {
    if (wide_.empty()) return false;
    const Vec3 inverse_direction = 1.0f / ray.direction;
    float best = min_of(ray.t_max, hit.t);
    std::uint32_t best_id = kNoSphere;
    struct Pending {
      std::uint32_t node;
      float enter;
    };
    // Each level pushes at most three siblings; the binary tree's depth is capped, so this
    // bounds the stack.
    std::array<Pending, 3 * kStackSize> stack;
    int top = 0;
    stack[std::size_t(top++)] = Pending{0, ray.t_min};
    while (top > 0) {
      const Pending pending = stack[std::size_t(--top)];
      if (pending.enter > best) continue;
      const WideNode& node = wide_[pending.node];
      float enter[4];
      enter_boxes(node, ray.origin, inverse_direction, ray.t_min, best, enter);
      // Children nearest first (insertion sort of at most four).
      int order[4];
      int hits = 0;
      for (int c = 0; c < 4; ++c) {
        if (enter[c] == kInfinity || node.child[c] == kEmptySlot) continue;
        int k = hits++;
        while (k > 0 && enter[order[k - 1]] > enter[c]) {
          order[k] = order[k - 1];
          --k;
        }
        order[k] = c;
      }
      // Leaves now, nearest first, so that their hits prune the inner children; inner
      // children pushed farthest first, so the nearest is popped next.
      for (int k = 0; k < hits; ++k) {
        const int c = order[k];
        if (node.count[c] == 0 || enter[c] > best) continue;
        for (std::uint32_t i = node.child[c]; i < node.child[c] + node.count[c]; ++i) {
          const LeafSphere& s = spheres_[i];
          if (s.id == ray.origin_sphere) continue;
          SphereRoots roots;
          if (!intersect_sphere(ray.origin, ray.direction, s.center, s.radius, roots)) continue;
          const float t = roots.near > ray.t_min ? roots.near : roots.far;
          if (t > ray.t_min && (t < best || (t == best && s.id < best_id))) {
            best = t;
            best_id = s.id;
            if constexpr (kAnyHit) {
              hit.t = best;
              hit.sphere = best_id;
              return true;
            }
          }
        }
      }
      for (int k = hits - 1; k >= 0; --k) {
        const int c = order[k];
        if (node.count[c] == 0 && enter[c] <= best)
          stack[std::size_t(top++)] = Pending{node.child[c], enter[c]};
      }
    }
    if (best_id == kNoSphere) return false;
    hit.t = best;
    hit.sphere = best_id;
    return true;
  }

  std::vector<Node> nodes_;     // binary tree: building and box queries
  std::vector<WideNode> wide_;  // 4-wide tree: ray traversal
  std::vector<LeafSphere> spheres_;
};

}  // namespace glint
