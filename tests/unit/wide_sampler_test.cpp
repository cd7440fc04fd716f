// The samplers' lane-wise forms (S::Wide<W>) against the samplers themselves: at widths 8 and
// 16 every lane must draw bit for bit what a sampler started with that lane's pixel sample
// draws, through starts of some lanes while others are under way, draws for random subsets of
// lanes, and lanes moved in and out. And the 64-bit lanes they hash with (UInt64<W>) against
// std::uint64_t arithmetic, lane by lane, in whatever instruction set the compiler targets.

#include <bit>
#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "../support/float_values.hpp"
#include "glint/math/random.hpp"
#include "glint/math/sobol.hpp"
#include "glint/math/wide.hpp"
#include "glint/policy/concepts.hpp"
#include "glint/policy/sampler.hpp"

using glint::Mask;
using glint::UInt;
using glint::UInt64;

namespace {

using glint_test::same_bits;

std::uint64_t any_u64(glint::Pcg32& rng) {
  // The ends of the range and small values among them, where carries and shifts go wrong.
  switch (rng.next_u32() % 8) {
    case 0:
      return 0;
    case 1:
      return ~std::uint64_t{0};
    case 2:
      return rng.next_u32() % 64;
    case 3:
      return std::uint64_t{1} << (rng.next_u32() % 64);
    default:
      return (std::uint64_t{rng.next_u32()} << 32) | rng.next_u32();
  }
}

std::uint32_t any_u32(glint::Pcg32& rng) {
  return static_cast<std::uint32_t>(any_u64(rng) >> (rng.next_u32() % 2 == 0 ? 0 : 32));
}

/// A mask with lane i true where bit i of `bits` is set.
template <int W>
Mask<W> mask_of(std::uint32_t bits) {
  Mask<W> mask{};
  for (int i = 0; i < W; ++i)
    glint::set_lane(mask, i, ((bits >> i) & 1u) != 0 ? -1 : 0);
  return mask;
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("UInt64<W> computes lane by lane what std::uint64_t computes",
                       "[wide][sampler][unit]", ((int W), W), 8, 16) {
  glint::Pcg32 rng(2026, std::uint64_t(W));
  for (int round = 0; round < 2000; ++round) {
    std::uint64_t a[W], b[W];
    std::uint32_t small[W];
    UInt64<W> va{}, vb{};
    UInt<W> vsmall{};
    const std::uint32_t bits = rng.next_u32() & ((1u << W) - 1u);
    for (int i = 0; i < W; ++i) {
      a[i] = any_u64(rng);
      b[i] = any_u64(rng);
      small[i] = any_u32(rng);
      glint::set_lane(va, i, a[i]);
      glint::set_lane(vb, i, b[i]);
      glint::set_lane(vsmall, i, small[i]);
    }
    const std::uint64_t constant = any_u64(rng);
    const UInt64<W> product = va * vb, by_constant = va * constant, sum = va + vb,
                    sum_constant = va + constant, xored = va ^ vb, ored = va | vb, anded = va & vb,
                    shifted_right_33 = va >> 33, shifted_right_59 = va >> 59,
                    shifted_left_6 = va << 6, shifted_left_32 = va << 32, shifted_right_1 = va >> 1;
    const UInt64<W> widened = glint::widen(vsmall);
    const UInt<W> low = glint::low_bits(va), high = glint::high_bits(va);
    const UInt64<W> chosen = glint::select(mask_of<W>(bits), va, vb);
    const UInt64<W> splat = glint::splat64<UInt64<W>>(constant);
    for (int i = 0; i < W; ++i) {
      INFO("round " << round << ", lane " << i << ": a = " << a[i] << ", b = " << b[i]);
      CHECK(glint::lane(va, i) == a[i]);
      CHECK(product[i] == a[i] * b[i]);
      CHECK(by_constant[i] == a[i] * constant);
      CHECK(sum[i] == a[i] + b[i]);
      CHECK(sum_constant[i] == a[i] + constant);
      CHECK(xored[i] == (a[i] ^ b[i]));
      CHECK(ored[i] == (a[i] | b[i]));
      CHECK(anded[i] == (a[i] & b[i]));
      CHECK(shifted_right_33[i] == a[i] >> 33);
      CHECK(shifted_right_59[i] == a[i] >> 59);
      CHECK(shifted_right_1[i] == a[i] >> 1);
      CHECK(shifted_left_6[i] == a[i] << 6);
      CHECK(shifted_left_32[i] == a[i] << 32);
      CHECK(widened[i] == std::uint64_t{small[i]});
      CHECK(low[i] == static_cast<std::uint32_t>(a[i]));
      CHECK(high[i] == static_cast<std::uint32_t>(a[i] >> 32));
      CHECK(chosen[i] == (((bits >> i) & 1u) != 0 ? a[i] : b[i]));
      CHECK(splat[i] == constant);
    }
  }
}

TEMPLATE_TEST_CASE_SIG("hash_lanes, mix_bits and PCG32 in lanes are their one-value forms",
                       "[wide][sampler][unit]", ((int W), W), 8, 16) {
  glint::Pcg32 rng(2027, std::uint64_t(W));
  for (int round = 0; round < 500; ++round) {
    UInt<W> x{}, y{};
    UInt64<W> seeds{}, streams{};
    std::uint64_t seed[W], stream[W];
    for (int i = 0; i < W; ++i) {
      glint::set_lane(x, i, any_u32(rng));
      glint::set_lane(y, i, any_u32(rng));
      seed[i] = any_u64(rng);
      stream[i] = any_u64(rng);
      glint::set_lane(seeds, i, seed[i]);
      glint::set_lane(streams, i, stream[i]);
    }
    const std::uint64_t shared = any_u64(rng);
    const UInt64<W> hashed = glint::hash_lanes<W>(x, shared, y, 7u);
    const UInt64<W> mixed = glint::mix_bits(seeds);
    // Lanes of a mask reseeded, the others left as they were: every lane then steps as its own
    // generator, the reseeded from (seed, stream), the others from the default generator.
    const std::uint32_t bits = rng.next_u32() & ((1u << W) - 1u);
    glint::Pcg32::Wide<W> lanes;
    glint::Pcg32::Wide<1> fresh;
    fresh.reseed(true, 42, 54);
    for (int i = 0; i < W; ++i)
      lanes.set_lane(i, fresh);
    lanes.reseed(mask_of<W>(bits), seeds, streams);
    std::vector<glint::Pcg32> one(static_cast<std::size_t>(W), glint::Pcg32(42, 54));
    for (int i = 0; i < W; ++i) {
      INFO("round " << round << ", lane " << i);
      CHECK(hashed[i] == glint::hash_values(x[i], shared, y[i], 7u));
      CHECK(mixed[i] == glint::mix_bits(seed[i]));
      if (((bits >> i) & 1u) != 0) one[std::size_t(i)].reseed(seed[i], stream[i]);
    }
    for (int step = 0; step < 8; ++step) {
      const std::uint32_t drawing = rng.next_u32() & ((1u << W) - 1u);
      const UInt<W> drawn = lanes.next_u32(mask_of<W>(drawing));
      for (int i = 0; i < W; ++i) {
        if (((drawing >> i) & 1u) == 0) continue;
        INFO("round " << round << ", step " << step << ", lane " << i);
        CHECK(drawn[i] == one[std::size_t(i)].next_u32());
      }
    }
  }
}

TEMPLATE_TEST_CASE_SIG("bit reversal in lanes is the one-word reversal, digit by digit",
                       "[wide][sampler][unit]", ((int W), W), 8, 16) {
  // The lanes' form shuffles bytes and looks nibbles up in tables (with AVX2 and AVX-512); the
  // definition moves digit k to digit 31 - k.
  const auto by_digits = [](std::uint32_t v) {
    std::uint32_t r = 0;
    for (int k = 0; k < 32; ++k)
      r |= ((v >> k) & 1u) << (31 - k);
    return r;
  };
  glint::Pcg32 rng(2029, std::uint64_t(W));
  for (int round = 0; round < 2000; ++round) {
    UInt<W> words{};
    for (int i = 0; i < W; ++i)
      glint::set_lane(words, i, round < 32 ? (1u << round) + std::uint32_t(i) : any_u32(rng));
    const UInt<W> reversed = glint::detail::reverse_bits(words);
    for (int i = 0; i < W; ++i) {
      INFO("round " << round << ", lane " << i << ", word " << words[i]);
      CHECK(reversed[i] == by_digits(words[i]));
      CHECK(glint::detail::reverse_bits(words[i]) == by_digits(words[i]));
    }
  }
}

namespace {

/// W samplers of type S, one per lane, beside the lane-wise form that must match them.
template <typename S, int W>
struct Lanes {
  std::vector<S> scalar = std::vector<S>(std::size_t(W));
  typename S::template Wide<W> wide;
};

/// A pixel sample anywhere in the ranges a render uses, and at the ends of the words.
glint::PixelSample any_pixel_sample(glint::Pcg32& rng, std::uint32_t count, std::uint64_t seed) {
  return {any_u32(rng), any_u32(rng), any_u32(rng), count, seed};
}

}  // namespace

TEMPLATE_TEST_CASE_SIG(
    "a sampler's Wide form draws bit for bit what the sampler draws, lane by lane",
    "[wide][sampler][unit]", ((typename S, int W), S, W), (glint::IndependentSampler, 8),
    (glint::IndependentSampler, 16), (glint::SobolSampler, 8), (glint::SobolSampler, 16),
    (glint::HybridSobolSampler<>, 8), (glint::HybridSobolSampler<>, 16),
    (glint::HybridSobolSampler<1>, 8), (glint::HybridSobolSampler<1>, 16),
    (glint::HybridSobolSampler<6>, 8), (glint::HybridSobolSampler<6>, 16)) {
  static_assert(glint::WideSamplerStart<S, W>);
  // Each trial mixes what the wavefront does to a block of paths: draws for random subsets of
  // lanes (those left out keep their state), starts of some lanes while the others are part way
  // along their paths, lanes stored to a sampler and loaded from one. After every step, every
  // lane's draws must be those of the sampler it mirrors.
  glint::Pcg32 rng(2028, std::uint64_t(W));
  const std::uint32_t all = (1u << W) - 1u;
  for (int trial = 0; trial < 24; ++trial) {
    Lanes<S, W> lanes;
    // Half the lanes start lane-wise, the others are loaded from samplers under way.
    const std::uint32_t count = 1 + rng.next_u32() % 256;
    const std::uint64_t seed = any_u64(rng);
    glint::PixelSamples<W> first{.samples_per_pixel = count, .seed = seed};
    for (int i = 0; i < W; ++i) {
      const glint::PixelSample s = any_pixel_sample(rng, count, seed);
      glint::set_lane(first.x, i, s.x);
      glint::set_lane(first.y, i, s.y);
      glint::set_lane(first.index, i, s.index);
      lanes.scalar[std::size_t(i)].start(s);
    }
    const std::uint32_t started = rng.next_u32() & all;
    lanes.wide.start(mask_of<W>(started), first);
    for (int i = 0; i < W; ++i) {
      if (((started >> i) & 1u) != 0) continue;
      S& loaded = lanes.scalar[std::size_t(i)];
      loaded.start(any_pixel_sample(rng, 1 + rng.next_u32() % 64, any_u64(rng)));
      for (std::uint32_t draws = rng.next_u32() % 9; draws > 0; --draws)
        loaded.next_1d();
      lanes.wide.set_lane(i, loaded);
    }
    for (int step = 0; step < 300; ++step) {
      INFO("trial " << trial << ", step " << step);
      const std::uint32_t bits = rng.next_u32() & all;
      const Mask<W> mask = mask_of<W>(bits);
      switch (rng.next_u32() % 16) {
        case 0: {  // the lanes of a mask start new samples mid-way
          glint::PixelSamples<W> next{.samples_per_pixel = 1 + rng.next_u32() % 256,
                                      .seed = any_u64(rng)};
          for (int i = 0; i < W; ++i) {
            const glint::PixelSample s = any_pixel_sample(rng, next.samples_per_pixel, next.seed);
            glint::set_lane(next.x, i, s.x);
            glint::set_lane(next.y, i, s.y);
            glint::set_lane(next.index, i, s.index);
            if (((bits >> i) & 1u) != 0) lanes.scalar[std::size_t(i)].start(s);
          }
          lanes.wide.start(mask, next);
          break;
        }
        case 1: {  // a lane stored to a sampler continues there as the sampler it mirrors
          const int i = int(rng.next_u32() % std::uint32_t(W));
          S stored, expected = lanes.scalar[std::size_t(i)];
          lanes.wide.get_lane(i, stored);
          for (int draw = 0; draw < 6; ++draw) {
            INFO("stored lane " << i << ", draw " << draw);
            if (draw % 2 == 0) {
              CHECK(same_bits(stored.next_1d(), expected.next_1d()));
            } else {
              const glint::Vec2 u = stored.next_2d(), v = expected.next_2d();
              CHECK(same_bits(u.x, v.x));
              CHECK(same_bits(u.y, v.y));
            }
          }
          break;
        }
        case 2: {  // a lane loaded from a sampler of another pixel, part way along its path
          const int i = int(rng.next_u32() % std::uint32_t(W));
          S& loaded = lanes.scalar[std::size_t(i)];
          loaded.start(any_pixel_sample(rng, 1 + rng.next_u32() % 64, any_u64(rng)));
          for (std::uint32_t draws = rng.next_u32() % 9; draws > 0; --draws)
            loaded.next_2d();
          lanes.wide.set_lane(i, loaded);
          break;
        }
        default: {
          const bool two = rng.next_u32() % 2 == 0;
          const glint::Float<W> zero{};
          const auto drawn = two ? lanes.wide.next_2d(mask)
                                 : glint::Vector2<glint::Float<W>>{lanes.wide.next_1d(mask), zero};
          for (int i = 0; i < W; ++i) {
            if (((bits >> i) & 1u) == 0) continue;
            INFO("lane " << i << (two ? ", 2D" : ", 1D"));
            S& scalar = lanes.scalar[std::size_t(i)];
            if (two) {
              const glint::Vec2 u = scalar.next_2d();
              CHECK(same_bits(drawn.x[i], u.x));
              CHECK(same_bits(drawn.y[i], u.y));
            } else {
              CHECK(same_bits(drawn.x[i], scalar.next_1d()));
            }
          }
        }
      }
    }
  }
}
