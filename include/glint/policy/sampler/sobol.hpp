#pragma once
// Owen-scrambled Sobol' points, padded across dimensions.

#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/random.hpp"
#include "glint/math/sobol.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/sampler/sample_keys.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

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
  /// W samplers, one per lane, each drawing what a SobolSampler draws (the hashes are integer
  /// arithmetic, exact in every lane); a lane outside a call's mask keeps its state. The sampler
  /// itself is the width-1 form with every lane on.
  template <int W>
  class Wide {
   public:
    void set_lane(int i, const SobolSampler& s) { set_lane(i, s.state_); }
    void get_lane(int i, SobolSampler& s) const { get_lane(i, s.state_); }
    void set_lane(int i, const Wide<1>& one) {
      glint::set_lane(pixel_key_, i, one.pixel_key_);
      glint::set_lane(reversed_index_, i, one.reversed_index_);
      glint::set_lane(dimension_, i, one.dimension_);
    }
    void get_lane(int i, Wide<1>& one) const {
      one.pixel_key_ = lane(pixel_key_, i);
      one.reversed_index_ = lane(reversed_index_, i);
      one.dimension_ = lane(dimension_, i);
    }
    /// SobolSampler::start for the lanes of `mask`.
    void start(Mask<W> mask, const PixelSamples<W>& s) {
      reversed_index_ = select(mask, detail::reverse_bits(s.index), reversed_index_);
      pixel_key_ = select(mask, detail::pixel_key(s), pixel_key_);
      dimension_ = select(mask, UInt<W>{}, dimension_);
    }
    Float<W> next_1d(Mask<W> mask) {
      const UInt<W> dimension = advance(mask);
      return to_unit_float(owen_scramble_reversed(shuffled_index(dimension),
                                                  detail::dimension_key(pixel_key_, dimension, 1)));
    }
    Vec2For<Float<W>> next_2d(Mask<W> mask) {
      const UInt<W> dimension = advance(mask);
      const UInt<W> index = shuffled_index(dimension);
      // Both coordinates stay in reversed digit order until the scramble is done: the first
      // dimension's reversed digits are the index itself, which saves two reversals.
      const UInt<W> x =
          owen_scramble_reversed(index, detail::dimension_key(pixel_key_, dimension, 1));
      const UInt<W> y = owen_scramble_reversed(sobol_second_dimension_reversed(index),
                                               detail::dimension_key(pixel_key_, dimension, 2));
      return {to_unit_float(x), to_unit_float(y)};
    }

   private:
    template <int>
    friend class Wide;

    UInt<W> advance(Mask<W> mask) {
      const UInt<W> dimension = dimension_;
      dimension_ = select(mask, UInt<W>(dimension + 1u), dimension);
      return dimension;
    }
    UInt<W> shuffled_index(UInt<W> dimension) const {
      // owen_scramble(index), with the index's reversal done once in start().
      return detail::reverse_bits(
          owen_scramble_reversed(reversed_index_, detail::dimension_key(pixel_key_, dimension, 0)));
    }
    static Float<W> to_unit_float(UInt<W> reversed_fraction) {
      return bits_to_unit_float(detail::reverse_bits(reversed_fraction));
    }

    UInt64<W> pixel_key_{};
    UInt<W> reversed_index_{};
    UInt<W> dimension_{};
  };

  void start(const PixelSample& s) { state_.start(true, s); }
  float next_1d() { return state_.next_1d(true); }
  Vec2 next_2d() { return state_.next_2d(true); }

 private:
  Wide<1> state_;
};
static_assert(Sampler<SobolSampler>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
