#pragma once
// The metals a scene names (`metal=gold`): their complex refractive index n + ik at the red, green
// and blue primaries, for the mirror lobe's Fresnel reflectance (scene/material.hpp): measured
// spectra reduced to the three primaries, as renderers that work in RGB tabulate them. At normal
// incidence they reflect about (0.97, 0.80, 0.32) for gold, (0.97, 0.96, 0.91) for silver,
// (0.95, 0.62, 0.51) for copper and (0.93, 0.92, 0.92) for aluminium.

#include <array>
#include <cstddef>
#include <iterator>
#include <optional>
#include <string_view>

#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A metal's complex refractive index at the red, green and blue primaries.
struct Metal {
  std::string_view name;
  Color eta;  ///< n, the real part of the index
  Color k;    ///< the extinction coefficient, its imaginary part
};

namespace detail {
/// The table as plain numbers, so that it is constant-initialised: a table of Colors would be
/// built before main by code of each instruction set glint-render holds, which a CPU without the
/// widest of them cannot run.
struct MetalEntry {
  std::string_view name;
  float eta[3];
  float k[3];
};
inline constexpr MetalEntry kMetalTable[] = {
    {"gold", {0.143f, 0.375f, 1.442f}, {3.983f, 2.386f, 1.603f}},
    {"silver", {0.155f, 0.117f, 0.138f}, {4.828f, 3.122f, 2.147f}},
    {"copper", {0.200f, 0.924f, 1.102f}, {3.913f, 2.453f, 2.142f}},
    {"aluminium", {1.657f, 0.880f, 0.521f}, {9.224f, 6.270f, 4.837f}},
};
}  // namespace detail

/// The names of the metals glint knows, in the table's order.
inline constexpr auto kMetalNames = [] {
  std::array<std::string_view, std::size(detail::kMetalTable)> names{};
  for (std::size_t i = 0; i < names.size(); ++i)
    names[i] = detail::kMetalTable[i].name;
  return names;
}();

/// The metal called `name`, if glint knows it.
inline std::optional<Metal> metal_named(std::string_view name) {
  for (const detail::MetalEntry& entry : detail::kMetalTable)
    if (entry.name == name)
      return Metal{entry.name, Color(entry.eta[0], entry.eta[1], entry.eta[2]),
                   Color(entry.k[0], entry.k[1], entry.k[2])};
  return std::nullopt;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
