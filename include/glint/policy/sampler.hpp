#pragma once
// Sampler policies: where the renderer's random numbers come from.
//
// Every sampler is a pure function of (pixel, sample index, seed, dimension): `start` forgets
// everything about the previous sample, so the image does not depend on which thread renders
// which pixel or in what order. A "dimension" is one request, 1D or 2D, counted from start();
// the stratified and low-discrepancy samplers spread the samples of one pixel evenly over each
// dimension, which helps wherever request d serves the same purpose in every sample (the
// antialiasing pair first, then the bounces in order).

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "glint/math/random.hpp"
#include "glint/policy/concepts.hpp"

namespace glint {

/// Independent uniform values from a PCG32 stream seeded by hashing (pixel, sample, seed):
/// the report's sampler, and the baseline for the others.
class IndependentSampler {
 public:
  void start(const PixelSample& s) {
    rng_.reseed(hash_values(s.x, s.y, s.index, s.seed), hash_values(s.seed));
  }
  float next_1d() { return rng_.next_float(); }
  Vec2 next_2d() {
    const float u = rng_.next_float();
    return {u, rng_.next_float()};
  }

 private:
  Pcg32 rng_;
};
static_assert(Sampler<IndependentSampler>);

namespace detail {

inline constexpr std::uint64_t kGoldenGamma = 0x9e3779b97f4a7c15ULL;

/// One key per (pixel, seed). The two inner hashes are independent, so their latencies
/// overlap: cheaper than hashing the three values in sequence, which start() would pay for
/// every sample.
constexpr std::uint64_t pixel_key(const PixelSample& s) {
  const std::uint64_t pixel = (std::uint64_t{s.y} << 32) | s.x;
  return mix_bits(mix_bits(pixel) ^ mix_bits(s.seed + kGoldenGamma));
}

/// A key for one dimension of one pixel. mix_bits is a bijection, so distinct dimensions of a
/// pixel never share a key, and its avalanche decorrelates neighbouring ones.
constexpr std::uint64_t dimension_key(std::uint64_t pixel_key, std::uint32_t dimension,
                                      std::uint32_t salt = 0) {
  return mix_bits(pixel_key + (std::uint64_t{dimension} * 4 + salt + 1) * kGoldenGamma);
}

/// A 32-bit hash with low bias (the "lowbias32" constants found by Wellons' hash prospector),
/// used as the round function of permute_index.
constexpr std::uint32_t hash_u32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/// Element i of a permutation of {0, ..., n-1} chosen by `key`, computed without storing the
/// permutation. A keyed bijection on the next power of two is cycle-walked back into range
/// (each walk step is accepted with probability > 1/2), then rotated by an offset drawn from
/// an independent hash: the bijection decorrelates the images of different elements, and the
/// rotation makes the image of each single element exactly uniform over keys, which is what
/// keeps a sampler that uses only some of the strata unbiased.
///
/// The bijection is a Feistel network on the two halves of the bits (Luby and Rackoff): each
/// round xors one half with a hash of the other, invertible whatever the hash. Cheaper
/// arithmetic bijections (odd multipliers and xorshifts modulo 2^bits) are nearly affine on
/// the tiny domains a pixel's sample count gives, and so reach only a few of the permutations.
/// Four rounds already make two dimensions' permutations as unrelated as random ones (same
/// integration error for functions of both, within 1%); two rounds do not. Eight would also
/// make the pair (pi(i), pi(j)) of one permutation uniform, which no estimate depends on.
inline constexpr std::uint32_t kFeistelRoundPairs = 2;

constexpr std::uint32_t permute_index(std::uint32_t i, std::uint32_t n, std::uint64_t key) {
  if (n <= 1) return 0;
  const int bits = std::bit_width(n - 1);
  const int low_bits = bits / 2;
  const std::uint32_t low_mask = (1u << low_bits) - 1u;
  const std::uint32_t high_mask = (1u << (bits - low_bits)) - 1u;
  const auto a = static_cast<std::uint32_t>(key);
  const auto b = static_cast<std::uint32_t>(key >> 32);
  std::uint32_t low = i & low_mask;
  std::uint32_t high = (i >> low_bits) & high_mask;
  do {
    for (std::uint32_t round = 0; round < kFeistelRoundPairs; ++round) {
      high ^= hash_u32(low ^ (a + round * 0x9e3779b9u)) & high_mask;
      low ^= hash_u32(high ^ (b + round * 0x9e3779b9u)) & low_mask;
    }
  } while (((high << low_bits) | low) >= n);
  const std::uint32_t permuted = (high << low_bits) | low;
  const std::uint64_t offset_bits = mix_bits(key ^ kGoldenGamma);
  const auto offset = static_cast<std::uint32_t>(((offset_bits >> 32) * n) >> 32);
  const std::uint32_t rotated = permuted + offset;
  return rotated >= n ? rotated - n : rotated;
}

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

/// Bit reversal: turns a binary fraction's digits (most significant first) into an integer's
/// (least significant first) and back.
constexpr std::uint32_t reverse_bits(std::uint32_t v) {
  v = (v << 16) | (v >> 16);
  v = ((v & 0x00ff00ffu) << 8) | ((v >> 8) & 0x00ff00ffu);
  v = ((v & 0x0f0f0f0fu) << 4) | ((v >> 4) & 0x0f0f0f0fu);
  v = ((v & 0x33333333u) << 2) | ((v >> 2) & 0x33333333u);
  v = ((v & 0x55555555u) << 1) | ((v >> 1) & 0x55555555u);
  return v;
}

}  // namespace detail

/// Column j of the generator matrix of the second dimension of Sobol's sequence, as a binary
/// fraction (bit 31 is the first digit). That dimension's primitive polynomial is x + 1 with
/// initial direction number m_1 = 1, so Sobol's recurrence reduces to v_j = v_{j-1} ^
/// (v_{j-1} >> 1): row t of column j is C(j, t) mod 2, Pascal's triangle. The sampler uses the
/// faster sobol_second_dimension below; this is the definition it is tested against.
constexpr std::uint32_t sobol_generator_column(int j) {
  std::uint32_t v = 0x80000000u;
  for (int k = 0; k < j; ++k)
    v ^= v >> 1;
  return v;
}

/// The first dimension of Sobol's sequence (van der Corput in base 2), as a binary fraction.
constexpr std::uint32_t sobol_first_dimension(std::uint32_t index) {
  return detail::reverse_bits(index);
}

/// The second dimension of Sobol's sequence, as a binary fraction, with the digits still in
/// reversed (integer) order. By Lucas's theorem C(j, t) is odd exactly when the bits of t are
/// a subset of those of j, so reversed digit t is the xor of the index bits j that contain t:
/// a subset-sum transform over the five bits of a bit position, one masked shift-xor per bit
/// instead of a 32-step matrix product.
constexpr std::uint32_t sobol_second_dimension_reversed(std::uint32_t index) {
  std::uint32_t v = index;
  v ^= (v >> 1) & 0x55555555u;
  v ^= (v >> 2) & 0x33333333u;
  v ^= (v >> 4) & 0x0f0f0f0fu;
  v ^= (v >> 8) & 0x00ff00ffu;
  v ^= (v >> 16) & 0x0000ffffu;
  return v;
}

constexpr std::uint32_t sobol_second_dimension(std::uint32_t index) {
  return detail::reverse_bits(sobol_second_dimension_reversed(index));
}

/// A hash-based Owen scramble of a binary fraction given with its digits reversed (Laine and
/// Karras 2012; Burley 2020). Owen scrambling flips each digit by a random function of the
/// digits before it; in reversed order "before" means "less significant", and every step
/// below (adding a constant, multiplying by an odd number, xor with the value times an even
/// number) changes bit k only by a function of bits below k. Any composition of such steps is
/// therefore an Owen scramble, which preserves every (t, m, s)-net property; the steps only
/// decide how random the flips look. Returns the digits still reversed.
constexpr std::uint32_t owen_scramble_reversed(std::uint32_t v, std::uint64_t key) {
  const auto a = static_cast<std::uint32_t>(key);
  const auto b = static_cast<std::uint32_t>(key >> 32);
  v += a;
  v ^= v * 0x9e3779b8u;
  v *= b | 1u;
  v ^= v * 0x7feb352cu;
  v += b;
  v ^= v * 0x846ca68au;
  v ^= v * ((a >> 7) << 1);
  return v;
}

/// An Owen scramble of a binary fraction in ordinary order (bit 31 the first digit).
constexpr std::uint32_t owen_scramble(std::uint32_t fraction, std::uint64_t key) {
  return detail::reverse_bits(owen_scramble_reversed(detail::reverse_bits(fraction), key));
}

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

/// Owen-scrambled Sobol' points, padded across dimensions as in Burley 2020 ("Practical
/// Hash-based Owen Scrambling", JCGT 9(4)). Every request draws from the first two dimensions
/// of Sobol's sequence, a (0,2)-sequence: any 2^m consecutive aligned points form a (0,m,2)-
/// net, one point in every 2^-a x 2^-(m-a) box. Each request (a 1D request takes the first
/// coordinate of a pair) gets its own keys from (pixel, seed, dimension):
///  - the sample index is Owen-scrambled as a binary number, which maps the first 2^m indices
///    onto another aligned block of 2^m, in a shuffled order: the net property survives, but
///    different dimensions see the points in unrelated orders, so pairing dimension d of
///    sample i with dimension d' of the same sample is as good as independent;
///  - each coordinate is then Owen-scrambled, which keeps the net and makes every point
///    uniformly distributed, so estimates are unbiased.
/// With a power-of-two sample count a pixel's samples are a (0,m,2)-net in every request;
/// other counts use a prefix of the sequence, still well spread but without the guarantee.
/// No tables: the second dimension's generator matrix is computed (sobol_second_dimension).
class SobolSampler {
 public:
  void start(const PixelSample& s) {
    reversed_index_ = detail::reverse_bits(s.index);
    pixel_key_ = detail::pixel_key(s);
    dimension_ = 0;
  }

  float next_1d() {
    const std::uint32_t dimension = dimension_++;
    const std::uint32_t index = shuffled_index(dimension);
    return to_float(owen_scramble_reversed(index, detail::dimension_key(pixel_key_, dimension, 1)));
  }

  Vec2 next_2d() {
    const std::uint32_t dimension = dimension_++;
    const std::uint32_t index = shuffled_index(dimension);
    // Both coordinates stay in reversed digit order until the scramble is done: the first
    // dimension's reversed digits are the index itself, which saves two reversals.
    const std::uint32_t x =
        owen_scramble_reversed(index, detail::dimension_key(pixel_key_, dimension, 1));
    const std::uint32_t y = owen_scramble_reversed(sobol_second_dimension_reversed(index),
                                                   detail::dimension_key(pixel_key_, dimension, 2));
    return {to_float(x), to_float(y)};
  }

 private:
  std::uint32_t shuffled_index(std::uint32_t dimension) const {
    // owen_scramble(index), with the index's reversal done once in start().
    return detail::reverse_bits(
        owen_scramble_reversed(reversed_index_, detail::dimension_key(pixel_key_, dimension, 0)));
  }
  static float to_float(std::uint32_t reversed_fraction) {
    return bits_to_unit_float(detail::reverse_bits(reversed_fraction));
  }

  std::uint64_t pixel_key_ = 0;
  std::uint32_t reversed_index_ = 0;
  std::uint32_t dimension_ = 0;
};
static_assert(Sampler<SobolSampler>);

/// Sobol' values for the first kSobolRequests requests of a sample (the camera jitter and the
/// first bounces, where low discrepancy visibly lowers the error), independent PCG32 values
/// after that (deep bounces, where it hardly helps but a scrambled Sobol' draw costs about
/// four times an independent one). The image converges to the same result as with either.
template <std::uint32_t kSobolRequests = 4>
class HybridSobolSampler {
 public:
  void start(const PixelSample& s) {
    sobol_.start(s);
    rng_.reseed(hash_values(s.x, s.y, s.index, s.seed, 0x50b01u), hash_values(s.seed));
    requests_ = 0;
  }
  float next_1d() { return requests_++ < kSobolRequests ? sobol_.next_1d() : rng_.next_float(); }
  Vec2 next_2d() {
    if (requests_++ < kSobolRequests) return sobol_.next_2d();
    const float u = rng_.next_float();
    return {u, rng_.next_float()};
  }

 private:
  SobolSampler sobol_;
  Pcg32 rng_;
  std::uint32_t requests_ = 0;
};
static_assert(Sampler<HybridSobolSampler<>>);

}  // namespace glint
