#pragma once
// OpenEXR images of a Film: linear RGB as 32-bit float (exact) or 16-bit half, with typed
// attributes in the header (glint-render records its render settings there), and back.
//
// Not part of the header-only core: the functions are compiled into the glint::exr library,
// which links OpenEXR (Debian: libopenexr-dev). This header itself needs only glint and the
// standard library, so a program that links glint::exr needs no OpenEXR include path.
//
//   target_link_libraries(app PRIVATE glint::exr)
//
// Files are scan-line images with lossless compression (ZIP for float32, PIZ for float16: see
// exr_image.cpp for why), one R, G and B channel, the data and display windows both
// [0, width-1] x [0, height-1], row 0 at the top as in the Film.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "glint/image/film.hpp"

namespace glint {

/// The channels' pixel type in an EXR file.
enum class ExrPixelType {
  float32,  ///< IEEE single precision: every value of the Film, NaN and infinities included,
            ///< is written and read back bit for bit
  float16,  ///< half precision: half the size, 11 significant bits (rounded to nearest:
            ///< relative error at most 2^-11 from 2^-14 up); below 2^-14 subnormal halves, in
            ///< steps of 2^-24 (absolute error at most 2^-25, and zero below that); magnitudes
            ///< above kExrLargestHalf, infinities included, are written as +-kExrLargestHalf
            ///< and counted (ExrEncoded::clamped_values), not as infinities, which would turn
            ///< filters and blurs in other programs into NaN; NaN stays NaN
};

/// The largest finite half, 65504: the most a float16 EXR holds.
inline constexpr float kExrLargestHalf = 65504.0f;

/// The types of attribute this library writes and reads back: EXR's int, float, double and
/// string attributes. EXR has no 64-bit integer attribute: store one (a seed) as its decimal
/// string, which keeps it exact.
using ExrAttributeValue = std::variant<int, float, double, std::string>;

/// One named attribute of the header. Names are what the caller chooses; glint-render's are
/// "glint/..." (see docs/glint-render.md), plus the standard "comments".
struct ExrAttribute {
  std::string name;
  ExrAttributeValue value;
  friend bool operator==(const ExrAttribute&, const ExrAttribute&) = default;
};

struct ExrWriteOptions {
  ExrPixelType pixel_type = ExrPixelType::float32;
  /// Written in the header, each with its own type. A name must be new: not empty, not one of
  /// the attributes the file's structure uses (channels, compression, dataWindow, ...), not
  /// given twice; a standard attribute of OpenEXR (ImfStandardAttributes.h: comments, owner,
  /// capDate, utcOffset, ...) must have its standard type. Otherwise encoding throws
  /// ImageWriteError.
  std::vector<ExrAttribute> attributes;
};

/// An EXR file's bytes, and how many channel values (not pixels) float16 clamped to
/// +-kExrLargestHalf; always 0 for float32.
struct ExrEncoded {
  std::vector<char> bytes;
  std::size_t clamped_values = 0;
};

/// The EXR file of the film, in memory, for glint::write_files or a program's own staged
/// writer. Throws ImageWriteError: an empty film, a refused attribute, or OpenEXR failing.
ExrEncoded encode_exr(const Film& film, const ExrWriteOptions& options = {});

/// Writes the EXR file of the film to `path` through glint::write_files (a temporary renamed
/// into place: a failed write leaves nothing behind). Returns the clamped values' count, as
/// encode_exr. Throws ImageWriteError naming the path.
std::size_t write_exr(const Film& film, const std::filesystem::path& path,
                      const ExrWriteOptions& options = {});

/// An EXR image read back.
struct ExrImage {
  Film film;  ///< the data window's pixels, row 0 at the top
  /// float16 when R, G and B are all half channels, float32 otherwise (float, or 32-bit
  /// unsigned integer channels, which are converted to float).
  ExrPixelType pixel_type = ExrPixelType::float32;
  /// Every int, float, double and string attribute of the header except those of the file's
  /// structure (channels, compression, pixelAspectRatio, ...), in name order. Attributes of
  /// other types (chromaticities, matrices, ...) are skipped.
  std::vector<ExrAttribute> attributes;

  /// The attribute called `name`, or nullptr.
  const ExrAttribute* find(const std::string& name) const;
};

/// Decodes an EXR file held in memory: any scan-line or tiled OpenEXR image (the first part of
/// a multi-part file) with R, G and B channels, of glint's image size limits at most. Throws
/// ImageReadError starting with `name` (the file's name, for the message) for anything else:
/// not an EXR file, truncated or damaged data, no RGB channels, subsampled channels, deep
/// data, an image too large.
ExrImage decode_exr(const char* data, std::size_t size, const std::string& name);

/// The largest EXR file read_exr reads: twice an uncompressed 32-bit RGBA image of glint's
/// largest size. A pipe or a device is refused once it has delivered more.
inline constexpr std::uint64_t kMaxExrFileSize = std::uint64_t{2} << 30;

/// Reads the EXR file at `path`; throws ImageReadError naming it (see decode_exr). A file that
/// does not begin with EXR's magic number is refused after its first four bytes, one larger
/// than kMaxExrFileSize before it is read, and a pipe or device after kMaxExrFileSize bytes.
ExrImage read_exr(const std::filesystem::path& path);

/// Lets read_texture (<glint/io/texture_reader.hpp>), and so a scene's `texture=` and
/// `background image=`, read OpenEXR files with read_exr: their R, G and B channels as linear
/// values. For the whole program, once before scenes are read.
void enable_exr_textures();

}  // namespace glint
