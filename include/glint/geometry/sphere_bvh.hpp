#pragma once
// A bounding volume hierarchy over spheres, for scenes too large for a linear SIMD scan.
// Built top-down with a binned surface-area heuristic; nodes are 32 bytes, depth-first, the
// left child right after its parent; leaf spheres are stored contiguously in traversal order
// so a leaf is one short linear scan. Traversal visits the nearer child first and skips any
// subtree whose box starts beyond the closest hit found so far.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include <glm/vector_relational.hpp>

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
  template <typename Visit>
  void for_each_near_box(const Vec3& lower, const Vec3& upper, Visit&& visit) const {
    if (nodes_.empty()) return;
    std::vector<std::uint32_t> pending{0};
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

  struct LeafSphere {
    Vec3 center;
    float radius;
    std::uint32_t id;
  };

  static constexpr std::uint32_t kMaxLeafSize = 4;
  static constexpr int kBins = 16;
  static constexpr int kStackSize = 64;

  void build(std::vector<Input> spheres) {
    nodes_.clear();
    spheres_.clear();
    if (spheres.empty()) return;
    nodes_.reserve(2 * spheres.size() / 2 + 1);
    spheres_.reserve(spheres.size());
    build_node(spheres, 0, spheres.size(), 0);
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

  /// Entry distance of the ray into a node's box, or +infinity if it misses within [t_min, t_max].
  [[gnu::always_inline]] static float enter_box(const Node& node, const Vec3& origin,
                                                const Vec3& inverse_direction, float t_min,
                                                float t_max) {
    const Vec3 t0 = (node.lower - origin) * inverse_direction;
    const Vec3 t1 = (node.upper - origin) * inverse_direction;
    const Vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
    const float enter = max_of(max_of(near.x, near.y), max_of(near.z, t_min));
    const float leave = min_of(min_of(far.x, far.y), min_of(far.z, t_max));
    return enter <= leave ? enter : kInfinity;
  }

  template <bool kAnyHit>
  bool traverse(const Ray& ray, SphereHit& hit) const {
    if (nodes_.empty()) return false;
    const Vec3 inverse_direction = 1.0f / ray.direction;
    float best = min_of(ray.t_max, hit.t);
    std::uint32_t best_id = kNoSphere;
    struct Pending {
      std::uint32_t node;
      float enter;
    };
    std::array<Pending, kStackSize> stack;
    int top = 0;
    std::uint32_t current = 0;
    if (enter_box(nodes_[0], ray.origin, inverse_direction, ray.t_min, best) == kInfinity)
      return false;
    for (;;) {
      const Node& node = nodes_[current];
      if (node.count > 0) {
        for (std::uint32_t i = node.offset; i < node.offset + node.count; ++i) {
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
      } else {
        const std::uint32_t left = current + 1, right = node.offset;
        const float t_left =
            enter_box(nodes_[left], ray.origin, inverse_direction, ray.t_min, best);
        const float t_right =
            enter_box(nodes_[right], ray.origin, inverse_direction, ray.t_min, best);
        if (t_left != kInfinity || t_right != kInfinity) {
          if (t_left == kInfinity) {
            current = right;
          } else if (t_right == kInfinity) {
            current = left;
          } else {
            const bool left_first = t_left <= t_right;
            current = left_first ? left : right;
            stack[std::size_t(top++)] =
                left_first ? Pending{right, t_right} : Pending{left, t_left};
          }
          continue;
        }
      }
      // Pop the next subtree that can still hold something nearer than the best hit.
      while (top > 0 && stack[std::size_t(top - 1)].enter > best)
        --top;
      if (top == 0) break;
      current = stack[std::size_t(--top)].node;
    }
    if (best_id == kNoSphere) return false;
    hit.t = best;
    hit.sphere = best_id;
    return true;
  }

  std::vector<Node> nodes_;
  std::vector<LeafSphere> spheres_;
};

}  // namespace glint
