#pragma once
// Reading a Film back from a PFM file (linear float RGB), as written by write_pfm.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "glint/error.hpp"
#include "glint/image/film.hpp"
#include "glint/scene/image_settings.hpp"

namespace glint {

/// Reads a PFM written by write_pfm (or any little- or big-endian colour PFM).
inline Film read_pfm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ImageReadError("cannot read " + path.string());
  std::string magic;
  int width = 0, height = 0;
  double scale = 0.0;
  in >> magic >> width >> height >> scale;
  in.get();
  if (!in || magic != "PF" || width < 1 || height < 1 || width > limits::max_image_side ||
      height > limits::max_image_side)
    throw ImageReadError(path.string() + ": not a colour PFM file");
  const bool little_endian = scale < 0.0;
  Film film(width, height);
  for (int y = height - 1; y >= 0; --y) {
    for (int x = 0; x < width; ++x) {
      float rgb[3];
      for (float& v : rgb) {
        unsigned char b[4];
        if (!in.read(reinterpret_cast<char*>(b), 4))
          throw ImageReadError(path.string() + ": truncated PFM file");
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

}  // namespace glint
