#pragma once
// An image to be looked up by continuous coordinates: linear RGB texels and their bilinear
// filtering over (u, v) in the unit square, u wrapping around (a longitude) and v clamped at the
// top and bottom edges (the poles). Immutable once built, so that spheres and threads share one.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "glint/error.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class Texture {
 public:
  /// `texels`: `width` x `height` linear RGB values, row by row from the top, each component
  /// finite and non-negative (ImageReadError naming `name` and the texel otherwise). `name`
  /// says where the image came from: the path as a scene file gives it.
  Texture(std::string name, int width, int height, std::vector<Color> texels)
      : name_(std::move(name)), width_(width), height_(height), texels_(std::move(texels)) {
    if (width < 1 || height < 1 || texels_.size() != std::size_t(width) * std::size_t(height))
      throw ImageReadError(name_ + ": a texture needs width x height texels (" +
                           std::to_string(width) + "x" + std::to_string(height) + ", " +
                           std::to_string(texels_.size()) + " given)");
    for (std::size_t i = 0; i < texels_.size(); ++i) {
      const Color& c = texels_[i];
      if (!(c.r >= 0.0f && c.g >= 0.0f && c.b >= 0.0f) || !std::isfinite(c.r) ||
          !std::isfinite(c.g) || !std::isfinite(c.b))
        throw ImageReadError(name_ + ": texel (" + std::to_string(i % std::size_t(width)) + ", " +
                             std::to_string(i / std::size_t(width)) +
                             ") is not a finite, non-negative colour");
    }
  }

  const std::string& name() const { return name_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<Color>& texels() const { return texels_; }
  const Color& at(int x, int y) const {
    return texels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
  }

  /// The image at (u, v), u in [0, 1] from the left edge, v in [0, 1] from the top, between the
  /// four nearest texel centres: texel (x, y) is centred on ((x + 0.5) / width, (y + 0.5) /
  /// height). Columns wrap around (u = 0 and u = 1 meet), rows end at the edges. Each blend is
  /// a + t (b - a), so an image of one colour gives that colour exactly.
  Color filtered(float u, float v) const {
    const float x = u * float(width_) - 0.5f;
    const float y = v * float(height_) - 0.5f;
    const float x_floor = std::floor(x), y_floor = std::floor(y);
    const float tx = x - x_floor, ty = y - y_floor;
    // u is in [0, 1], so x_floor is in [-1, width]: one wrap either way.
    int x0 = int(x_floor);
    x0 = x0 < 0 ? x0 + width_ : x0 >= width_ ? x0 - width_ : x0;
    const int x1 = x0 + 1 == width_ ? 0 : x0 + 1;
    const int y_top = int(y_floor);
    const int y0 = y_top < 0 ? 0 : y_top >= height_ ? height_ - 1 : y_top;
    const int y1 = y_top + 1 < 0 ? 0 : y_top + 1 >= height_ ? height_ - 1 : y_top + 1;
    const auto blend = [](const Color& a, const Color& b, float t) { return a + t * (b - a); };
    return blend(blend(at(x0, y0), at(x1, y0), tx), blend(at(x0, y1), at(x1, y1), tx), ty);
  }

 private:
  std::string name_;
  int width_;
  int height_;
  std::vector<Color> texels_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
