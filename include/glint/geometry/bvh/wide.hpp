#pragma once
// Collapsing the binary tree into a kWideWidth-wide one for traversal: each wide node holds its
// children's boxes in structure-of-arrays form, so that one SIMD pass tests them all.

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "glint/geometry/bvh/build.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::bvh {

/// Children per wide node: eight, tested at once by one AVX2 pass (two SSE passes, or a loop,
/// without it). Fewer levels than a 4-wide tree, so fewer dependent node loads per ray.
inline constexpr int kWideWidth = 8;

/// kWideWidth child slots, each an inner node (count 0; child = index of its wide node), a leaf
/// (count > 0; child = its first sphere) or empty (child = kEmptySlot). Aligned to cache lines:
/// a node is four lines, never five.
struct alignas(64) WideNode {
  float lower_x[kWideWidth], lower_y[kWideWidth], lower_z[kWideWidth];
  float upper_x[kWideWidth], upper_y[kWideWidth], upper_z[kWideWidth];
  std::uint32_t child[kWideWidth];
  std::uint32_t count[kWideWidth];
};

inline constexpr std::uint32_t kEmptySlot = 0xffffffffu;

namespace detail {

/// The binary nodes that become the children of one wide node.
struct WideChildren {
  std::array<std::uint32_t, kWideWidth> node{};
  int count = 0;
};

/// The children of binary node `root` as a wide node: its two children, then repeatedly the
/// inner child of largest area replaced by its own two, until there are kWideWidth or only
/// leaves.
/// Pulling the largest boxes up keeps the wide tree's surface area low.
inline WideChildren gather_children(const std::vector<Node>& nodes, std::uint32_t root) {
  WideChildren children;
  if (nodes[root].count > 0) {  // a tree that is a single leaf
    children.node[std::size_t(children.count++)] = root;
    return children;
  }
  children.node[std::size_t(children.count++)] = root + 1;
  children.node[std::size_t(children.count++)] = nodes[root].offset;
  while (children.count < kWideWidth) {
    int widest = -1;
    float widest_area = -1.0f;
    for (int c = 0; c < children.count; ++c) {
      const Node& n = nodes[children.node[std::size_t(c)]];
      const float area = Box{n.lower, n.upper}.half_area();
      if (n.count == 0 && area > widest_area) {
        widest = c;
        widest_area = area;
      }
    }
    if (widest < 0) break;
    const std::uint32_t expanded = children.node[std::size_t(widest)];
    children.node[std::size_t(widest)] = expanded + 1;
    children.node[std::size_t(children.count++)] = nodes[expanded].offset;
  }
  return children;
}

/// Slot `c` of `wide` for binary node `n`; an inner node's wide index is filled in later.
inline void set_slot(WideNode& wide, int c, const Node& n) {
  wide.lower_x[c] = n.lower.x;
  wide.lower_y[c] = n.lower.y;
  wide.lower_z[c] = n.lower.z;
  wide.upper_x[c] = n.upper.x;
  wide.upper_y[c] = n.upper.y;
  wide.upper_z[c] = n.upper.z;
  wide.count[c] = n.count;
  wide.child[c] = n.count > 0 ? n.offset : 0;
}

/// An empty slot: an inverted box, which no ray enters.
inline void set_empty_slot(WideNode& wide, int c) {
  wide.lower_x[c] = wide.lower_y[c] = wide.lower_z[c] = std::numeric_limits<float>::max();
  wide.upper_x[c] = wide.upper_y[c] = wide.upper_z[c] = -std::numeric_limits<float>::max();
  wide.child[c] = kEmptySlot;
  wide.count[c] = 0;
}

/// Appends the wide node for binary node `root`, then those of its inner children (depth
/// first); returns its index.
inline std::uint32_t collapse(const std::vector<Node>& nodes, std::uint32_t root,
                              std::vector<WideNode>& wide) {
  const WideChildren children = gather_children(nodes, root);
  const auto index = static_cast<std::uint32_t>(wide.size());
  WideNode& node = wide.emplace_back();
  for (int c = 0; c < kWideWidth; ++c) {
    if (c < children.count)
      set_slot(node, c, nodes[children.node[std::size_t(c)]]);
    else
      set_empty_slot(node, c);
  }
  // `node` dangles from here: collapsing a child may move `wide`.
  for (int c = 0; c < children.count; ++c) {
    const std::uint32_t child = children.node[std::size_t(c)];
    if (nodes[child].count == 0) {
      const std::uint32_t child_index = collapse(nodes, child, wide);
      wide[index].child[c] = child_index;
    }
  }
  return index;
}

}  // namespace detail

/// The wide tree of a binary tree, the root first; empty for an empty tree.
inline std::vector<WideNode> collapse_to_wide(const std::vector<Node>& nodes) {
  std::vector<WideNode> wide;
  if (nodes.empty()) return wide;
  wide.reserve(nodes.size() / (kWideWidth - 1) + 1);
  detail::collapse(nodes, 0, wide);
  return wide;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::bvh
