#pragma once
// Reading an image file as a Texture of linear RGB: PNG (8 or 16 bits) and JPEG, taken as
// sRGB-encoded, and Radiance HDR and colour PFM, taken as linear; decoded by stb_image but for
// the PFM. OpenEXR, linear too, is read where the program links glint's EXR library and has
// called glint::enable_exr_textures() (<glint/exr/exr_image.hpp>): the header-only core does not
// depend on OpenEXR. Which it is, the file's first bytes say, not its name. The file is read
// through InputFile with a bound, and the image's size is checked against glint's limits before
// it is decoded.

#include <array>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <stb_image.h>

#include "glint/error.hpp"
#include "glint/image/texture.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/image_reader.hpp"
#include "glint/io/input_file.hpp"
#include "glint/math/elementary_functions.hpp"
#include "glint/scene/image_settings.hpp"

namespace glint {

/// An image decoded outside glint's headers: linear RGB values, three per texel, row by row from
/// the top.
struct DecodedTexels {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
};

/// How read_texture reads an OpenEXR file: null unless the program linked glint's EXR library
/// and called glint::enable_exr_textures(). One for the whole program (it lies outside the
/// instruction sets' namespaces); the reader throws ImageReadError naming the file.
using ExrTextureReader = DecodedTexels (*)(const std::filesystem::path&);
inline ExrTextureReader& exr_texture_reader() {
  static ExrTextureReader reader = nullptr;
  return reader;
}

}  // namespace glint

namespace glint::inline GLINT_ISA_NAMESPACE {

/// read_texture refuses larger files: a compressed image of glint's largest size takes far less,
/// and an endless device (/dev/zero) is stopped there.
inline constexpr std::uint64_t kMaxTextureFileSize = std::uint64_t{1} << 30;

/// The linear value of an sRGB-encoded value in [0, 1] (IEC 61966-2-1), with glint's own log and
/// exp, so that a texture decodes to the same floats on every machine.
inline float srgb_to_linear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return exponential(2.4f * log((encoded + 0.055f) / 1.055f));
}

namespace detail::texture_reader {

/// Frees what stb_image allocated.
struct StbFree {
  void operator()(void* pixels) const { stbi_image_free(pixels); }
};

/// The formats read_texture takes, known by their first bytes.
enum class Format { png, jpeg, radiance_hdr, pfm, openexr, unknown };
inline Format format_of(std::string_view head) {
  if (head.starts_with("\x89PNG\r\n\x1a\n")) return Format::png;
  if (head.starts_with("\xff\xd8\xff")) return Format::jpeg;
  if (head.starts_with("#?RADIANCE") || head.starts_with("#?RGBE")) return Format::radiance_hdr;
  if (head.starts_with("PF") || head.starts_with("Pf")) return Format::pfm;
  if (head.starts_with("\x76\x2f\x31\x01")) return Format::openexr;
  return Format::unknown;
}
inline constexpr std::size_t kLongestMagic = 10;

}  // namespace detail::texture_reader

/// The PNG, JPEG or Radiance HDR image in `bytes` as a Texture named `name`; `shown` names the
/// bytes in messages (read_texture's path). Throws ImageReadError for anything else, for an
/// image beyond glint's limits, and for one stb_image cannot decode. Nothing the size of the
/// image is allocated before the decoder has succeeded, so a header that claims a large image
/// in a short file costs what the decoder gives up on.
inline Texture decode_texture(std::string_view bytes, std::string name, const std::string& shown) {
  using namespace detail::texture_reader;
  const Format format = format_of(bytes);
  if (format != Format::png && format != Format::jpeg && format != Format::radiance_hdr)
    throw ImageReadError(shown + ": not a PNG, JPEG or Radiance HDR image");
  if (bytes.size() > std::size_t(INT_MAX))
    throw ImageReadError(shown + ": too large for the image decoder (stb_image)");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &width, &height, &channels))
    throw ImageReadError(
        shown + ": cannot read the image's header (stb_image says: " + stbi_failure_reason() + ")");
  if (width < 1 || height < 1 || width > limits::max_image_side ||
      height > limits::max_image_side || std::int64_t{width} * height > limits::max_image_pixels)
    throw ImageReadError(shown + ": " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels, beyond glint's limits (" +
                         std::to_string(limits::max_image_side) + " pixels a side, " +
                         std::to_string(limits::max_image_pixels) + " in all)");
  const std::size_t count = std::size_t(width) * std::size_t(height);
  std::vector<Color> texels;
  int got_width = 0, got_height = 0, got_channels = 0;
  const auto failed = [&] {
    return ImageReadError(
        shown + ": cannot decode the image (stb_image says: " + stbi_failure_reason() + ")");
  };
  const auto check_size = [&] {
    if (got_width != width || got_height != height)
      throw ImageReadError(shown + ": the decoder's size differs from the header's");
  };
  if (format == Format::radiance_hdr) {
    const std::unique_ptr<float, StbFree> pixels(
        stbi_loadf_from_memory(data, size, &got_width, &got_height, &got_channels, 3));
    if (!pixels) throw failed();
    check_size();
    texels.resize(count);
    for (std::size_t i = 0; i < count; ++i)
      texels[i] = Color(pixels.get()[3 * i], pixels.get()[3 * i + 1], pixels.get()[3 * i + 2]);
  } else if (stbi_is_16_bit_from_memory(data, size)) {
    const std::unique_ptr<stbi_us, StbFree> pixels(
        stbi_load_16_from_memory(data, size, &got_width, &got_height, &got_channels, 3));
    if (!pixels) throw failed();
    check_size();
    texels.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const auto decode = [&](int c) {
        return srgb_to_linear(float(pixels.get()[3 * i + std::size_t(c)]) / 65535.0f);
      };
      texels[i] = Color(decode(0), decode(1), decode(2));
    }
  } else {
    const std::unique_ptr<stbi_uc, StbFree> pixels(
        stbi_load_from_memory(data, size, &got_width, &got_height, &got_channels, 3));
    if (!pixels) throw failed();
    check_size();
    texels.resize(count);
    std::array<float, 256> linear{};
    for (int v = 0; v < 256; ++v)
      linear[std::size_t(v)] = srgb_to_linear(float(v) / 255.0f);
    for (std::size_t i = 0; i < count; ++i)
      texels[i] = Color(linear[pixels.get()[3 * i]], linear[pixels.get()[3 * i + 1]],
                        linear[pixels.get()[3 * i + 2]]);
  }
  return Texture(std::move(name), width, height, std::move(texels));
}

/// Reads the image at `path` as a Texture named `name` (the path as a scene file gives it).
/// Throws ImageReadError naming `path` and the problem: a file that cannot be read, one that is
/// no image glint reads, one beyond glint's image limits, a texel that is negative or not finite.
inline Texture read_texture(const std::filesystem::path& path, std::string name) {
  using namespace detail::texture_reader;
  const std::string shown = path.string();
  const auto too_large = [&] {
    throw ImageReadError(shown + ": larger than " + std::to_string(kMaxTextureFileSize >> 20) +
                         " MiB, glint's limit for a texture file");
  };
  std::vector<char> bytes(kLongestMagic);
  Format format = Format::unknown;
  {
    InputFile file(path, [&](const std::string& why) {
      throw ImageReadError("cannot read " + shown + ": " + why);
    });
    if (file.size() && *file.size() > kMaxTextureFileSize) too_large();
    // The format from the first bytes, before the rest is read: a file of anything else (a
    // scene, /dev/zero) is refused at once.
    bytes.resize(file.read(bytes.data(), bytes.size()));
    format = format_of(std::string_view(bytes.data(), bytes.size()));
    if (format == Format::unknown)
      throw ImageReadError(shown + ": not a PNG, JPEG, Radiance HDR, PFM or OpenEXR file");
    if (format == Format::openexr && !exr_texture_reader())
      throw ImageReadError(shown +
                           ": an OpenEXR file, which this program does not read (it is not built "
                           "with OpenEXR): convert it to PFM or Radiance HDR");
    // The PFM reader opens the file again, which only a regular file allows.
    if (format == Format::pfm && !file.size())
      throw ImageReadError(shown + ": a PFM texture must be a regular file, not a pipe or device");
    // A regular file is read as far as its size when it was opened, into one allocation; a
    // pipe or a device as far as it goes, up to the limit. The PFM and OpenEXR readers read the
    // file themselves.
    if (format != Format::pfm && format != Format::openexr) {
      if (file.size())
        file.append(bytes, *file.size() > bytes.size() ? *file.size() - bytes.size() : 0);
      else if (file.append(bytes, kMaxTextureFileSize) && !file.at_end())
        too_large();
    }
  }
  if (format == Format::pfm) {
    // Its own reader, which checks the header against the limits in the same way.
    const Film film = read_pfm(path);
    return Texture(std::move(name), film.width(), film.height(), film.pixels());
  }
  if (format == Format::openexr) {
    const DecodedTexels decoded = exr_texture_reader()(path);
    std::vector<Color> texels(decoded.rgb.size() / 3);
    for (std::size_t i = 0; i < texels.size(); ++i)
      texels[i] = Color(decoded.rgb[3 * i], decoded.rgb[3 * i + 1], decoded.rgb[3 * i + 2]);
    return Texture(std::move(name), decoded.width, decoded.height, std::move(texels));
  }
  return decode_texture(std::string_view(bytes.data(), bytes.size()), std::move(name), shown);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
