#pragma once
// False colour for maps of positive values spanning decades (glint-compare's error maps): a
// log scale onto [0, 1], then a colour ramp whose luminance rises from black to near white,
// so that the map reads in the right order even in grey or to a colour-blind eye.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

/// The ramp's control points, sRGB-encoded, at equal steps from 0 to 1: black, indigo,
/// magenta, red-orange, amber, pale yellow. Interpolating linearly between the encoded values
/// is what a CSS linear-gradient does, so a page can draw the legend from the same points.
inline constexpr std::array<Rgb8, 6> kErrorRamp{{
    {0, 0, 4},
    {44, 16, 92},
    {140, 28, 110},
    {224, 72, 58},
    {252, 166, 54},
    {252, 252, 216},
}};

/// The ramp's colour at t: 0 is the first control point, 1 the last, values outside [0, 1]
/// clamp to the ends. NaN gives the last colour: a value that is not known is shown as the
/// worst, never hidden as the best.
inline Rgb8 error_ramp(float t) {
  if (!(t >= 0.0f)) t = std::isnan(t) ? 1.0f : 0.0f;
  if (t > 1.0f) t = 1.0f;
  const float position = t * float(kErrorRamp.size() - 1);
  const std::size_t i = std::min(std::size_t(position), kErrorRamp.size() - 2);
  const float f = position - float(i);
  const auto mix = [f](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(float(a) + (float(b) - float(a)) * f));
  };
  const Rgb8& a = kErrorRamp[i];
  const Rgb8& b = kErrorRamp[i + 1];
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

/// Where `value` lies from `low` to `high` on a log scale: 0 at or below low (zero and
/// negative values too), 1 at or above high, NaN (a value not known) at 1. Needs
/// 0 < low < high.
inline float log_scale_position(double value, double low, double high) {
  if (std::isnan(value)) return 1.0f;
  if (!(value > low)) return 0.0f;
  if (value >= high) return 1.0f;
  return static_cast<float>(std::log(value / low) / std::log(high / low));
}

/// 8-bit RGB (row by row, three bytes a value) of `values` through log_scale_position and
/// error_ramp.
inline std::vector<std::uint8_t> false_color_rgb8(const std::vector<float>& values, double low,
                                                  double high) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(values.size() * 3);
  for (const float v : values) {
    const Rgb8 c = error_ramp(log_scale_position(v, low, high));
    bytes.insert(bytes.end(), {c.r, c.g, c.b});
  }
  return bytes;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
