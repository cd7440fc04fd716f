#pragma once
// The merge candidates of one iteration of vertex connection and merging
// (render/bidirectional_execution.hpp): the vertices of every pixel's light subpath at which its
// light may be merged with a camera path's, each as a candidate that holds what a merge needs
// (MergeCandidate), in a hash grid, so that a query reads the grid alone. The subpaths themselves
// are not kept: a camera subpath joined to its own pixel's light subpath traces it again from
// the same sample values.
//
// The grid is filled in chunks of consecutive paths, each chunk by one thread into storage of
// its own, so what a chunk holds depends on its paths' indices only. The grid is a counting sort
// of the candidates by cell, in path and vertex order, and a query visits its cells in a fixed
// order: the candidates a camera vertex meets, and the order in which their light is added,
// depend on the scene, the settings and the seed, never on the threads.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The merge candidates, of type Candidate (MergeCandidate: with a `point`), of one light subpath
/// per path index.
template <typename Candidate>
class MergeGrid {
 public:
  /// Paths per chunk: enough to keep a thread busy between its claims, few enough to share a
  /// pass of a small image among threads.
  static constexpr std::size_t kChunkPaths = 512;

  explicit MergeGrid(std::size_t paths)
      : paths_(paths), chunks_((paths + kChunkPaths - 1) / kChunkPaths) {}

  std::size_t path_count() const { return paths_; }
  std::size_t chunk_count() const { return chunks_.size(); }

  /// Refills chunk `chunk` with its paths' candidates: trace(path index, candidates) appends
  /// them to `candidates` in vertex order.
  template <typename Trace>
  void fill_chunk(std::size_t chunk, Trace&& trace) {
    std::vector<Candidate>& candidates = chunks_[chunk];
    candidates.clear();
    const std::size_t first = chunk * kChunkPaths;
    const std::size_t last = std::min(first + kChunkPaths, paths_);
    for (std::size_t path = first; path < last; ++path)
      trace(path, candidates);
  }

  /// The merge candidates in the grid, for what a pass of light paths costs in memory.
  std::size_t candidate_count() const { return sorted_.size(); }

  /// Indexes the chunks' merge candidates for queries of radius `radius`, and releases the
  /// chunks' copies. A counting sort by bucket written straight into the grid: one pass counts
  /// each bucket's candidates, one places them, each bucket's in path and vertex order.
  void build_grid(float radius) {
    radius_ = radius;
    inverse_cell_ = 1.0 / (2.0 * double(radius));
    std::size_t count = 0;
    for (const std::vector<Candidate>& c : chunks_)
      count += c.size();
    const std::size_t buckets = std::bit_ceil(std::max<std::size_t>(1, 2 * count));
    mask_ = buckets - 1;
    // Bucket b's count at b + 2; after the running sum, bucket_starts_[b + 1] is where bucket b
    // begins, the cursor its entries advance, which leaves it where bucket b ends: bucket b is
    // then [bucket_starts_[b], bucket_starts_[b + 1]).
    bucket_starts_.assign(buckets + 2, 0);
    for (const std::vector<Candidate>& c : chunks_)
      for (const Candidate& candidate : c)
        ++bucket_starts_[bucket(cell(candidate.point, 0.0)) + 2];
    for (std::size_t b = 2; b < bucket_starts_.size(); ++b)
      bucket_starts_[b] += bucket_starts_[b - 1];
    sorted_.resize(count);
    for (std::vector<Candidate>& c : chunks_) {
      for (const Candidate& candidate : c)
        sorted_[bucket_starts_[bucket(cell(candidate.point, 0.0)) + 1]++] = candidate;
      std::vector<Candidate>().swap(c);
    }
  }

  /// Calls visit(candidate) for each indexed candidate within the radius of `point` (strictly),
  /// in an order fixed by the grid.
  template <typename Visit>
  void for_each_near(const Vec3& point, Visit&& visit) const {
    // The cells are twice the radius wide: the ball around `point` meets two of them along each
    // axis, from the one holding point - radius.
    const std::array<std::int64_t, 3> base = cell(point, -0.5);
    std::array<std::size_t, 8> visited{};
    std::size_t count = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const std::size_t b = bucket(
          {base[0] + (corner & 1), base[1] + ((corner >> 1) & 1), base[2] + ((corner >> 2) & 1)});
      // Two cells may share a bucket: each bucket is visited once.
      if (std::find(visited.begin(), visited.begin() + std::ptrdiff_t(count), b) !=
          visited.begin() + std::ptrdiff_t(count))
        continue;
      visited[count++] = b;
      const float radius2 = radius_ * radius_;
      for (std::uint32_t e = bucket_starts_[b]; e < bucket_starts_[b + 1]; ++e) {
        const Vec3 offset = sorted_[e].point - point;
        if (glm::dot(offset, offset) < radius2) visit(sorted_[e]);
      }
    }
  }

 private:
  /// The cell holding `point` shifted by `shift` cells along each axis.
  std::array<std::int64_t, 3> cell(const Vec3& point, double shift) const {
    return {std::int64_t(std::floor(double(point.x) * inverse_cell_ + shift)),
            std::int64_t(std::floor(double(point.y) * inverse_cell_ + shift)),
            std::int64_t(std::floor(double(point.z) * inverse_cell_ + shift))};
  }

  std::size_t bucket(const std::array<std::int64_t, 3>& c) const {
    const std::uint64_t h = std::uint64_t(c[0]) * 0x9e3779b97f4a7c15ull ^
                            std::uint64_t(c[1]) * 0xc2b2ae3d27d4eb4full ^
                            std::uint64_t(c[2]) * 0x165667b19e3779f9ull;
    return std::size_t((h ^ (h >> 29)) & mask_);
  }

  std::size_t paths_;
  std::vector<std::vector<Candidate>> chunks_;  ///< until build_grid, in path and vertex order
  float radius_ = 0.0f;
  double inverse_cell_ = 0.0;
  std::size_t mask_ = 0;
  std::vector<Candidate> sorted_;
  std::vector<std::uint32_t> bucket_starts_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
