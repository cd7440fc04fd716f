#pragma once
// Building text: joining message pieces, printing floats the same way everywhere (error
// messages, scene files, the options a generated file records), and JSON strings.

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <string_view>
#include <system_error>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

namespace detail {

/// Joins message pieces. Unlike a chain of `"literal" + std::string(...)`, this does not set
/// off GCC 12's false -Wrestrict warning (GCC bug 105651) when inlined.
inline std::string concat(std::initializer_list<std::string_view> parts) {
  std::size_t size = 0;
  for (std::string_view part : parts)
    size += part.size();
  std::string out;
  out.reserve(size);
  for (std::string_view part : parts)
    out.append(part);
  return out;
}

/// How a float is spelt. Either way the text has the fewest significant digits that read back
/// (std::strtof, std::from_chars) as the same float, bit for bit, -0 and subnormals included.
enum class FloatNotation {
  /// std::to_chars's shortest text, plain or scientific, whichever is shorter: 0.1, 1e+05.
  shortest,
  /// Plain notation unless it is more than 3 characters longer than the shortest text, so that
  /// a file to read and edit by hand says 100000 rather than 1e+05 (but 1e+30 and 1e-07).
  plain_unless_long,
};

/// The most characters write_number writes: the smallest subnormal in plain notation, with its
/// sign, "-0.000...0001" (the 1 is the 45th decimal).
inline constexpr std::size_t kMaxFloatTextLength = 48;

/// Writes the text of `value` to `out`, which has room for kMaxFloatTextLength characters, and
/// returns the end of the text. Infinities and NaNs are "inf", "-inf", "nan" and "-nan". Unlike
/// std::to_string and printf it ignores the C locale. The one place glint spells a float as text.
inline char* write_number(char* out, float value,
                          FloatNotation notation = FloatNotation::shortest) {
  char shortest[kMaxFloatTextLength];
  const char* const shortest_end = std::to_chars(shortest, shortest + sizeof shortest, value).ptr;
  if (notation == FloatNotation::plain_unless_long) {
    // Without a precision, std::to_chars writes the fewest digits that read back in the format
    // asked for as well.
    const auto plain =
        std::to_chars(out, out + kMaxFloatTextLength, value, std::chars_format::fixed);
    if (plain.ec == std::errc{} && plain.ptr - out <= shortest_end - shortest + 3) return plain.ptr;
  }
  return std::copy(static_cast<const char*>(shortest), shortest_end, out);
}

/// Appends the text of `value` (write_number) to `out`.
inline void append_number(std::string& out, float value,
                          FloatNotation notation = FloatNotation::shortest) {
  char text[kMaxFloatTextLength];
  out.append(text, write_number(text, value, notation));
}

/// The text of `value` (write_number).
inline std::string format_number(float value, FloatNotation notation = FloatNotation::shortest) {
  std::string out;
  append_number(out, value, notation);
  return out;
}

/// `text` as a JSON string: quotes and backslashes escaped, control characters, DEL and '<' as
/// \u00XX ('<' so that the JSON can sit in an HTML <script> element, which "</script>" would
/// end); other bytes as they are (UTF-8 stays readable).
inline std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f || c == '<') {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", unsigned(byte));
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace detail

}  // namespace glint::inline GLINT_ISA_NAMESPACE
