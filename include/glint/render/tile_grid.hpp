#pragma once
// The image cut into square tiles, the unit of work of a render: a tile's pixels are written by
// the one thread that renders it, so tiles can be handed out in any order, to any thread or
// process (Renderer::render_tiles), without changing a pixel.

#include <algorithm>
#include <cstddef>

#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Pixels [x0, x1) x [y0, y1).
struct Tile {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  std::size_t pixel_count() const { return std::size_t(width()) * std::size_t(height()); }
};

/// Square tiles of `size` pixels, numbered row by row from the top left; those of the last
/// column and row are cut at the image's edge.
struct TileGrid {
  TileGrid(int image_width, int image_height, int tile_size)
      : size(tile_size),
        width(image_width),
        height(image_height),
        columns((width + size - 1) / size),
        count(std::size_t(columns) * std::size_t((height + size - 1) / size)) {}
  /// The grid a render with these settings uses (their size and tile_size).
  explicit TileGrid(const RenderSettings& settings)
      : TileGrid(settings.width, settings.height, settings.tile_size) {}

  /// Tile `index`, below `count`.
  Tile tile(std::size_t index) const {
    const int x0 = int(index % std::size_t(columns)) * size;
    const int y0 = int(index / std::size_t(columns)) * size;
    return {x0, y0, std::min(x0 + size, width), std::min(y0 + size, height)};
  }

  int size, width, height, columns;
  std::size_t count;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
