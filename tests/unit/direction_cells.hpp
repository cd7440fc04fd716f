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
#include "statistics.hpp"

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
/// a kSub x kSub grid per cell in (cos theta, phi), in which solid angle is area.
template <int kSub = 8, typename Density>
std::vector<double> cell_masses(Density&& pdf) {
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

/// Where the cells' pole lies: +z, or +y (for lobes about the plane y = 0 that reach the z
/// poles, such as refraction into glass, whose narrow lobe would fall within one row of the
/// cells' midpoint rule there).
enum class CellPole { z, y };

/// Chi-square of `n` sampled directions against the density `pdf` they claim (per unit solid
/// angle): `draw()` gives a sample with `direction` and `delta`, the delta samples (and those
/// that carry nothing) counted in one more cell, which gets the mass the density leaves.
template <int kSub = 8, typename Draw, typename Density>
ChiSquare sampling_against_density(Draw&& draw, Density&& pdf, int n, CellPole pole = CellPole::z) {
  const auto to_cells = [&](const glint::Vec3& d) {
    return pole == CellPole::z ? d : glint::Vec3(d.z, d.x, d.y);
  };
  const auto from_cells = [&](const glint::Vec3& c) {
    return pole == CellPole::z ? c : glint::Vec3(c.y, c.z, c.x);
  };
  std::vector<double> observed(kCells + 1, 0.0);
  std::vector<double> expected(kCells + 1, 0.0);
  for (int i = 0; i < n; ++i) {
    const auto s = draw();
    ++observed[s.delta ? std::size_t(kCells) : std::size_t(cell_of(to_cells(s.direction)))];
  }
  const std::vector<double> mass =
      cell_masses<kSub>([&](const glint::Vec3& c) { return pdf(from_cells(c)); });
  double total = 0.0;
  for (int c = 0; c < kCells; ++c) {
    expected[std::size_t(c)] = n * mass[std::size_t(c)];
    total += mass[std::size_t(c)];
  }
  expected[kCells] = n * std::max(0.0, 1.0 - total);
  return chi_square_pooled(observed, expected);
}

}  // namespace glint::test
