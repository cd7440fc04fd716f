#pragma once
// The image type that rendering produces and image files are written from or read into.

#include <cstddef>
#include <vector>

#include "glint/math/vector.hpp"

namespace glint {

/// Linear radiance per pixel, row-major from the top-left, black when made. Tone mapping and the
/// sRGB transfer happen only when writing 8-bit images. A render also keeps its per-pixel sums
/// of samples in one between passes.
class Film {
 public:
  Film() = default;
  Film(int width, int height)
      : width_(width),
        height_(height),
        pixels_(std::size_t(width) * std::size_t(height), Color(0.0f)) {}

  int width() const { return width_; }
  int height() const { return height_; }
  Color& at(int x, int y) { return pixels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)]; }
  const Color& at(int x, int y) const {
    return pixels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
  }
  const std::vector<Color>& pixels() const { return pixels_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Color> pixels_;
};

}  // namespace glint
