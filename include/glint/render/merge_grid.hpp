#pragma once
// The merge candidates of one iteration of vertex connection and merging
// (render/bidirectional_execution.hpp): the vertices of every pixel's light subpath at which its
// light may be merged with a camera path's, each as a candidate that holds what a merge needs
// (MergeCandidate), in a hash grid, so that a query reads the grid alone. The subpaths themselves
// are not kept: a camera subpath joined to its own pixel's light subpath traces it again from
// the same sample values.
//
// The grid is filled in chunks of consecutive paths, each chunk by one thread into storage of
// its own, so what a chunk holds depends on its paths' indices only. The chunks are then moved
// into one array in chunk order, each released as it is moved (their pages go back to the system
// at once: detail::PageAllocator), and sorted there by bucket in place: the candidates are held
// once, not twice. The order within a bucket follows from the array's, and a query visits its
// cells in a fixed order: the candidates a camera vertex meets, and the order in which their
// light is added, depend on the scene, the settings and the seed, never on the threads.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "glint/detail/page_allocator.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The merge candidates, of type Candidate (MergeCandidate: with a `point`), of one light subpath
/// per path index.
template <typename Candidate>
class MergeGrid {
 public:
  /// Paths per chunk at least: enough to keep a thread busy between its claims, few enough to
  /// share a pass of a small image among threads.
  static constexpr std::size_t kChunkPaths = 512;
  /// Chunks at most, each its own mapping of pages (a large image has larger chunks): far below
  /// the system's limit on mappings. The candidates' order does not depend on the chunks.
  static constexpr std::size_t kMaxChunks = 1024;

  explicit MergeGrid(std::size_t paths)
      : paths_(paths),
        chunk_paths_(std::max(kChunkPaths, (paths + kMaxChunks - 1) / kMaxChunks)),
        chunks_((paths + chunk_paths_ - 1) / chunk_paths_) {}

  std::size_t path_count() const { return paths_; }
  std::size_t chunk_count() const { return chunks_.size(); }

  using Candidates = std::vector<Candidate, detail::PageAllocator<Candidate>>;

  /// A grid up to this size keeps its array from pass to pass: holding it beside the next
  /// pass's chunks costs little, and mapping it again would cost its page faults each pass.
  static constexpr std::size_t kKeptBytes = std::size_t(64) << 20;

  /// Releases the candidates of the last pass, before the chunks of the next are filled (a small
  /// grid keeps its storage).
  void clear() {
    if (sorted_.capacity() * sizeof(Candidate) > kKeptBytes) {
      Candidates().swap(sorted_);
      BucketStarts().swap(bucket_starts_);
    } else {
      sorted_.clear();
    }
  }

  /// Refills chunk `chunk` with its paths' candidates: trace(path index, candidates) appends
  /// them to `candidates` in vertex order.
  template <typename Trace>
  void fill_chunk(std::size_t chunk, Trace&& trace) {
    Candidates& candidates = chunks_[chunk];
    candidates.clear();
    // A few candidates per path without growing: each growth maps new pages.
    candidates.reserve(4 * chunk_paths_);
    const std::size_t first = chunk * chunk_paths_;
    const std::size_t last = std::min(first + chunk_paths_, paths_);
    for (std::size_t path = first; path < last; ++path)
      trace(path, candidates);
  }

  /// The merge candidates in the grid, for what a pass of light paths costs in memory.
  std::size_t candidate_count() const { return sorted_.size(); }

  /// Indexes the chunks' merge candidates for queries of radius `radius`: moves them into one
  /// array in chunk order, releasing each chunk as it goes, then sorts that array by bucket in
  /// place (an American flag sort: each candidate swapped straight to the next free place of its
  /// own range), in two levels so that the swaps stay near each other: first into 256 parts of
  /// consecutive buckets (256 places written in order, through the cache), then each part,
  /// small enough to stay in the cache, into its buckets.
  void build_grid(float radius) {
    radius_ = radius;
    inverse_cell_ = 1.0 / (2.0 * double(radius));
    std::size_t count = 0;
    for (const Candidates& c : chunks_)
      count += c.size();
    clear();
    sorted_.reserve(count);
    for (Candidates& c : chunks_) {
      sorted_.insert(sorted_.end(), c.begin(), c.end());
      Candidates().swap(c);
    }
    // About one bucket per candidate: a query meets few candidates of other cells.
    const std::size_t buckets = std::bit_ceil(std::max<std::size_t>(1, count));
    mask_ = buckets - 1;
    // Bucket b's count at b + 1; after the running sum, bucket b is
    // [bucket_starts_[b], bucket_starts_[b + 1]).
    bucket_starts_.assign(buckets + 1, 0);
    for (const Candidate& candidate : sorted_)
      ++bucket_starts_[bucket_of(candidate) + 1];
    for (std::size_t b = 1; b < bucket_starts_.size(); ++b)
      bucket_starts_[b] += bucket_starts_[b - 1];
    // Parts of 2^shift consecutive buckets: 256 of them, or one bucket each in a smaller grid.
    const int bits = std::countr_zero(buckets);
    const int shift = std::max(0, bits - kPartBits);
    const std::size_t parts = buckets >> shift;
    sort_into(
        parts, [&](std::size_t part) { return bucket_starts_[part << shift]; },
        [&](const Candidate& c) { return bucket_of(c) >> shift; });
    if (shift == 0) return;
    for (std::size_t part = 0; part < parts; ++part) {
      const std::size_t first = part << shift;
      sort_into(
          std::size_t(1) << shift, [&](std::size_t b) { return bucket_starts_[first + b]; },
          [&](const Candidate& c) { return bucket_of(c) - first; });
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

  std::size_t bucket_of(const Candidate& candidate) const {
    return bucket(cell(candidate.point, 0.0));
  }

  /// The parts of the first level of build_grid's sort: 2^kPartBits.
  static constexpr int kPartBits = 8;

  /// Sorts the candidates from start(0) to start(ranges) in place into `ranges` ranges, range r
  /// being [start(r), start(r + 1)) and holding the candidates c with range(c) == r (each one's
  /// place counted beforehand).
  template <typename Start, typename Range>
  void sort_into(std::size_t ranges, const Start& start, const Range& range) {
    next_.resize(ranges);
    for (std::size_t r = 0; r < ranges; ++r)
      next_[r] = start(r);
    for (std::size_t r = 0; r < ranges; ++r) {
      const std::uint32_t end = start(r + 1);
      while (next_[r] < end) {
        const std::size_t home = range(sorted_[next_[r]]);
        if (home == r)
          ++next_[r];
        else
          std::swap(sorted_[next_[r]], sorted_[next_[home]++]);
      }
    }
  }

  std::size_t bucket(const std::array<std::int64_t, 3>& c) const {
    const std::uint64_t h = std::uint64_t(c[0]) * 0x9e3779b97f4a7c15ull ^
                            std::uint64_t(c[1]) * 0xc2b2ae3d27d4eb4full ^
                            std::uint64_t(c[2]) * 0x165667b19e3779f9ull;
    return std::size_t((h ^ (h >> 29)) & mask_);
  }

  std::size_t paths_;
  std::size_t chunk_paths_;
  std::vector<Candidates> chunks_;  ///< until build_grid, in path and vertex order
  float radius_ = 0.0f;
  double inverse_cell_ = 0.0;
  std::size_t mask_ = 0;
  Candidates sorted_;
  /// Where each bucket begins in sorted_, read at random by every query as sorted_ is.
  using BucketStarts = std::vector<std::uint32_t, detail::PageAllocator<std::uint32_t>>;
  BucketStarts bucket_starts_;
  std::vector<std::uint32_t> next_;  ///< build_grid's next free place of each range
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
