#pragma once
// The sphere of directions in cells of equal solid angle, for chi-square tests of sampled
// directions against a density: bands of cos(theta) about +z times sectors of phi. The band
// edges include cos = 0 (where a lobe's density drops to zero) and every multiple of 1/8.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "glint/math/vector.hpp"

namespace glint::test {

constexpr int kBands = 16;
constexpr int kSectors = 32;
constexpr int kCells = kBands * kSectors;

inline int cell_of(const glint::Vec3& direction) {
  const double cosine = std::clamp(double(direction.z), -1.0, 1.0);
  const int band = std::min(int((cosine + 1.0) / 2.0 * kBands), kBands - 1);
  const double phi = std::atan2(double(direction.y), double(direction.x));
  const int sector = std::clamp(int((phi + std::numbers::pi) / (2.0 * std::numbers::pi) * kSectors),
                                0, kSectors - 1);
  return band * kSectors + sector;
}

/// The probability of each cell under density `pdf` (per unit solid angle): a midpoint rule on
/// an 8 x 8 grid per cell in (cos theta, phi), in which solid angle is area.
template <typename Density>
std::vector<double> cell_masses(Density&& pdf) {
  constexpr int kSub = 8;
  const double d_cos = 2.0 / (kBands * kSub), d_phi = 2.0 * std::numbers::pi / (kSectors * kSub);
  std::vector<double> mass(kCells, 0.0);
  for (int i = 0; i < kBands * kSub; ++i) {
    const double cosine = -1.0 + (i + 0.5) * d_cos;
    const double sine = std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
    for (int j = 0; j < kSectors * kSub; ++j) {
      const double phi = -std::numbers::pi + (j + 0.5) * d_phi;
      const glint::Vec3 direction(float(sine * std::cos(phi)), float(sine * std::sin(phi)),
                                  float(cosine));
      mass[std::size_t((i / kSub) * kSectors + j / kSub)] += double(pdf(direction)) * d_cos * d_phi;
    }
  }
  return mass;
}

}  // namespace glint::test
