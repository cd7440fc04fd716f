#pragma once
// Statistical comparison of two renderers' images. Each renders a 16x16 image with many seeds;
// the mean radiance (sum of channels) of every 4x4-pixel block and of the whole image, one
// value per seed, gives a mean with its standard error over the seeds. The blocks find a
// difference in one place, the whole image a small difference spread over all of it. Each
// comparison is one entry of the test case's ComparisonFamily (significance.hpp), which judges
// them together at the suite's false-alarm budget.

#include <array>
#include <catch2/catch.hpp>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "../support/significance.hpp"
#include "glint/render/renderer.hpp"
#include "renderer_types.hpp"

namespace glint_test {

/// Renders per estimate. Many renders of few samples rather than few of many: the same cost,
/// but the standard errors come with many degrees of freedom, so the t thresholds stay close
/// to the normal ones.
inline constexpr int kReplicates = 32;
inline constexpr int kBlock = 4;
inline constexpr int kBlocksPerSide = 4;
inline constexpr int kBlockImageSize = kBlock * kBlocksPerSide;
inline constexpr std::size_t kBlocks = kBlocksPerSide * kBlocksPerSide;
/// Index of the whole image among the per-seed values.
inline constexpr std::size_t kWholeImage = kBlocks;

/// per_seed[b][s]: the mean radiance of block b (kWholeImage: of the whole image) in the
/// render with the s-th seed.
struct BlockSamples {
  std::array<std::vector<double>, kBlocks + 1> per_seed;
};

/// Renderer R's blocks (a Renderer or a WavefrontRenderer) over kReplicates renders with seeds
/// first_seed, first_seed + 1, ...: `settings` resized to kBlockImageSize pixels square, each
/// render with the given samples per pixel.
template <typename R>
BlockSamples render_blocks(const glint::Scene& scene, std::uint64_t first_seed,
                           glint::RenderSettings settings) {
  settings.width = kBlockImageSize;
  settings.height = kBlockImageSize;
  settings.threads = 2;
  BlockSamples samples;
  for (int seed = 0; seed < kReplicates; ++seed) {
    settings.seed = std::uint64_t(seed) + first_seed;
    const glint::RenderResult result = glint_test::render_by<R>(scene, settings);
    REQUIRE(result.stats.invalid_samples == 0);
    std::array<double, kBlocks> sums{};
    for (int y = 0; y < settings.height; ++y)
      for (int x = 0; x < settings.width; ++x) {
        const glint::Color& c = result.film.at(x, y);
        sums[std::size_t((y / kBlock) * kBlocksPerSide + x / kBlock)] += c.x + c.y + c.z;
      }
    double image = 0.0;
    for (std::size_t b = 0; b < kBlocks; ++b) {
      samples.per_seed[b].push_back(sums[b] / (kBlock * kBlock));
      image += sums[b];
    }
    samples.per_seed[kWholeImage].push_back(image / (kBlockImageSize * kBlockImageSize));
  }
  return samples;
}

/// As above with `samples_per_pixel` samples per render and the scene's other settings.
template <typename R>
BlockSamples render_blocks(const glint::Scene& scene, std::uint64_t first_seed,
                           int samples_per_pixel) {
  glint::RenderSettings settings = glint::RenderSettings::from(scene);
  settings.samples_per_pixel = samples_per_pixel;
  return render_blocks<R>(scene, first_seed, settings);
}

inline std::string block_name(std::size_t b) {
  if (b == kWholeImage) return "whole image";
  std::ostringstream name;
  name << "block " << b % kBlocksPerSide << "," << b / kBlocksPerSide;
  return name.str();
}

/// A difference this small relative to the reference is float rounding, not evidence: two
/// renderers may add the same light in another order.
inline constexpr double kRelativeRounding = 1e-4;

/// Adds to `family` the comparisons of two independent estimates (different seeds, or
/// renderers whose paths differ): Welch's test for every block and the whole image. Returns the
/// reference's whole-image mean, for the caller to check that the comparison is not between
/// zeros.
inline double compare_independent(ComparisonFamily& family, const std::string& what,
                                  const BlockSamples& reference, const BlockSamples& candidate) {
  for (std::size_t b = 0; b <= kBlocks; ++b) {
    const MeanEstimate r = estimate_mean(reference.per_seed[b]);
    const MeanEstimate c = estimate_mean(candidate.per_seed[b]);
    std::ostringstream line;
    line << what << ", " << block_name(b) << ": reference " << r.mean << " +- " << r.standard_error
         << ", candidate " << c.mean << " +- " << c.standard_error;
    family.add(line.str(), welch_p_value(r, c, kRelativeRounding * std::abs(r.mean)));
  }
  return estimate_mean(reference.per_seed[kWholeImage]).mean;
}

/// Adds to `family` the comparisons of two estimates made with the same seeds by estimators
/// that follow the same paths and differ only in their weights: each seed's difference is far
/// less noisy than either estimate, and its spread over the seeds gives a valid standard error
/// whether the two are correlated or not. Returns the reference's whole-image mean.
inline double compare_paired(ComparisonFamily& family, const std::string& what,
                             const BlockSamples& reference, const BlockSamples& candidate) {
  for (std::size_t b = 0; b <= kBlocks; ++b) {
    std::vector<double> difference;
    for (std::size_t s = 0; s < reference.per_seed[b].size(); ++s)
      difference.push_back(candidate.per_seed[b][s] - reference.per_seed[b][s]);
    const MeanEstimate d = estimate_mean(difference);
    const MeanEstimate r = estimate_mean(reference.per_seed[b]);
    std::ostringstream line;
    line << what << ", " << block_name(b) << ": reference " << r.mean << " +- " << r.standard_error
         << ", difference " << d.mean << " +- " << d.standard_error;
    family.add(line.str(), zero_mean_p_value(d, kRelativeRounding * std::abs(r.mean)));
  }
  return estimate_mean(reference.per_seed[kWholeImage]).mean;
}

}  // namespace glint_test
