#pragma once
// Tone mapping: linear radiance to a display value in [0, 1], applied before the sRGB curve
// when an 8-bit image is written. The film and the PFM/EXR files keep the linear radiance.
//
// Every operator works on each channel alone, so that the same value maps the same way in
// every channel and the operators' known values (0, 1, a large value) hold channel by channel.
// Per-channel curves desaturate very bright colours towards white, as film does.

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

enum class ToneMapOperator {
  /// Radiance above 1 is shown as 1: the report's images, and glint's default.
  clip,
  /// x / (1 + x): every radiance keeps a distinct value, 1 becomes one half.
  reinhard,
  /// Narkowicz's 2015 rational fit of the ACES filmic curve (RRT and ODT): a toe and a soft
  /// shoulder, reaching 1 at a radiance of about 7.2.
  aces,
};

/// The operators' names, as the command line and the documentation spell them; the one list
/// that parsing, messages and help text are made from.
inline constexpr std::array<std::pair<std::string_view, ToneMapOperator>, 3> kToneMapOperators{{
    {"clip", ToneMapOperator::clip},
    {"reinhard", ToneMapOperator::reinhard},
    {"aces", ToneMapOperator::aces},
}};

inline constexpr std::string_view name_of(ToneMapOperator op) {
  for (const auto& [name, value] : kToneMapOperators)
    if (value == op) return name;
  return "unknown";
}

inline constexpr std::optional<ToneMapOperator> parse_tone_map_operator(std::string_view name) {
  for (const auto& [known, value] : kToneMapOperators)
    if (known == name) return value;
  return std::nullopt;
}

/// "clip, reinhard or aces": the names for a message.
inline std::string tone_map_operator_list() {
  std::string list;
  for (std::size_t i = 0; i < kToneMapOperators.size(); ++i) {
    if (i > 0) list += i + 1 == kToneMapOperators.size() ? " or " : ", ";
    list += kToneMapOperators[i].first;
  }
  return list;
}

namespace limits {
/// Exposure is a power of two: beyond +-64 EV a float radiance over- or underflows anyway.
inline constexpr float max_exposure = 64.0f;
}  // namespace limits

/// An exposure written as text ("-1.5"): the number of stops, or nullopt unless the whole text
/// is a decimal number within +-limits::max_exposure (so never NaN or infinite).
inline std::optional<float> parse_exposure(std::string_view text) {
  float value = 0.0f;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() ||
      !(std::abs(value) <= limits::max_exposure))
    return std::nullopt;
  return value;
}

/// "stops from -64 to 64": the exposure's range for a message.
inline std::string exposure_range_text() {
  const std::string bound = std::to_string(int(limits::max_exposure));
  return "stops from -" + bound + " to " + bound;
}

/// The display value in [0, 1] of one channel's linear radiance, which may be anything: NaN,
/// negative values and -inf give 0, +inf gives 1. Non-decreasing in `linear`.
inline float tone_map(float linear, ToneMapOperator op) {
  if (!(linear > 0.0f)) return 0.0f;
  switch (op) {
    case ToneMapOperator::clip:
      return linear < 1.0f ? linear : 1.0f;
    // The curves are evaluated in double: rounded once to float, they stay non-decreasing,
    // which float arithmetic with its several roundings does not promise.
    case ToneMapOperator::reinhard: {
      if (linear == std::numeric_limits<float>::infinity()) return 1.0f;  // not inf / inf
      const double x = linear;
      return static_cast<float>(x / (1.0 + x));
    }
    case ToneMapOperator::aces: {
      // The curve passes 1 at x = 7.24 and keeps rising towards 2.51 / 2.43, so it is cut at 1.
      if (linear >= 8.0f) return 1.0f;
      const double x = linear;
      const double curve = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
      return curve < 1.0 ? static_cast<float>(curve) : 1.0f;
    }
  }
  return 0.0f;
}

/// How linear radiance becomes an 8-bit image: scaled by 2^exposure, then mapped by `op`.
struct ToneMapping {
  ToneMapOperator op = ToneMapOperator::clip;
  /// In stops (EV): +1 doubles the radiance before the operator. Within +-limits::max_exposure.
  float exposure = 0.0f;

  /// The display value in [0, 1] of one channel. Exposure 0 scales by exactly 1, so the
  /// default mapping is the plain clip of the radiance.
  float operator()(float linear) const { return tone_map(linear * scale(), op); }
  float scale() const { return std::exp2(exposure); }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
