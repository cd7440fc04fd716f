#pragma once
// Text from a file the user did not write (a checkpoint's variant name) shown in a message:
// escaped, so that a forged file cannot put newlines, terminal escape sequences or megabytes
// into the messages, and bounded.

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// `text` with every byte outside printable ASCII, and the backslash, written as \xNN, cut
/// after `max_bytes` bytes of it (then "..." follows).
inline std::string escaped(std::string_view text, std::size_t max_bytes = 64) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < max_bytes; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7f && byte != '\\') {
      out += char(byte);
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      out += hex;
    }
  }
  if (text.size() > max_bytes) out += "...";
  return out;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
