#pragma once
// The settings of an image (size, samples per pixel, depth, pixel filter width): their
// defaults, their limits and the one check of both. A scene file's `image` statement, the
// random scene generator, RenderSettings and glint-render's options all take them from here.

#include <cstdint>
#include <string>

#include "glint/detail/text.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The report's settings (800x800 pixels, 1000 samples per pixel, 12 bounces, a Gaussian pixel
/// filter of standard deviation half a pixel): what a scene that sets nothing renders with.
namespace defaults {
inline constexpr int image_width = 800;
inline constexpr int image_height = 800;
inline constexpr int samples_per_pixel = 1000;
inline constexpr int max_depth = 12;            ///< most bounces after the camera ray
inline constexpr float antialias_sigma = 0.5f;  ///< pixels
}  // namespace defaults

/// Limits that reject absurd input before it turns into a huge allocation or an endless render.
namespace limits {
inline constexpr int max_image_side = 1 << 15;
/// A float RGB film of this many pixels takes 768 MiB; a side limit alone would allow 12 GiB.
inline constexpr std::int64_t max_image_pixels = std::int64_t{1} << 26;
inline constexpr int max_samples_per_pixel = 1 << 20;
inline constexpr int max_depth = 1024;
inline constexpr float max_antialias_sigma = 100.0f;  ///< pixels
inline constexpr int max_threads = 4096;
inline constexpr int max_tile_size = 1024;
/// The most rays one camera sample of the report's tree model may trace in the worst case
/// (render/work_estimate.hpp). At the report's 800x800 pixels and 1000 samples even 16 rays a
/// sample are 10^10 rays; 2^20 lets every scene of the report through at its own depth and
/// refuses the exponential cases (mirror-and-glass spheres 20 bounces deep).
inline constexpr double max_tree_rays_per_sample = 1 << 20;
}  // namespace limits

/// An image's size, samples per pixel and depth: what a scene file's `image` statement sets,
/// and where RenderSettings starts from.
struct ImageSettings {
  int width = defaults::image_width;
  int height = defaults::image_height;
  int samples_per_pixel = defaults::samples_per_pixel;
  int max_depth = defaults::max_depth;  ///< most bounces after the camera ray; 0: direct light
};

/// The first thing wrong with an image's size, samples per pixel or depth (named as in the
/// scene format), or an empty string when all are within the limits.
inline std::string image_settings_problem(const ImageSettings& image) {
  using detail::concat;
  const auto [width, height, samples_per_pixel, max_depth] = image;
  if (width < 1 || width > limits::max_image_side || height < 1 || height > limits::max_image_side)
    return concat({"image size must be between 1 and ", std::to_string(limits::max_image_side),
                   " pixels a side, got ", std::to_string(width), "x", std::to_string(height)});
  if (std::int64_t{width} * height > limits::max_image_pixels)
    return concat({"image size ", std::to_string(width), "x", std::to_string(height), " exceeds ",
                   std::to_string(limits::max_image_pixels), " pixels"});
  if (samples_per_pixel < 1 || samples_per_pixel > limits::max_samples_per_pixel)
    return concat({"spp must be between 1 and ", std::to_string(limits::max_samples_per_pixel),
                   ", got ", std::to_string(samples_per_pixel)});
  if (max_depth < 0 || max_depth > limits::max_depth)
    return concat({"max_depth must be between 0 and ", std::to_string(limits::max_depth), ", got ",
                   std::to_string(max_depth)});
  return {};
}

/// What is wrong with a pixel filter width, or an empty string.
inline std::string antialias_sigma_problem(float sigma) {
  if (sigma >= 0.0f && sigma <= limits::max_antialias_sigma) return {};
  return detail::concat({"antialias sigma must be in [0, ",
                         detail::format_number(limits::max_antialias_sigma), "] pixels, got ",
                         detail::format_number(sigma)});
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
