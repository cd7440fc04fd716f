#pragma once
// A render's checkpoint: the per-pixel sums of its completed passes and what identifies the
// image they belong to, so that a later run can continue it (Renderer's RenderControl::start)
// and produce exactly the bytes an uninterrupted render would.
//
// The format, little-endian with explicit sizes (version 3; version 2 had no splat layer,
// version 1 held float sums):
//
//   offset  size  field
//   0       8     magic "GLINTCKP"
//   8       4     u32 format version
//   12      8     u64 FNV-1a hash of the scene file's bytes and its images
//   20      4     u32 variant name length n (at most kMaxVariantName)
//   24      n     variant name
//   24+n    4*9   u32 width, height, samples per pixel, max depth, max_pass_samples;
//                 u64 seed; u32 antialias sigma (float bits)
//   60+n    8     u32 passes done, u32 samples per pixel done
//   68+n    4     u32 layers: 0 (the sums), 1 (the sums and a splat layer)
//   72+n    24wh  f64 sums, r g b per pixel, rows from the top
//   ...     48wh  with a splat layer: i64 splat sums, coarse and fine for r g b per pixel, rows
//                 from the top (image/splat_sums.hpp)
//   end-8   8     u64 FNV-1a hash of every byte before it
//
// The image settings are stored as they are, not only hashed, so that a mismatch can be named.
// The reader checks every size against the header before allocating, and never trusts one.

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "glint/error.hpp"
#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/input_file.hpp"
#include "glint/render/render_settings.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A checkpoint that cannot be read, is damaged, or belongs to another render.
class CheckpointError : public Error {
 public:
  using Error::Error;
};

/// What makes two renders the same image: a checkpoint continues only a render that has the
/// same key. The thread count and tile size are not in it, because the image does not depend
/// on them.
struct CheckpointKey {
  std::uint64_t scene_hash = 0;  ///< fnv1a of the scene file's bytes and its images
  std::string variant;
  int width = 0;
  int height = 0;
  int samples_per_pixel = 0;
  int max_depth = 0;
  int max_pass_samples = 0;
  std::uint64_t seed = 0;
  float antialias_sigma = 0.0f;

  static CheckpointKey of(std::uint64_t scene_hash, std::string_view variant,
                          const RenderSettings& settings) {
    return {scene_hash,
            std::string(variant),
            settings.width,
            settings.height,
            settings.samples_per_pixel,
            settings.max_depth,
            settings.max_pass_samples,
            settings.seed,
            settings.antialias_sigma};
  }
};

/// The state of a render after `passes_done` passes.
struct Checkpoint {
  CheckpointKey key;
  int passes_done = 0;
  int samples_per_pixel_done = 0;
  /// Per-pixel sums of the samples of the completed passes (PassReport::sums), with their splat
  /// layer where the render splats.
  PixelSums sums;
};

inline constexpr char kCheckpointMagic[8] = {'G', 'L', 'I', 'N', 'T', 'C', 'K', 'P'};
inline constexpr std::uint32_t kCheckpointVersion = 3;
inline constexpr std::uint32_t kMaxVariantName = 64;

/// 64-bit FNV-1a, continuing from `hash`: the checkpoint's content and scene hashes. Not a
/// defence against forgery, only against mix-ups and damage.
inline std::uint64_t fnv1a(const void* data, std::size_t size,
                           std::uint64_t hash = 0xcbf29ce484222325ULL) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

namespace detail::checkpoint {

inline constexpr std::size_t kFixedHeader = 8 + 4 + 8 + 4;  // up to the variant name
inline constexpr std::size_t kSettingsAndPasses = 4 * 5 + 8 + 4 + 4 + 4 + 4;
inline constexpr std::size_t kBytesPerPixel = 3 * 8;
inline constexpr std::size_t kSplatBytesPerPixel = SplatSums::kWordsPerPixel * 8;
/// Pixels per piece when a checkpoint is written or read in pieces.
inline constexpr std::size_t kPiecePixels = std::size_t{1} << 14;

/// Writes fields in order into bytes sized beforehand (GCC 12 warns, wrongly, about a
/// vector<char> growing by insert).
struct Writer {
  char* at;
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
      *at++ = static_cast<char>(v >> (8 * i));
  }
  void u64(std::uint64_t v) {
    u32(std::uint32_t(v));
    u32(std::uint32_t(v >> 32));
  }
  void bytes(const char* data, std::size_t size) {
    std::memcpy(at, data, size);
    at += size;
  }
};

/// Reads fields in order from bytes whose size was checked beforehand.
struct Cursor {
  const char* at;
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
      v |= std::uint32_t(static_cast<unsigned char>(at[i])) << (8 * i);
    at += 4;
    return v;
  }
  std::uint64_t u64() {
    const std::uint64_t low = u32();
    return low | std::uint64_t(u32()) << 32;
  }
};

/// The header's fields, read from its first bytes; `size` is where the sums begin.
struct Header {
  Checkpoint meta;      ///< everything but the sums
  bool splats = false;  ///< a splat layer follows the sums
  std::size_t size = 0;
  std::uint64_t file_size = 0;  ///< what the header says the whole file holds
};

/// Parses the header from `bytes` (the file's first bytes, perhaps all of it) of a file of
/// `file_size` bytes (empty for a pipe, whose size is not known beforehand); throws
/// CheckpointError with `fail`'s prefix.
template <typename Fail>
Header parse_header(const char* bytes, std::size_t available,
                    std::optional<std::uint64_t> file_size, const Fail& fail) {
  const auto truncated = [&] {
    fail("it is truncated (" + std::to_string(file_size.value_or(available)) + " bytes)");
  };
  if (available < kFixedHeader) truncated();
  if (std::memcmp(bytes, kCheckpointMagic, sizeof kCheckpointMagic) != 0)
    fail("it is not a glint checkpoint (no GLINTCKP magic)");
  Cursor in{bytes + sizeof kCheckpointMagic};
  const std::uint32_t version = in.u32();
  if (version != kCheckpointVersion)
    fail("format version " + std::to_string(version) + ", this glint reads version " +
         std::to_string(kCheckpointVersion));
  Header header;
  CheckpointKey& key = header.meta.key;
  key.scene_hash = in.u64();
  const std::uint32_t name_size = in.u32();
  if (name_size > kMaxVariantName)
    fail("a variant name of " + std::to_string(name_size) + " bytes");
  header.size = kFixedHeader + name_size + kSettingsAndPasses;
  if (available < header.size) truncated();
  key.variant.assign(in.at, name_size);
  in.at += name_size;
  const std::uint32_t width = in.u32(), height = in.u32(), spp = in.u32(), depth = in.u32(),
                      max_pass = in.u32();
  key.seed = in.u64();
  key.antialias_sigma = std::bit_cast<float>(in.u32());
  const std::uint32_t passes = in.u32(), spp_done = in.u32(), layers = in.u32();

  // Every count within glint's limits before any of them sizes anything.
  if (width < 1 || width > std::uint32_t(limits::max_image_side) || height < 1 ||
      height > std::uint32_t(limits::max_image_side) ||
      std::uint64_t(width) * height > std::uint64_t(limits::max_image_pixels))
    fail("an image size of " + std::to_string(width) + "x" + std::to_string(height));
  if (spp < 1 || spp > std::uint32_t(limits::max_samples_per_pixel) || max_pass < 1 ||
      max_pass > std::uint32_t(limits::max_samples_per_pixel) ||
      depth > std::uint32_t(limits::max_depth))
    fail("settings outside glint's limits");
  key.width = int(width);
  key.height = int(height);
  key.samples_per_pixel = int(spp);
  key.max_depth = int(depth);
  key.max_pass_samples = int(max_pass);
  const std::vector<int> ends = pass_ends(key.samples_per_pixel, key.max_pass_samples);
  if (passes < 1 || passes > ends.size() || ends[passes - 1] != int(spp_done))
    fail(std::to_string(passes) + " passes of " + std::to_string(spp_done) +
         " samples per pixel, which is no pass boundary of its settings");
  if (layers > 1)
    fail(std::to_string(layers) +
         " layers of sums, where a render keeps its sums and perhaps "
         "a splat layer");
  header.meta.passes_done = int(passes);
  header.meta.samples_per_pixel_done = int(spp_done);
  header.splats = layers == 1;
  header.file_size =
      header.size +
      std::uint64_t(width) * height * (kBytesPerPixel + (header.splats ? kSplatBytesPerPixel : 0)) +
      8;
  if (file_size && *file_size != header.file_size)
    fail((*file_size < header.file_size ? "it is truncated (" : "it is too long (") +
         std::to_string(*file_size) + " bytes, the header promises " +
         std::to_string(header.file_size) + ")");
  return header;
}

/// Decodes `pixels` sums, from the pixel `first` on (row-major), from `bytes`. Returns the
/// index of the first pixel that no render can have made, or `bad` unchanged if all are sound.
inline std::size_t decode_sums(const char* bytes, std::size_t pixels, std::size_t first,
                               PixelSums& sums, std::size_t bad) {
  Cursor in{bytes};
  const std::size_t width = std::size_t(sums.width());
  for (std::size_t i = first; i < first + pixels; ++i) {
    ColorSum& pixel = sums.at(int(i % width), int(i / width));
    pixel.x = std::bit_cast<double>(in.u64());
    pixel.y = std::bit_cast<double>(in.u64());
    pixel.z = std::bit_cast<double>(in.u64());
    // A render's samples are finite radiance, never negative (-0.0 is zero, and passes).
    if (!(pixel.x >= 0.0 && pixel.y >= 0.0 && pixel.z >= 0.0 && std::isfinite(pixel.x) &&
          std::isfinite(pixel.y) && std::isfinite(pixel.z)) &&
        i < bad)
      bad = i;
  }
  return bad;
}

/// Decodes the splat words of `pixels` pixels, from the pixel `first` on (row-major), from
/// `bytes`. Returns the index of the first pixel whose splat sum no render can have made (a
/// negative one: splats are light, at least zero), or `bad` unchanged if all are sound.
inline std::size_t decode_splats(const char* bytes, std::size_t pixels, std::size_t first,
                                 SplatSums& splats, std::size_t bad) {
  Cursor in{bytes};
  std::int64_t* words = splats.words().data() + first * SplatSums::kWordsPerPixel;
  for (std::size_t i = first; i < first + pixels; ++i) {
    bool negative = false;
    for (int c = 0; c < 3; ++c) {
      const auto coarse = std::int64_t(in.u64()), fine = std::int64_t(in.u64());
      *words++ = coarse;
      *words++ = fine;
      // coarse 2^-kCoarseBits + fine 2^-kFineBits < 0, in integers: coarse below zero, or below
      // the coarse units that a negative fine part needs, ceil(-fine / 2^(kFineBits -
      // kCoarseBits)) (unsigned: -fine reaches 2^63).
      constexpr int kShift = SplatSums::kFineBits - SplatSums::kCoarseBits;
      const std::uint64_t fine_below_zero = fine < 0 ? 0 - std::uint64_t(fine) : 0;
      const std::uint64_t coarse_needed =
          (fine_below_zero + ((std::uint64_t{1} << kShift) - 1)) >> kShift;
      negative = negative || coarse < 0 || std::uint64_t(coarse) < coarse_needed;
    }
    if (negative && i < bad) bad = i;
  }
  return bad;
}

/// Refuses the splats if decode_splats found a pixel `bad` that no render makes, naming it.
template <typename Fail>
void check_splats(const SplatSums& splats, std::size_t bad, const Fail& fail) {
  const std::size_t width = std::size_t(splats.width());
  if (bad >= std::size_t(splats.width()) * std::size_t(splats.height())) return;
  fail("pixel (" + std::to_string(bad % width) + ", " + std::to_string(bad / width) +
       ") holds a negative splat sum, which no render makes");
}

/// Refuses the sums if decode_sums found a pixel `bad` that no render makes, naming it.
template <typename Fail>
void check_sums(const PixelSums& sums, std::size_t bad, const Fail& fail) {
  const std::size_t width = std::size_t(sums.width());
  if (bad >= sums.pixels().size()) return;
  const int x = int(bad % width), y = int(bad / width);
  const ColorSum& pixel = sums.at(x, y);
  const std::string where = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
  if (!(std::isfinite(pixel.x) && std::isfinite(pixel.y) && std::isfinite(pixel.z)))
    fail(where + " holds a sum that is not finite");
  fail(where + " holds a negative sum, which no render makes");
}

inline auto failer(const std::string& name) {
  return [name](const std::string& why) {
    throw CheckpointError("cannot resume from " + name + ": " + why);
  };
}

}  // namespace detail::checkpoint

/// Encodes the checkpoint of a render with `key` after `passes_done` passes, when its pixels
/// hold the sums `sums` of `samples_per_pixel_done` samples each, handing its bytes to
/// `put(const char* data, std::size_t size)` in order, in pieces of at most some hundred
/// kilobytes: a checkpoint written this way is never held whole in memory. The splat layer, where
/// the sums have one, is kept too.
template <typename Put>
void encode_checkpoint_pieces(const CheckpointKey& key, int passes_done, int samples_per_pixel_done,
                              const PixelSums& sums, Put&& put) {
  using namespace detail::checkpoint;
  std::vector<char> piece(kFixedHeader + key.variant.size() + kSettingsAndPasses);
  Writer out{piece.data()};
  out.bytes(kCheckpointMagic, sizeof kCheckpointMagic);
  out.u32(kCheckpointVersion);
  out.u64(key.scene_hash);
  out.u32(std::uint32_t(key.variant.size()));
  out.bytes(key.variant.data(), key.variant.size());
  for (const int v :
       {key.width, key.height, key.samples_per_pixel, key.max_depth, key.max_pass_samples})
    out.u32(std::uint32_t(v));
  out.u64(key.seed);
  out.u32(std::bit_cast<std::uint32_t>(key.antialias_sigma));
  out.u32(std::uint32_t(passes_done));
  out.u32(std::uint32_t(samples_per_pixel_done));
  out.u32(sums.has_splats() ? 1 : 0);
  std::uint64_t hash = fnv1a(piece.data(), piece.size());
  put(static_cast<const char*>(piece.data()), piece.size());

  const std::vector<ColorSum>& pixels = sums.pixels();
  for (std::size_t first = 0; first < pixels.size(); first += kPiecePixels) {
    const std::size_t count = std::min(kPiecePixels, pixels.size() - first);
    piece.resize(count * kBytesPerPixel);
    out.at = piece.data();
    for (std::size_t i = first; i < first + count; ++i)
      for (const double v : {pixels[i].x, pixels[i].y, pixels[i].z})
        out.u64(std::bit_cast<std::uint64_t>(v));
    hash = fnv1a(piece.data(), piece.size(), hash);
    put(static_cast<const char*>(piece.data()), piece.size());
  }
  if (sums.has_splats()) {
    const std::vector<std::int64_t>& words = sums.splats().words();
    constexpr std::size_t kPieceWords = kPiecePixels * SplatSums::kWordsPerPixel;
    for (std::size_t first = 0; first < words.size(); first += kPieceWords) {
      const std::size_t count = std::min(kPieceWords, words.size() - first);
      piece.resize(count * 8);
      out.at = piece.data();
      for (std::size_t i = first; i < first + count; ++i)
        out.u64(std::uint64_t(words[i]));
      hash = fnv1a(piece.data(), piece.size(), hash);
      put(static_cast<const char*>(piece.data()), piece.size());
    }
  }
  piece.resize(8);
  out.at = piece.data();
  out.u64(hash);
  put(static_cast<const char*>(piece.data()), piece.size());
}

/// The bytes of the checkpoint of a render with `key` after `passes_done` passes, when its
/// pixels hold the sums `sums` of `samples_per_pixel_done` samples each.
inline std::vector<char> encode_checkpoint(const CheckpointKey& key, int passes_done,
                                           int samples_per_pixel_done, const PixelSums& sums) {
  std::vector<char> out;
  out.reserve(detail::checkpoint::kFixedHeader + key.variant.size() +
              detail::checkpoint::kSettingsAndPasses +
              sums.pixels().size() *
                  (detail::checkpoint::kBytesPerPixel +
                   (sums.has_splats() ? detail::checkpoint::kSplatBytesPerPixel : 0)) +
              8);
  encode_checkpoint_pieces(
      key, passes_done, samples_per_pixel_done, sums,
      [&](const char* data, std::size_t size) { out.insert(out.end(), data, data + size); });
  return out;
}

inline std::vector<char> encode_checkpoint(const Checkpoint& c) {
  return encode_checkpoint(c.key, c.passes_done, c.samples_per_pixel_done, c.sums);
}

/// The checkpoint in `bytes`, read from the file `name` (for messages). Throws CheckpointError
/// naming the file and the problem for anything but a complete, undamaged checkpoint.
inline Checkpoint decode_checkpoint(const std::vector<char>& bytes, const std::string& name) {
  using namespace detail::checkpoint;
  const auto fail = failer(name);
  Header header = parse_header(bytes.data(), bytes.size(), bytes.size(), fail);
  Checkpoint c = std::move(header.meta);
  Cursor in{bytes.data() + bytes.size() - 8};
  if (in.u64() != fnv1a(bytes.data(), bytes.size() - 8))
    fail("it is damaged (its content hash does not match)");
  c.sums = PixelSums(c.key.width, c.key.height, header.splats);
  const std::size_t pixels = c.sums.pixels().size();
  check_sums(c.sums, decode_sums(bytes.data() + header.size, pixels, 0, c.sums, pixels), fail);
  if (header.splats)
    check_splats(c.sums.splats(),
                 decode_splats(bytes.data() + header.size + pixels * kBytesPerPixel, pixels, 0,
                               c.sums.splats(), pixels),
                 fail);
  return c;
}

/// Reads and checks the checkpoint file `path`. Its header is read first and checked against
/// glint's limits and the file's size, so that a damaged or foreign file costs at most what it
/// holds; the sums are then read in pieces straight into the checkpoint, never held twice. A
/// pipe or a device, whose size is known only at its end, is read as far as its data arrives
/// and no further than its header promises. Throws CheckpointError.
inline Checkpoint read_checkpoint(const std::filesystem::path& path) {
  using namespace detail::checkpoint;
  const std::string name = path.string();
  const auto fail = failer(name);
  InputFile file(path, fail);
  // The largest header: the fixed fields and the longest variant name.
  std::vector<char> piece(kFixedHeader + kMaxVariantName + kSettingsAndPasses);
  piece.resize(file.read(piece.data(), piece.size()));
  Header header = parse_header(piece.data(), piece.size(), file.size(), fail);
  if (!file.size()) {
    if (piece.size() > header.file_size)
      fail("it is too long (the header promises " + std::to_string(header.file_size) + " bytes)");
    if (!file.append(piece, header.file_size - piece.size()))
      fail("it is truncated (" + std::to_string(piece.size()) + " bytes, the header promises " +
           std::to_string(header.file_size) + ")");
    if (!file.at_end())
      fail("it is too long (the header promises " + std::to_string(header.file_size) + " bytes)");
    return decode_checkpoint(piece, name);
  }

  Checkpoint c = std::move(header.meta);
  c.sums = PixelSums(c.key.width, c.key.height, header.splats);
  std::uint64_t hash = fnv1a(piece.data(), header.size);
  piece.erase(piece.begin(), piece.begin() + std::ptrdiff_t(header.size));
  const std::size_t pixels = c.sums.pixels().size();
  // Reads a layer of `bytes_per_pixel` bytes per pixel in pieces of whole pixels, handing each
  // to decode(bytes, count, first pixel, bad); with the last layer, the content hash too.
  const auto read_layer = [&](std::size_t bytes_per_pixel, bool last, const auto& decode) {
    std::size_t done = 0, bad = pixels;
    while (done < pixels) {
      const std::size_t count = std::min(kPiecePixels, pixels - done);
      const std::size_t size = count * bytes_per_pixel;
      const std::size_t want = size + (last && done + count == pixels ? 8 : 0);
      if (const std::size_t have = piece.size(); have < want) {
        piece.resize(want);
        if (file.read(piece.data() + have, want - have) != want - have)
          fail("it shrank while being read");
      }
      hash = fnv1a(piece.data(), size, hash);
      bad = decode(piece.data(), count, done, bad);
      done += count;
      piece.erase(piece.begin(), piece.begin() + std::ptrdiff_t(size));
    }
    return bad;
  };
  const std::size_t bad_sum =
      read_layer(kBytesPerPixel, !header.splats,
                 [&](const char* bytes, std::size_t count, std::size_t first, std::size_t bad) {
                   return decode_sums(bytes, count, first, c.sums, bad);
                 });
  std::size_t bad_splat = pixels;
  if (header.splats)
    bad_splat =
        read_layer(kSplatBytesPerPixel, true,
                   [&](const char* bytes, std::size_t count, std::size_t first, std::size_t bad) {
                     return decode_splats(bytes, count, first, c.sums.splats(), bad);
                   });
  if (Cursor{piece.data()}.u64() != hash) fail("it is damaged (its content hash does not match)");
  check_sums(c.sums, bad_sum, fail);
  check_splats(c.sums.splats(), bad_splat, fail);
  return c;
}

/// Throws CheckpointError, naming the file and the first difference, unless the checkpoint
/// `c` read from `name` belongs to the render `expected` describes.
inline void check_checkpoint_matches(const Checkpoint& c, const CheckpointKey& expected,
                                     const std::string& name) {
  const auto fail = detail::checkpoint::failer(name);
  const CheckpointKey& got = c.key;
  const auto differs = [&](const char* what, const auto& theirs, const auto& ours) {
    if (theirs != ours)
      fail(std::string("it was made with ") + what + " " + std::to_string(theirs) +
           ", this render has " + std::to_string(ours));
  };
  if (got.scene_hash != expected.scene_hash)
    fail("it was made from another scene (the scene file's bytes or its images differ)");
  if (got.variant != expected.variant)
    fail("it was made by variant '" + got.variant + "', this is variant '" + expected.variant +
         "'");
  differs("width", got.width, expected.width);
  differs("height", got.height, expected.height);
  differs("samples per pixel", got.samples_per_pixel, expected.samples_per_pixel);
  differs("max depth", got.max_depth, expected.max_depth);
  differs("seed", got.seed, expected.seed);
  differs("samples per pass at most", got.max_pass_samples, expected.max_pass_samples);
  if (std::bit_cast<std::uint32_t>(got.antialias_sigma) !=
      std::bit_cast<std::uint32_t>(expected.antialias_sigma))
    fail("it was made with antialias sigma " + std::to_string(got.antialias_sigma) +
         ", this render has " + std::to_string(expected.antialias_sigma));
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
