#pragma once
// Helpers of the EXR tests: scratch directories, films of chosen values, bitwise comparison.

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/scratch_directory.hpp"
#include "glint/image/film.hpp"

namespace glint::exr_test {

using glint_test::ScratchDirectory;

inline std::uint32_t bits(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

/// A width x height film whose channel values are `values` in turn, repeated as needed (row
/// 0 first, then R, G, B of each pixel).
inline Film film_of(int width, int height, const std::vector<float>& values) {
  Film film(width, height);
  std::size_t next = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        film.at(x, y)[c] = values[next++ % values.size()];
  return film;
}

/// Values at every pixel and channel with random 23-bit mantissas (so that a flipped or
/// shifted image shows) and binary exponents in [min_exponent, max_exponent]: by default about
/// 1e-6 to 1e6.
inline Film varied_film(int width, int height, int min_exponent = -20, int max_exponent = 19) {
  Film film(width, height);
  std::uint64_t state = 0x9e3779b97f4a7c15ULL;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const float mantissa = 1.0f + float(state >> 41) * 0x1p-23f;
        const int exponent =
            min_exponent + int((state >> 20) % std::uint64_t(max_exponent - min_exponent + 1));
        film.at(x, y)[c] = std::ldexp(mantissa, exponent);
      }
  return film;
}

/// Whether every channel value of `a` and `b` has the same bits (NaN included).
inline bool same_bits(const Film& a, const Film& b) {
  if (a.width() != b.width() || a.height() != b.height()) return false;
  for (std::size_t i = 0; i < a.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (bits(a.pixels()[i][c]) != bits(b.pixels()[i][c])) return false;
  return true;
}

}  // namespace glint::exr_test
