#pragma once
// Reading a Film back from a PFM file (linear float RGB), as written by write_pfm.

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "glint/error.hpp"
#include "glint/image/film.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/input_file.hpp"
#include "glint/scene/image_settings.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The most bytes a PFM header may take before its pixels: "PF", the width, the height and
/// the scale with the whitespace between them. A longer one is no PFM glint reads, and the
/// bound stops a binary file or an endless device (/dev/zero) at once.
inline constexpr std::size_t kMaxPfmHeader = 256;

namespace detail::pfm {

/// The next whitespace-separated word of the header, at most kMaxWord bytes; "" at the end of
/// the file, or when the word or the header grows beyond its bound.
inline std::string word(InputFile& file) {
  constexpr std::size_t kMaxWord = 32;
  int c = file.get();
  while (c >= 0 && std::isspace(c) && file.position() < kMaxPfmHeader)
    c = file.get();
  std::string out;
  while (c >= 0 && !std::isspace(c)) {
    if (out.size() == kMaxWord || file.position() > kMaxPfmHeader) return "";
    out += char(c);
    c = file.get();
  }
  return out;  // the whitespace after the word has been taken
}

template <typename Number>
bool parse(const std::string& text, Number& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

}  // namespace detail::pfm

/// Reads a colour PFM (little- or big-endian), as write_pfm writes it. Throws ImageReadError,
/// naming the file and the problem, for anything else. The header is read with a bound and its
/// size checked against glint's image limits and against the bytes the file holds before the
/// image is allocated: a short file claiming a large image costs what the file holds, and a
/// pipe or device is read only as far as its data arrives.
inline Film read_pfm(const std::filesystem::path& path) {
  using namespace detail::pfm;
  const std::string name = path.string();
  InputFile file(path, [&](const std::string& why) {
    throw ImageReadError("cannot read " + name + ": " + why);
  });
  // What the file holds, rather than whether it can be read, is named with the file alone.
  const auto refuse = [&](const std::string& why) { throw ImageReadError(name + ": " + why); };
  const std::string magic = word(file);
  if (magic != "PF")
    refuse(magic == "Pf" ? "a greyscale PFM file, glint reads colour ones (PF)"
                         : "not a colour PFM file (it does not begin with PF)");
  int width = 0, height = 0;
  double scale = 0.0;
  const std::string width_text = word(file), height_text = word(file), scale_text = word(file);
  if (!parse(width_text, width) || !parse(height_text, height) || !parse(scale_text, scale) ||
      !std::isfinite(scale) || scale == 0.0)
    refuse("not a colour PFM file (its header is not PF, width, height and scale within " +
           std::to_string(kMaxPfmHeader) + " bytes)");
  if (width < 1 || height < 1 || width > limits::max_image_side ||
      height > limits::max_image_side || std::int64_t{width} * height > limits::max_image_pixels)
    refuse("its header claims " + std::to_string(width) + "x" + std::to_string(height) +
           " pixels, beyond glint's limits (" + std::to_string(limits::max_image_side) +
           " pixels a side, " + std::to_string(limits::max_image_pixels) + " in all)");
  const std::size_t row_bytes = std::size_t(width) * 12;
  const std::uint64_t data_bytes = std::uint64_t(row_bytes) * std::uint64_t(height);
  if (const std::optional<std::uint64_t> left = file.remaining(); left && *left < data_bytes)
    refuse("truncated PFM file: its header claims " + std::to_string(width) + "x" +
           std::to_string(height) + " pixels (" + std::to_string(data_bytes) +
           " bytes), the file holds " + std::to_string(*left) + " bytes after the header");
  // A pipe or a device: its pixels are taken as they come, before the film is allocated.
  const bool streaming = !file.size();
  std::vector<char> streamed;
  if (streaming && !file.append(streamed, data_bytes))
    refuse("truncated PFM file: its header claims " + std::to_string(width) + "x" +
           std::to_string(height) + " pixels (" + std::to_string(data_bytes) +
           " bytes), the file held " + std::to_string(streamed.size()) + " after the header");

  const bool little_endian = scale < 0.0;
  Film film(width, height);
  std::vector<char> row(streaming ? 0 : row_bytes);
  for (int y = height - 1; y >= 0; --y) {
    const char* bytes = nullptr;
    if (!streaming) {
      if (file.read(row.data(), row.size()) != row.size())
        refuse("truncated PFM file (it shrank while being read)");
      bytes = row.data();
    } else {
      bytes = streamed.data() + std::size_t(height - 1 - y) * row_bytes;
    }
    for (int x = 0; x < width; ++x) {
      float rgb[3];
      for (float& v : rgb) {
        const auto* b = reinterpret_cast<const unsigned char*>(bytes);
        bytes += 4;
        const std::uint32_t bits = little_endian
                                       ? (std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                                          std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24)
                                       : (std::uint32_t(b[3]) | std::uint32_t(b[2]) << 8 |
                                          std::uint32_t(b[1]) << 16 | std::uint32_t(b[0]) << 24);
        std::memcpy(&v, &bits, sizeof v);
      }
      film.at(x, y) = Color(rgb[0], rgb[1], rgb[2]);
    }
  }
  return film;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
