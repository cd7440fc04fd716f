#pragma once
// Writing a Film: 8-bit sRGB PNG (through Debian's libstb), tone-mapped, and linear float PFM.
//
// Every file is written to a temporary file beside its target and renamed into place, so a
// failed write never leaves a truncated image behind. The temporary's name is unpredictable
// and it is created with O_EXCL and O_NOFOLLOW: it is always a new file, never one that was
// already there, and a symbolic link planted beside the target is never followed. write_files
// renames several files into place only once all of them have been written; a program that
// must also clean up from a signal handler (glint-render) uses StagedFile directly.

#include <fcntl.h>
#include <stb_image_write.h>
#include <unistd.h>
#include <climits>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "glint/error.hpp"
#include "glint/image/film.hpp"
#include "glint/image/tone_map.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The sRGB transfer function (IEC 61966-2-1) from linear [0,1] to an 8-bit code value.
inline std::uint8_t linear_to_srgb8(float linear) {
  if (!(linear > 0.0f)) return 0;  // also maps NaN to black
  if (linear >= 1.0f) return 255;
  const float encoded =
      linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(encoded * 255.0f));
}

/// A file written under a temporary name beside `target`, then renamed over it by commit().
/// Until then the target is untouched, and the destructor removes the temporary.
class StagedFile {
 public:
  /// How a temporary's name ends, after TARGET and a dot and 12 random hex digits.
  static constexpr const char* kTemporaryEnd = ".glint-partial";
  static constexpr std::size_t kTemporarySuffixSize = 1 + 12 + 14;

  /// The part of a temporary's name that comes from `target`: its file name, shortened so that
  /// the whole name fits in 255 bytes (the random part is never shortened).
  static std::string temporary_prefix(const std::filesystem::path& target) {
    return target.filename().string().substr(0, 255 - kTemporarySuffixSize);
  }

  /// True when `name` (a file name) is that of a temporary of `target`.
  static bool is_temporary_of(const std::filesystem::path& target, std::string_view name) {
    const std::string prefix = temporary_prefix(target);
    if (name.size() != prefix.size() + kTemporarySuffixSize || !name.starts_with(prefix) ||
        !name.ends_with(kTemporaryEnd) || name[prefix.size()] != '.')
      return false;
    for (const char c : name.substr(prefix.size() + 1, 12))
      if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
    return true;
  }

  /// Creates the temporary, TARGET.XXXXXXXXXXXX.glint-partial with random hex digits, as a
  /// new file (mode 0666 less the umask, as any new file). Throws ImageWriteError.
  explicit StagedFile(std::filesystem::path target) : target_(std::move(target)) {
    if (target_.filename().empty()) fail("the name is a directory");
    std::random_device random;
    for (int attempt = 0; attempt < 32; ++attempt) {
      temporary_ = temporary_name(target_, std::uint64_t(random()) << 32 | random());
      fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
      if (fd_ >= 0) return;
      if (errno != EEXIST) fail(std::strerror(errno));
    }
    fail("no unused temporary file name");
  }
  StagedFile(StagedFile&& other) noexcept
      : target_(std::move(other.target_)),
        temporary_(std::move(other.temporary_)),
        fd_(std::exchange(other.fd_, -1)),
        state_(std::exchange(other.state_, State::moved)) {}
  StagedFile& operator=(StagedFile&&) = delete;
  ~StagedFile() {
    if (fd_ >= 0) ::close(fd_);
    if (state_ != State::committed && state_ != State::moved) ::unlink(temporary_.c_str());
  }

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporary() const { return temporary_; }

  /// Writes the whole content and finishes the file (finish()). On failure removes the
  /// temporary and throws ImageWriteError.
  void write(const std::vector<char>& bytes) {
    append(bytes.data(), bytes.size());
    finish();
  }

  /// Writes the next `size` bytes of the content: a large file written piece by piece is never
  /// held whole in memory. On failure removes the temporary and throws ImageWriteError.
  void append(const char* data, std::size_t size) {
    if (state_ != State::open) fail("the file is no longer open");
    while (size > 0) {
      const ssize_t written = ::write(fd_, data, std::min<std::size_t>(size, 1 << 30));
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) discard_and_fail(written < 0 ? std::strerror(errno) : "write failed");
      data += written;
      size -= std::size_t(written);
    }
  }

  /// Flushes the content to the disk (so that a crash after the rename cannot leave an empty
  /// file) and closes it. On failure removes the temporary and throws ImageWriteError.
  void finish() {
    if (state_ != State::open) fail("the file is no longer open");
    if (::fsync(fd_) != 0) discard_and_fail(std::strerror(errno));
    const int closed = ::close(std::exchange(fd_, -1));
    if (closed != 0) discard_and_fail(std::strerror(errno));
    state_ = State::written;
  }

  /// Renames the written temporary over the target (replacing a file or a symbolic link
  /// there, never writing through it). Throws ImageWriteError, removing the temporary.
  void commit() {
    if (state_ != State::written) fail("nothing was written");
    if (::rename(temporary_.c_str(), target_.c_str()) != 0) discard_and_fail(std::strerror(errno));
    state_ = State::committed;
  }

 private:
  enum class State { open, written, committed, discarded, moved };

  static std::filesystem::path temporary_name(const std::filesystem::path& target,
                                              std::uint64_t random) {
    char suffix[40];
    std::snprintf(suffix, sizeof suffix, ".%012llx%s",
                  static_cast<unsigned long long>(random & 0xffffffffffffULL), kTemporaryEnd);
    return target.parent_path() / (temporary_prefix(target) + suffix);
  }

  [[noreturn]] void fail(const std::string& why) const {
    throw ImageWriteError("cannot write " + target_.string() + ": " + why);
  }
  [[noreturn]] void discard_and_fail(const std::string& why) {
    if (fd_ >= 0) ::close(std::exchange(fd_, -1));
    ::unlink(temporary_.c_str());
    state_ = State::discarded;
    fail(why);
  }

  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  State state_ = State::open;
};

/// Removes the temporaries of `target` that a StagedFile made and never renamed or removed:
/// what a process killed outright (SIGKILL, a crash, a power cut) while writing left behind.
/// Only regular files named as StagedFile names them (TARGET.<12 hex digits>.glint-partial) go;
/// a symbolic link or a directory of that name stays, and no link is followed. Returns how many
/// were removed. A program calls it for its outputs before it writes them; a temporary of another
/// process writing the same target at that moment would go too, and that write then fails
/// (never writing a wrong file).
inline int remove_stale_temporaries(const std::filesystem::path& target) {
  namespace fs = std::filesystem;
  const fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code error;
  int removed = 0;
  for (fs::directory_iterator it(directory, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    std::error_code ignored;
    // unlink removes a link itself, never what it points to; only regular files are removed.
    if (StagedFile::is_temporary_of(target, name) && it->is_regular_file(ignored) &&
        !it->is_symlink(ignored) && ::unlink(it->path().c_str()) == 0)
      ++removed;
  }
  return removed;
}

/// Throws ImageWriteError unless `target` can be written: its name fits the file system (a
/// file name of at most NAME_MAX bytes, a path shorter than PATH_MAX), its directory exists and
/// lets this process create files there (shown by creating and removing a temporary beside the
/// target, as the write will: permissions alone do not bind root, nor say that a file system is
/// read-only or full of inodes), and the target is not a directory. A program calls it for every
/// output before long work, so that a mistyped output fails at once instead of after the render,
/// and before any other output was replaced; the write itself still checks everything again.
inline void check_output_path(const std::filesystem::path& target) {
  namespace fs = std::filesystem;
  const auto fail = [&](const std::string& why) {
    throw ImageWriteError("cannot write " + target.string() + ": " + why);
  };
  if (target.filename().empty()) fail("the name is a directory");
  if (target.native().size() >= PATH_MAX)
    fail("the path is " + std::to_string(target.native().size()) + " bytes long, more than " +
         std::to_string(PATH_MAX - 1));
  const fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code error;
  const fs::file_status status = fs::status(directory, error);
  if (!fs::exists(status)) fail("directory " + directory.string() + " does not exist");
  if (!fs::is_directory(status)) fail(directory.string() + " is not a directory");
  const long name_max = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  const std::size_t name_size = target.filename().native().size();
  if (name_max > 0 && name_size > std::size_t(name_max))
    fail("the file name is " + std::to_string(name_size) + " bytes long, more than the " +
         std::to_string(name_max) + " its file system allows");
  // AT_EACCESS: the permissions of the effective user, who will create the file.
  if (faccessat(AT_FDCWD, directory.c_str(), W_OK | X_OK, AT_EACCESS) != 0)
    fail("directory " + directory.string() + " is not writable (" + std::strerror(errno) + ")");
  if (fs::is_directory(fs::symlink_status(target, error))) fail("it is a directory");
  const StagedFile probe(target);  // removed again by its destructor
}

/// A file's path and its whole content.
struct FileContents {
  std::filesystem::path path;
  std::vector<char> bytes;
};

/// Writes every file to a temporary and renames them into place only once all were written:
/// if one fails, none of the targets changes and no temporary is left (a rename failing after
/// another succeeded, which takes the directory changing under the write, is the exception).
/// Throws ImageWriteError naming the file that failed.
inline void write_files(const std::vector<FileContents>& files) {
  std::vector<StagedFile> staged;
  staged.reserve(files.size());
  for (const FileContents& file : files)
    staged.emplace_back(file.path);
  for (std::size_t i = 0; i < files.size(); ++i)
    staged[i].write(files[i].bytes);
  for (StagedFile& file : staged)
    file.commit();
}

/// 8-bit RGB, sRGB-encoded after `tone_mapping` (by default none: radiance above 1 clips).
inline std::vector<std::uint8_t> to_srgb8(const Film& film, const ToneMapping& tone_mapping = {}) {
  const float scale = tone_mapping.scale();
  std::vector<std::uint8_t> bytes;
  bytes.reserve(film.pixels().size() * 3);
  for (const Color& c : film.pixels())
    for (const float channel : {c.x, c.y, c.z})
      bytes.push_back(linear_to_srgb8(tone_map(channel * scale, tone_mapping.op)));
  return bytes;
}

/// The PNG file of 8-bit RGB pixels (`rgb`: rows from the top, three bytes a pixel, already
/// display-encoded), in memory. Throws ImageWriteError if encoding fails or `rgb` does not
/// hold width x height pixels.
inline std::vector<char> encode_png_rgb8(int width, int height,
                                         const std::vector<std::uint8_t>& rgb) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width < 1 || height < 1 || rgb.size() != std::size_t(width) * std::size_t(height) * 3)
    throw ImageWriteError("PNG encoding of a " + size + " image failed: " +
                          std::to_string(rgb.size()) + " bytes of pixels do not match");
  std::vector<char> encoded;
  const auto append = [](void* context, void* data, int bytes) {
    auto* out = static_cast<std::vector<char>*>(context);
    out->insert(out->end(), static_cast<char*>(data), static_cast<char*>(data) + bytes);
  };
  if (!stbi_write_png_to_func(append, &encoded, width, height, 3, rgb.data(), width * 3))
    throw ImageWriteError("PNG encoding of a " + size + " image failed");
  return encoded;
}

/// The PNG file of the film, in memory. Throws ImageWriteError if encoding fails.
inline std::vector<char> encode_png(const Film& film, const ToneMapping& tone_mapping = {}) {
  return encode_png_rgb8(film.width(), film.height(), to_srgb8(film, tone_mapping));
}

/// The PFM file of the film, in memory: portable float map, linear RGB, little-endian
/// (negative scale), rows bottom to top.
inline std::vector<char> encode_pfm(const Film& film) {
  const std::string header =
      "PF\n" + std::to_string(film.width()) + " " + std::to_string(film.height()) + "\n-1.0\n";
  std::vector<char> bytes(header.begin(), header.end());
  bytes.reserve(header.size() + film.pixels().size() * 12);
  for (int y = film.height() - 1; y >= 0; --y) {
    for (int x = 0; x < film.width(); ++x) {
      const Color& c = film.at(x, y);
      for (const float v : {c.x, c.y, c.z}) {
        std::uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int byte = 0; byte < 4; ++byte)
          bytes.push_back(static_cast<char>(bits >> (8 * byte)));
      }
    }
  }
  return bytes;
}

inline void write_png(const Film& film, const std::filesystem::path& path,
                      const ToneMapping& tone_mapping = {}) {
  std::vector<char> bytes;
  try {
    bytes = encode_png(film, tone_mapping);
  } catch (const ImageWriteError& error) {
    throw ImageWriteError("cannot write " + path.string() + ": " + error.what());
  }
  write_files({{path, std::move(bytes)}});
}

inline void write_pfm(const Film& film, const std::filesystem::path& path) {
  write_files({{path, encode_pfm(film)}});
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
