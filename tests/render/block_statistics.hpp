#pragma once
// Statistical comparison of two renderers' images: each renders a 16x16 image with several
// seeds, and the mean radiance of every 4x4-pixel block, with its standard error over the
// seeds, must agree between them within five standard errors of the difference.

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"

namespace glint_test {

inline constexpr int kSeeds = 8;
inline constexpr int kBlock = 4;
inline constexpr int kBlocksPerSide = 4;
inline constexpr int kBlockImageSize = kBlock * kBlocksPerSide;

struct BlockStatistics {
  std::array<double, kBlocksPerSide * kBlocksPerSide> mean{};
  std::array<double, kBlocksPerSide * kBlocksPerSide> standard_error{};
};

/// The block means of renderer R (a Renderer or a WavefrontRenderer) over kSeeds renders with
/// seeds first_seed, first_seed + 1, ...; `settings` as the scene asks by default, resized to
/// kBlockImageSize pixels square.
template <typename R>
BlockStatistics render_blocks(const glint::Scene& scene, std::uint64_t first_seed,
                              glint::RenderSettings settings) {
  settings.width = kBlockImageSize;
  settings.height = kBlockImageSize;
  settings.threads = 2;
  std::array<std::vector<double>, kBlocksPerSide * kBlocksPerSide> per_seed;
  for (int seed = 0; seed < kSeeds; ++seed) {
    settings.seed = std::uint64_t(seed) + first_seed;
    const glint::RenderResult result = glint_test::render_by<R>(scene, settings);
    REQUIRE(result.stats.invalid_samples == 0);
    std::array<double, kBlocksPerSide * kBlocksPerSide> sums{};
    for (int y = 0; y < settings.height; ++y)
      for (int x = 0; x < settings.width; ++x) {
        const glint::Color& c = result.film.at(x, y);
        sums[std::size_t((y / kBlock) * kBlocksPerSide + x / kBlock)] += c.x + c.y + c.z;
      }
    for (std::size_t b = 0; b < sums.size(); ++b)
      per_seed[b].push_back(sums[b] / (kBlock * kBlock));
  }
  BlockStatistics stats;
  for (std::size_t b = 0; b < per_seed.size(); ++b) {
    double sum = 0.0, sum2 = 0.0;
    for (const double v : per_seed[b]) {
      sum += v;
      sum2 += v * v;
    }
    const double mean = sum / kSeeds;
    const double variance = std::max(0.0, (sum2 - kSeeds * mean * mean) / (kSeeds - 1));
    stats.mean[b] = mean;
    stats.standard_error[b] = std::sqrt(variance / kSeeds);
  }
  return stats;
}

template <typename R>
BlockStatistics render_blocks(const glint::Scene& scene, std::uint64_t first_seed) {
  return render_blocks<R>(scene, first_seed, glint::RenderSettings::from(scene));
}

/// Checks every block of `candidate` against `reference` (five standard errors of the
/// difference, and a relative 1e-4 for blocks without noise); returns the sum of the
/// reference's block means, for the caller to check that the scene is lit.
inline double check_blocks_agree(const BlockStatistics& reference,
                                 const BlockStatistics& candidate) {
  double total_reference = 0.0;
  for (std::size_t b = 0; b < reference.mean.size(); ++b) {
    const double tolerance =
        5.0 * std::hypot(reference.standard_error[b], candidate.standard_error[b]) +
        1e-4 * std::abs(reference.mean[b]);
    INFO("block " << b << ": reference " << reference.mean[b] << " +- "
                  << reference.standard_error[b] << ", candidate " << candidate.mean[b] << " +- "
                  << candidate.standard_error[b]);
    CHECK(std::abs(candidate.mean[b] - reference.mean[b]) <= tolerance);
    total_reference += reference.mean[b];
  }
  return total_reference;
}

}  // namespace glint_test
