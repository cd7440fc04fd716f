#pragma once
// Memory that cannot be had, reported by what needed it and how much where that is known ("out
// of memory for the image of 32768x2048 pixels: ..."), rather than as std::bad_alloc.

#include <cstdint>
#include <cstdio>
#include <new>
#include <string>
#include <utility>

#include "glint/error.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// "12.3 MB", "2.42 GB".
inline std::string byte_size(double bytes) {
  char text[32];
  if (bytes < 1e9)
    std::snprintf(text, sizeof text, "%.1f MB", bytes * 1e-6);
  else
    std::snprintf(text, sizeof text, "%.2f GB", bytes * 1e-9);
  return text;
}

/// Calls `step` and returns what it returns; an allocation that fails in it becomes a
/// glint::Error "out of memory " + what() (what() is called only then).
template <typename Step, typename What>
decltype(auto) with_memory_for(const What& what, Step&& step) {
  try {
    return std::forward<Step>(step)();
  } catch (const std::bad_alloc&) {
    throw glint::Error("out of memory " + what());
  }
}

/// What a render of `settings` holds for its image: 24 bytes a pixel of sums (double), 12 of
/// film, 48 of splat sums where the renderer splats, and as much again for the sums of a resumed
/// checkpoint.
inline std::string image_memory(const glint::RenderSettings& settings, bool resumed, bool splats) {
  const double pixels = double(settings.width) * double(settings.height);
  const int sums = 24 + (splats ? 48 : 0);
  const int per_pixel = sums + 12 + (resumed ? sums : 0);
  return "for the image of " + std::to_string(settings.width) + "x" +
         std::to_string(settings.height) + " pixels: rendering it needs about " +
         byte_size(pixels * per_pixel) + " (" + std::to_string(per_pixel) +
         " bytes a pixel: its sums" + (splats ? " and splats" : "") + ", its film" +
         (resumed ? ", the checkpoint's sums" : "") + ")";
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
