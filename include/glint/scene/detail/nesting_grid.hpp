#pragma once
// The spatial index of the inclusion tree's fast builder (scene/inclusion_tree.hpp): transparent
// spheres in chains of nested spheres, filed in a hash grid with one level per power of two of
// the radius. It knows geometry only through the predicates its callers pass; what a relation
// means (a container, an overlap) is the builder's business.
//
// Why levels: a sphere q of level L (radius in [2^L, 2^(L+1))) can touch or contain a sphere s no
// larger than itself only if |c_q - c_s| < r_q + r_s <= 2 r_q. Filing q in every cell of side
// 2^(L+3) that meets the box c_q +- 2 r_q (at most 2 per axis, since 4 r_q < 2^(L+3)) puts it in
// the cell of every such centre c_s: a query reads one cell per level.
//
// Why chains: spheres of a cell that are nested inside one another can be many (an onion of
// shells), but disjoint ones cannot: they are at least 2^L in radius and lie within a few cell
// sides. So each cell keeps its spheres as chains, each sphere inside the one before it, and the
// number of chains is the number of pairwise disjoint innermost spheres, bounded by packing. The
// spheres of a chain that contain a given sphere are a prefix of it; its end is found in
// logarithmic time with Myers' jump pointers ("An applicative random-access stack", 1983): each
// node links to its predecessor and to one ancestor further up, chosen so that any ancestor is
// reached in O(log depth) jumps.

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::detail {

/// A cell of one level of the grid.
struct NestingCellKey {
  std::int32_t level, x, y, z;
  bool operator==(const NestingCellKey&) const = default;
};

class NestingGrid {
 public:
  static constexpr std::uint32_t kNone = 0xffffffffu;

  struct Node {
    std::uint32_t sphere;
    std::uint32_t prev;  ///< toward the chain's head (the largest sphere); kNone at the head
    std::uint32_t next;  ///< toward its tail; kNone at the tail
    std::uint32_t jump;  ///< an ancestor (the node itself at the head), for the search
    std::uint32_t depth;
  };
  struct Chain {
    std::uint32_t head, tail;  ///< nodes
  };
  /// A chain as its cell lists it: with its head's geometry inline, so that a query can pass
  /// over the chains far from it reading one contiguous array.
  struct Entry {
    Vec3 head_center;
    float head_radius;
    std::uint32_t chain;
  };
  /// A sphere to be filed, as the grid sees it.
  struct Sphere {
    Vec3 center;
    float radius;
  };

  /// The level of a radius: floor(log2(radius)), exact for any positive finite float.
  static int level_of(float radius) { return std::ilogb(radius); }

  /// Sets up the cells that the spheres will be filed in (each sphere in every cell of its
  /// level that meets the box center +- 2 radius), so that each cell's chains lie in one slice of
  /// one array. False where a cell index would not fit in 31 bits (a level far below the scale
  /// of the coordinates), which the builder leaves to its reference.
  bool prepare(const std::vector<Sphere>& spheres) {
    std::size_t slots = 1024;  // room for about 4 cells per sphere before the table grows
    while (slots < 8 * spheres.size())
      slots *= 2;
    slots_.assign(slots, Slot{});
    std::size_t filings = 0;
    for (const Sphere& s : spheres) {
      const bool ok = for_each_cell_near(s, [&](const NestingCellKey& key) {
        ++cells_[find_or_add(key)].capacity;
        ++filings;
      });
      if (!ok) return false;
    }
    std::uint32_t offset = 0;
    for (Cell& cell : cells_) {
      cell.offset = offset;
      offset += cell.capacity;
    }
    entries_.resize(filings);
    nodes_.reserve(filings);
    chains_.reserve(filings);
    return true;
  }

  /// The cell holding `point` at `level`, kNone if no sphere is filed there (or its index would
  /// not fit, in which case no sphere is filed there either).
  std::uint32_t cell_at(const Vec3& point, int level) const {
    const double side = std::ldexp(1.0, level + 3);
    NestingCellKey key{level, 0, 0, 0};
    std::int32_t* index[3] = {&key.x, &key.y, &key.z};
    for (int axis = 0; axis < 3; ++axis) {
      const std::optional<std::int32_t> i = index_of(double(point[axis]) / side);
      if (!i) return kNone;
      *index[axis] = *i;
    }
    return find(key);
  }

  /// The chains of a cell, filed so far.
  const Entry* begin(std::uint32_t cell) const { return &entries_[cells_[cell].offset]; }
  const Entry* end(std::uint32_t cell) const {
    return &entries_[cells_[cell].offset] + cells_[cell].size;
  }

  /// Calls visit(cell) for every cell sphere `s` is filed in (all set up by prepare).
  template <class Visit>
  void for_each_cell_of(const Sphere& s, Visit&& visit) const {
    for_each_cell_near(s, [&](const NestingCellKey& key) { visit(find(key)); });
  }

  const Chain& chain(std::uint32_t id) const { return chains_[id]; }
  const Node& node(std::uint32_t id) const { return nodes_[id]; }

  /// The deepest node of a chain whose sphere satisfies `contains` (a predicate true on a
  /// prefix of the chain, and true at its head), and the node after it (kNone at the tail).
  template <class Contains>
  std::pair<std::uint32_t, std::uint32_t> deepest(const Chain& c, Contains&& contains) const {
    std::uint32_t x = c.tail;
    if (contains(nodes_[x].sphere)) return {x, kNone};
    // Invariant: x fails; its ancestors from some point up (at least the head) hold.
    for (;;) {
      const Node& n = nodes_[x];
      if (!contains(nodes_[n.jump].sphere)) {
        x = n.jump;  // everything between fails too
        continue;
      }
      if (contains(nodes_[n.prev].sphere)) return {n.prev, x};
      x = n.prev;
    }
  }

  /// Files sphere `id` (geometry `s`) in `cell`: after the tail of chain `after` (a chain of
  /// that cell), or as a new chain of its own if `after` is kNone.
  void append(std::uint32_t cell, std::uint32_t after, std::uint32_t id, const Sphere& s) {
    const auto node = static_cast<std::uint32_t>(nodes_.size());
    if (after != kNone) {
      Chain& c = chains_[after];
      const Node& parent = nodes_[c.tail];
      const Node& jump = nodes_[parent.jump];
      // Myers' rule: jump two equal strides at once where the parent's own jump allows it.
      const bool merge = parent.depth - jump.depth == jump.depth - nodes_[jump.jump].depth;
      nodes_.push_back(Node{id, c.tail, kNone, merge ? jump.jump : c.tail, parent.depth + 1});
      nodes_[c.tail].next = node;
      c.tail = node;
      return;
    }
    nodes_.push_back(Node{id, kNone, kNone, node, 0});
    chains_.push_back(Chain{node, node});
    Cell& c = cells_[cell];
    entries_[c.offset + c.size++] =
        Entry{s.center, s.radius, static_cast<std::uint32_t>(chains_.size() - 1)};
  }

 private:
  struct Cell {
    std::uint32_t offset = 0, capacity = 0, size = 0;
  };
  struct Slot {
    NestingCellKey key;
    std::uint32_t cell = kNone;  ///< kNone: an empty slot
  };

  static std::optional<std::int32_t> index_of(double scaled) {
    const double cell = std::floor(scaled);
    constexpr double kLimit = 1073741824.0;  // 2^30
    if (!(cell > -kLimit && cell < kLimit)) return std::nullopt;
    return static_cast<std::int32_t>(cell);
  }

  /// Calls visit(key) for every cell at the sphere's level that meets the box center +- 2
  /// radius, computed in double precision, whose rounding can only widen the range (4 radius
  /// is less than a side: at most two cells per axis). False, visiting nothing, where an index
  /// would not fit.
  template <class Visit>
  static bool for_each_cell_near(const Sphere& s, Visit&& visit) {
    const int level = level_of(s.radius);
    const double side = std::ldexp(1.0, level + 3);
    std::int32_t lo[3], hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      const auto l = index_of((double(s.center[axis]) - 2.0 * double(s.radius)) / side);
      const auto h = index_of((double(s.center[axis]) + 2.0 * double(s.radius)) / side);
      if (!l || !h) return false;
      lo[axis] = *l;
      hi[axis] = *h;
    }
    for (std::int32_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int32_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int32_t z = lo[2]; z <= hi[2]; ++z)
          visit(NestingCellKey{level, x, y, z});
    return true;
  }

  static std::size_t hash(const NestingCellKey& k) {
    std::uint64_t h = std::uint64_t(std::uint32_t(k.x)) * 0x9E3779B97F4A7C15ull;
    h ^= std::uint64_t(std::uint32_t(k.y)) * 0xC2B2AE3D27D4EB4Full;
    h ^= std::uint64_t(std::uint32_t(k.z)) * 0x165667B19E3779F9ull;
    h ^= std::uint64_t(std::uint32_t(k.level)) * 0x27D4EB2F165667C5ull;
    return static_cast<std::size_t>(h ^ (h >> 29) ^ (h >> 47));
  }

  std::size_t mask() const { return slots_.size() - 1; }

  std::uint32_t find(const NestingCellKey& key) const {
    if (slots_.empty()) return kNone;
    for (std::size_t i = hash(key) & mask();; i = (i + 1) & mask()) {
      const Slot& slot = slots_[i];
      if (slot.cell == kNone || slot.key == key) return slot.cell;
    }
  }

  std::uint32_t find_or_add(const NestingCellKey& key) {
    if (2 * (cells_.size() + 1) > slots_.size()) grow();
    for (std::size_t i = hash(key) & mask();; i = (i + 1) & mask()) {
      Slot& slot = slots_[i];
      if (slot.cell == kNone) {
        slot = Slot{key, static_cast<std::uint32_t>(cells_.size())};
        cells_.emplace_back();
        return slot.cell;
      }
      if (slot.key == key) return slot.cell;
    }
  }

  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(old.empty() ? 1024 : 2 * old.size(), Slot{});
    for (const Slot& slot : old) {
      if (slot.cell == kNone) continue;
      std::size_t i = hash(slot.key) & mask();
      while (slots_[i].cell != kNone)
        i = (i + 1) & mask();
      slots_[i] = slot;
    }
  }

  std::vector<Slot> slots_;
  std::vector<Cell> cells_;
  std::vector<Entry> entries_;  ///< each cell's chains, in its slice
  std::vector<Node> nodes_;
  std::vector<Chain> chains_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::detail
