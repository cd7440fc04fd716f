#pragma once
// Owen-scrambled Sobol' points, padded across dimensions.

#include <cstdint>

#include "glint/math/random.hpp"
#include "glint/math/sobol.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/sampler/sample_keys.hpp"

namespace glint {

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

#if defined(GLINT_AVX2)
  /// Eight samplers, one per lane, drawing the same values as eight SobolSamplers would: the
  /// hashes are integer arithmetic, exact in SIMD lanes. A lane outside a draw's mask keeps its
  /// state.
  class Lanes {
   public:
    void set_lane(int i, const SobolSampler& s) {
      pixel_key_.set_lane(i, s.pixel_key_);
      reversed_index_[i] = s.reversed_index_;
      dimension_[i] = s.dimension_;
    }
    void get_lane(int i, SobolSampler& s) const {
      s.pixel_key_ = pixel_key_.lane(i);
      s.reversed_index_ = reversed_index_[i];
      s.dimension_ = dimension_[i];
    }
    /// SobolSampler::start for the lanes of `mask`; the others keep their state.
    void start(IntLanes mask, const PixelSampleLanes& s) {
      reversed_index_ = select(mask, detail::reverse_bits(s.index), reversed_index_);
      pixel_key_ = select(mask, detail::pixel_key(s), pixel_key_);
      dimension_ = select(mask, UintLanes{}, dimension_);
    }
    FloatLanes next_1d(IntLanes mask) {
      const UintLanes dimension = advance(mask);
      return to_floats(owen_scramble_reversed(shuffled_index(dimension),
                                              detail::dimension_key(pixel_key_, dimension, 1)));
    }
    Vec2Lanes next_2d(IntLanes mask) {
      const UintLanes dimension = advance(mask);
      const UintLanes index = shuffled_index(dimension);
      const UintLanes x =
          owen_scramble_reversed(index, detail::dimension_key(pixel_key_, dimension, 1));
      const UintLanes y = owen_scramble_reversed(sobol_second_dimension_reversed(index),
                                                 detail::dimension_key(pixel_key_, dimension, 2));
      return {to_floats(x), to_floats(y)};
    }

   private:
    UintLanes advance(IntLanes mask) {
      const UintLanes dimension = dimension_;
      dimension_ = select(mask, dimension + 1u, dimension);
      return dimension;
    }
    UintLanes shuffled_index(UintLanes dimension) const {
      return detail::reverse_bits(
          owen_scramble_reversed(reversed_index_, detail::dimension_key(pixel_key_, dimension, 0)));
    }
    static FloatLanes to_floats(UintLanes reversed_fraction) {
      return unit_floats(detail::reverse_bits(reversed_fraction));
    }

    Uint64Lanes pixel_key_{};
    UintLanes reversed_index_{};
    UintLanes dimension_{};
  };
#endif

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

}  // namespace glint
