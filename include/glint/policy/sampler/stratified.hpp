#pragma once
// Jittered stratified sampling over the samples of a pixel.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/permutation.hpp"
#include "glint/math/random.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/sampler/sample_keys.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

namespace detail {

/// A value uniform over stratum `stratum` of `count` equal strata of [0,1), from 24 random
/// bits. Values lie on the float grid k * 2^-24 (every value exactly representable, 1 never
/// reached), and the stratum is enforced in integer arithmetic so that rounding can never push
/// a sample into its neighbour's stratum. `inverse_count` is 1.0 / count, hoisted by callers.
inline float value_in_stratum(std::uint32_t stratum, std::uint32_t count, double inverse_count,
                              std::uint32_t random_bits) {
  constexpr std::uint64_t kOne = std::uint64_t{1} << 24;
  const std::uint64_t position = (std::uint64_t{stratum} << 24) | (random_bits >> 8);
  auto grid = static_cast<std::uint64_t>(static_cast<double>(position) * inverse_count);
  // grid = floor(position / count) can sit below the stratum's first grid point when the
  // stratum boundary is not on the grid; double rounding can also be one off either way.
  if (grid * count < std::uint64_t{stratum} * kOne)
    ++grid;
  else if (grid * count >= (std::uint64_t{stratum} + 1) * kOne)
    --grid;
  return static_cast<float>(std::min(grid, kOne - 1)) * 0x1p-24f;
}

}  // namespace detail

/// Jittered stratified sampling. Each request is stratified over the samples of a pixel: a 1D
/// request puts sample i of n in stratum pi(i) of n equal intervals, a 2D request puts it in
/// cell pi(i) of an nx x ny grid (nx = floor(sqrt n), ny = ceil(n / nx)), and the value is
/// uniform within the stratum, from an independent PCG stream. pi is a permutation keyed by
/// (pixel, seed, dimension), so the strata of different dimensions are unrelated (without it
/// sample i would sit in stratum i of every dimension: perfectly correlated dimensions).
/// When n is not nx * ny, a pixel's samples occupy a random subset of the cells; each sample
/// is still uniform over the whole square, so the estimate stays unbiased.
///
/// The stratification holds only when a pixel renders exactly samples_per_pixel samples;
/// an index beyond that reuses the strata of index mod n with fresh jitter. Values are
/// resolved to 2^-24, so sample counts above 2^24 are stratified as if they were 2^24.
class StratifiedSampler {
 public:
  void start(const PixelSample& s) {
    count_ = std::clamp<std::uint32_t>(s.samples_per_pixel, 1, kMaxStrata);
    slot_ = s.index % count_;
    if (count_ != cached_count_) plan_grid();
    pixel_key_ = detail::pixel_key(s);
    // A multiplier other than dimension_key's, so a jitter seed never equals a stratum key.
    rng_.reseed(mix_bits(pixel_key_ ^ (s.index * 0xd1b54a32d192ed03ULL + 1)), 0);
    dimension_ = 0;
  }

  float next_1d() {
    const std::uint32_t stratum =
        detail::permute_index(slot_, count_, detail::dimension_key(pixel_key_, dimension_++));
    return detail::value_in_stratum(stratum, count_, inverse_count_, rng_.next_u32());
  }

  Vec2 next_2d() {
    const std::uint32_t cell = detail::permute_index(
        slot_, columns_ * rows_, detail::dimension_key(pixel_key_, dimension_++));
    // cell / columns_ without a division: (cell + 1/2) / columns is at least 1/(2 columns)
    // away from an integer, far more than the double's rounding error.
    const auto row = static_cast<std::uint32_t>((cell + 0.5) * inverse_columns_);
    const std::uint32_t column = cell - row * columns_;
    const float u = detail::value_in_stratum(column, columns_, inverse_columns_, rng_.next_u32());
    return {u, detail::value_in_stratum(row, rows_, inverse_rows_, rng_.next_u32())};
  }

 private:
  // Also keeps the grid's arithmetic (columns * rows < count + columns) far from overflow.
  static constexpr std::uint32_t kMaxStrata = 1u << 24;

  // The grid depends only on the sample count, which is the same for every sample a renderer
  // thread draws, so it is computed once per sampler rather than once per sample.
  void plan_grid() {
    cached_count_ = count_;
    columns_ = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(count_)));
    while (columns_ * columns_ > count_)
      --columns_;
    while ((columns_ + 1) * (columns_ + 1) <= count_)
      ++columns_;
    rows_ = (count_ + columns_ - 1) / columns_;
    inverse_count_ = 1.0 / count_;
    inverse_columns_ = 1.0 / columns_;
    inverse_rows_ = 1.0 / rows_;
  }

  Pcg32 rng_;
  std::uint64_t pixel_key_ = 0;
  std::uint32_t count_ = 1;
  std::uint32_t slot_ = 0;
  std::uint32_t dimension_ = 0;
  std::uint32_t cached_count_ = 1;
  std::uint32_t columns_ = 1;
  std::uint32_t rows_ = 1;
  double inverse_count_ = 1.0;
  double inverse_columns_ = 1.0;
  double inverse_rows_ = 1.0;
};
static_assert(Sampler<StratifiedSampler>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
