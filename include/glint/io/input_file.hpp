#pragma once
// Reading a file whose content nobody vouches for: its header may claim more than the file
// holds, it may be binary where text is expected, or a device or a pipe that never ends
// (/dev/zero, /dev/urandom, a FIFO). glint's readers (PFM, EXR, checkpoints, scenes) open their
// files through InputFile, so that they
//   - learn the size of a regular file before they allocate what a header claims, and compare;
//   - read a header a byte at a time, up to a bound, instead of parsing an unbounded stream;
//   - take the data of a pipe or a device only as it arrives, up to what the header claimed,
//     so that one that ends early costs only what it held.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "glint/error.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A file opened for reading untrusted content. Every failure, from opening to reading, calls
/// the reader's `fail` with the problem ("it is a directory", "No such file or directory"):
/// a function that throws the reader's own error, naming the file.
class InputFile {
 public:
  using Fail = std::function<void(const std::string& problem)>;

  /// Opens `path` for reading (blocking, as any program does, until a FIFO has a writer).
  InputFile(const std::filesystem::path& path, Fail fail) : fail_(std::move(fail)) {
    do {
      fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    } while (fd_ < 0 && errno == EINTR);
    if (fd_ < 0) this->fail(std::strerror(errno));
    struct stat status {};
    if (::fstat(fd_, &status) != 0) this->fail(std::strerror(errno));
    if (S_ISDIR(status.st_mode)) this->fail("it is a directory");
    if (S_ISREG(status.st_mode)) size_ = std::uint64_t(status.st_size);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  ~InputFile() {
    if (fd_ >= 0) ::close(fd_);
  }

  /// The size in bytes of a regular file; empty for a pipe, a device or a socket, whose size
  /// is known only once they end (if they do).
  const std::optional<std::uint64_t>& size() const { return size_; }

  /// Bytes taken from the file so far (by get, read and append).
  std::uint64_t position() const { return position_; }

  /// Bytes of a regular file after those taken; empty when the size is unknown.
  std::optional<std::uint64_t> remaining() const {
    if (!size_) return std::nullopt;
    return *size_ > position_ ? *size_ - position_ : 0;
  }

  /// The next byte (0 to 255), or -1 at the end of the file.
  int get() {
    if (next_ == end_ && !refill()) return -1;
    ++position_;
    return static_cast<unsigned char>(buffer_[next_++]);
  }

  /// Reads `count` bytes into `to`; returns how many were read, fewer only at the end.
  std::size_t read(char* to, std::size_t count) {
    std::size_t done = 0;
    while (done < count) {
      if (next_ == end_ && !refill()) break;
      const std::size_t take = std::min(count - done, end_ - next_);
      std::memcpy(to + done, buffer_.data() + next_, take);
      next_ += take;
      done += take;
    }
    position_ += done;
    return done;
  }

  /// Appends `count` bytes to `to`, growing it a chunk at a time as the bytes arrive, so that
  /// a file that ends early costs no more memory than it held. Returns false, with what there
  /// was appended, when the file ends first.
  bool append(std::vector<char>& to, std::uint64_t count) {
    constexpr std::size_t kChunk = std::size_t{1} << 20;
    if (const std::optional<std::uint64_t> left = remaining(); left && *left >= count)
      to.reserve(to.size() + std::size_t(count));  // it is there: one allocation
    while (count > 0) {
      const std::size_t want = std::size_t(std::min<std::uint64_t>(count, kChunk));
      const std::size_t before = to.size();
      to.resize(before + want);
      const std::size_t got = read(to.data() + before, want);
      to.resize(before + got);
      if (got < want) return false;
      count -= got;
    }
    return true;
  }

  /// True when no byte is left (for a pipe or a device, after trying to read one more).
  bool at_end() {
    if (next_ != end_) return false;
    return !refill();
  }

  /// Calls the reader's fail with `problem`; it throws.
  [[noreturn]] void fail(const std::string& problem) const {
    fail_(problem);
    throw Error(problem);  // a fail that returns is a reader's mistake
  }

 private:
  bool refill() {
    for (;;) {
      const ssize_t got = ::read(fd_, buffer_.data(), buffer_.size());
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) fail(std::string("read error: ") + std::strerror(errno));
      next_ = 0;
      end_ = std::size_t(got);
      return got > 0;
    }
  }

  Fail fail_;
  int fd_ = -1;
  std::optional<std::uint64_t> size_;
  std::uint64_t position_ = 0;
  std::vector<char> buffer_ = std::vector<char>(std::size_t{1} << 16);
  std::size_t next_ = 0, end_ = 0;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
