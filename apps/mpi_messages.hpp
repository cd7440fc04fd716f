#pragma once
// glint-render-mpi's wire format: the point-to-point messages between rank 0 and the others,
// their fields, and their sending (never blocking) and receiving (by polling); and the one
// collective of a render, the sum of the ranks' splats after each pass.

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/tile_grid.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

// Point-to-point messages, all between rank 0 and one other rank.
enum Tag : int {
  kTagWork = 1,  ///< worker -> 0: finished tiles with their sums, and how many more it wants
  kTagAssign,    ///< 0 -> worker: tiles to render, with the sums of those it lacks
  kTagStop,      ///< 0 -> worker: the render is over
  kTagFailed,    ///< worker -> 0: what went wrong there
  kTagSplats,    ///< 0 -> worker: the pass is over, its splats go to rank 0 (sum_splats)
};

/// The longest a rank's main thread sleeps between two looks for messages while its threads
/// finish nothing: how late a request or an answer can be read. A look costs microseconds.
inline constexpr auto kPollInterval = std::chrono::microseconds(250);

/// The samples of a pass: [first, last).
struct PassSamples {
  int first, last;
};

/// Fields appended to a message, in this machine's byte order (all ranks run the same build).
class Packer {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* from = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), from, from + sizeof value);
  }
  void put_sums(const glint::Tile& tile, const glint::PixelSums& sums) {
    for (int y = tile.y0; y < tile.y1; ++y) {
      const auto* row = reinterpret_cast<const char*>(&sums.at(tile.x0, y));
      bytes_.insert(bytes_.end(), row, row + std::size_t(tile.width()) * sizeof(glint::ColorSum));
    }
  }
  std::vector<char> take() { return std::move(bytes_); }

 private:
  std::vector<char> bytes_;
};

/// Reads a message's fields back; a message shorter than its fields is a protocol error.
class Unpacker {
 public:
  explicit Unpacker(const std::vector<char>& bytes)
      : at_(bytes.data()), end_(bytes.data() + bytes.size()) {}
  template <typename T>
  T get() {
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  void get_sums(const glint::Tile& tile, glint::PixelSums& sums) {
    const std::size_t row = std::size_t(tile.width()) * sizeof(glint::ColorSum);
    for (int y = tile.y0; y < tile.y1; ++y)
      std::memcpy(&sums.at(tile.x0, y), take(row), row);
  }
  bool done() const { return at_ == end_; }

 private:
  const char* take(std::size_t size) {
    if (std::size_t(end_ - at_) < size) throw std::runtime_error("a truncated message");
    const char* from = at_;
    at_ += size;
    return from;
  }
  const char* at_;
  const char* end_;
};

/// Adds the splats of every rank to rank 0's and clears the others': called by every rank at
/// once (rank 0 tells the others with kTagSplats), once no thread of its is rendering. Splats
/// land on any pixel, so each rank holds those its own paths made; they are integers
/// (image/splat_sums.hpp), whose sum is the same whatever the ranks and the order of the
/// reduction. In slices, for MPI's int counts.
inline void sum_splats(int rank, glint::SplatSums& splats) {
  std::vector<std::int64_t>& words = splats.words();
  constexpr std::size_t kSlice = std::size_t(1) << 24;  // words: 128 MiB
  for (std::size_t at = 0; at < words.size(); at += kSlice) {
    const int count = int(std::min(kSlice, words.size() - at));
    std::int64_t* slice = words.data() + at;
    MPI_Reduce(rank == 0 ? MPI_IN_PLACE : slice, slice, count, MPI_INT64_T, MPI_SUM, 0,
               MPI_COMM_WORLD);
  }
  if (rank != 0) std::fill(words.begin(), words.end(), std::int64_t(0));
}

struct Message {
  int source = 0;
  int tag = 0;
  std::vector<char> bytes;
};

/// The next message that has arrived, if any.
inline std::optional<Message> poll() {
  int arrived = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
  if (!arrived) return std::nullopt;
  int size = 0;
  MPI_Get_count(&status, MPI_BYTE, &size);
  Message message{status.MPI_SOURCE, status.MPI_TAG, std::vector<char>(std::size_t(size))};
  MPI_Recv(message.bytes.data(), size, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return message;
}

/// Messages being sent, kept until MPI is done with them. Never a blocking send: two ranks
/// sending each other large messages at once would both wait for the other to receive.
class Outbox {
 public:
  void send(int to, Tag tag, std::vector<char> bytes) {
    bytes_ += bytes.size();
    ++messages_;
    pending_.push_back({MPI_REQUEST_NULL, std::move(bytes)});
    Pending& p = pending_.back();
    MPI_Isend(p.bytes.data(), int(p.bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD, &p.request);
  }
  /// Lets MPI move the messages on, and forgets those sent.
  void progress() {
    std::erase_if(pending_, [](Pending& p) {
      int done = 0;
      MPI_Test(&p.request, &done, MPI_STATUS_IGNORE);
      return done != 0;
    });
  }
  void flush() {
    for (Pending& p : pending_)
      MPI_Wait(&p.request, MPI_STATUS_IGNORE);
    pending_.clear();
  }
  std::uint64_t bytes() const { return bytes_; }
  std::uint64_t messages() const { return messages_; }

 private:
  // A vector's buffer stays where it is when the vector is moved: MPI keeps its address.
  struct Pending {
    MPI_Request request;
    std::vector<char> bytes;
  };
  std::vector<Pending> pending_;
  std::uint64_t bytes_ = 0;
  std::uint64_t messages_ = 0;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
