#pragma once
// Writing a Film: 8-bit sRGB PNG (through Debian's libstb) and linear float PFM. Both are
// written to a temporary file beside the target and renamed into place, so a failed write
// never leaves a truncated image behind.

#include <stb_image_write.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "glint/error.hpp"
#include "glint/image/film.hpp"

namespace glint {

/// The sRGB transfer function (IEC 61966-2-1) from linear [0,1] to an 8-bit code value.
inline std::uint8_t linear_to_srgb8(float linear) {
  if (!(linear > 0.0f)) return 0;  // also maps NaN to black
  if (linear >= 1.0f) return 255;
  const float encoded =
      linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(encoded * 255.0f));
}

namespace detail {

inline void write_file_atomically(const std::filesystem::path& path,
                                  const std::vector<char>& bytes) {
  std::filesystem::path temporary = path;
  temporary += ".glint-partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw ImageWriteError("cannot write " + path.string() + ": " + std::strerror(errno));
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw ImageWriteError("cannot write " + path.string() + ": write failed");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw ImageWriteError("cannot write " + path.string() + ": " + error.message());
  }
}

}  // namespace detail

/// 8-bit RGB, sRGB-encoded, no tone mapping: radiance above 1 clips.
inline std::vector<std::uint8_t> to_srgb8(const Film& film) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(film.pixels().size() * 3);
  for (const Color& c : film.pixels()) {
    bytes.push_back(linear_to_srgb8(c.x));
    bytes.push_back(linear_to_srgb8(c.y));
    bytes.push_back(linear_to_srgb8(c.z));
  }
  return bytes;
}

inline void write_png(const Film& film, const std::filesystem::path& path) {
  const std::vector<std::uint8_t> pixels = to_srgb8(film);
  std::vector<char> encoded;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<char>*>(context);
    out->insert(out->end(), static_cast<char*>(data), static_cast<char*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &encoded, film.width(), film.height(), 3, pixels.data(),
                              film.width() * 3))
    throw ImageWriteError("cannot write " + path.string() + ": PNG encoding failed");
  detail::write_file_atomically(path, encoded);
}

/// Portable float map: linear RGB, little-endian (negative scale), rows bottom to top.
inline void write_pfm(const Film& film, const std::filesystem::path& path) {
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
  detail::write_file_atomically(path, bytes);
}

}  // namespace glint
