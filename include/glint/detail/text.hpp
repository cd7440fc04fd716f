#pragma once
// Building error messages: joining pieces and printing floats, the same way everywhere.

#include <charconv>
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

/// Shortest round-trip text of a float; unlike std::to_string it ignores the C locale.
inline std::string format_number(float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (result.ec != std::errc{}) return "?";
  return std::string(buffer, result.ptr);
}

}  // namespace detail

}  // namespace glint::inline GLINT_ISA_NAMESPACE
