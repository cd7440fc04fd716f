// Splat sums (image/splat_sums.hpp): the same bits whatever the order of the additions, sums
// exact to far below a float's rounding, and values they cannot hold refused.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <thread>
#include <vector>

#include "glint/image/pixel_sums.hpp"
#include "glint/image/splat_sums.hpp"
#include "glint/math/random.hpp"

using glint::Color;

namespace {

struct Splat {
  int x, y;
  Color value;
};

/// Values over twelve orders of magnitude, of both signs, on a 5 x 3 image.
std::vector<Splat> random_splats(std::size_t count) {
  glint::Pcg32 rng(17, 5);
  std::vector<Splat> splats;
  for (std::size_t i = 0; i < count; ++i) {
    Color value;
    for (int c = 0; c < 3; ++c)
      value[c] = std::ldexp(rng.next_float() - 0.25f, int(rng.next_u32() % 40) - 24);
    splats.push_back({int(rng.next_u32() % 5), int(rng.next_u32() % 3), value});
  }
  return splats;
}

}  // namespace

TEST_CASE("splat sums: the same bits in any order and from any number of threads", "[splat]") {
  const std::vector<Splat> splats = random_splats(20000);
  glint::SplatSums forward(5, 3), backward(5, 3), threaded(5, 3);
  for (const Splat& s : splats)
    forward.add(s.x, s.y, s.value);
  for (auto s = splats.rbegin(); s != splats.rend(); ++s)
    backward.add(s->x, s->y, s->value);
  {
    std::vector<std::jthread> threads;
    for (int t = 0; t < 3; ++t)
      threads.emplace_back([&, t] {
        for (std::size_t i = std::size_t(t); i < splats.size(); i += 3)
          threaded.add(splats[i].x, splats[i].y, splats[i].value);
      });
  }
  CHECK(forward.words() == backward.words());
  CHECK(forward.words() == threaded.words());
  // Two halves summed apart and then together: the same as all at once.
  glint::SplatSums first(5, 3), second(5, 3);
  for (std::size_t i = 0; i < splats.size(); ++i)
    (i < splats.size() / 2 ? first : second).add(splats[i].x, splats[i].y, splats[i].value);
  first.add(second);
  CHECK(first.words() == forward.words());
}

TEST_CASE("splat sums: a pixel's sum is exact to 2^-56 per splat", "[splat]") {
  const std::vector<Splat> splats = random_splats(20000);
  glint::SplatSums sums(5, 3);
  std::vector<long double> exact(15 * 3, 0.0L);
  for (const Splat& s : splats) {
    sums.add(s.x, s.y, s.value);
    for (int c = 0; c < 3; ++c)
      exact[std::size_t((s.y * 5 + s.x) * 3 + c)] += (long double)(s.value[c]);
  }
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c) {
        const long double e = exact[std::size_t((y * 5 + x) * 3 + c)];
        // At most 20000 splats of 2^-57 each from the fine rounding, plus the double's rounding
        // of the sum.
        CHECK(std::abs((long double)(sums.at(x, y)[c]) - e) <=
              20000.0L * 0x1p-57L + 0x1p-52L * std::abs(e));
      }
  // Tiny values, which the coarse part alone (2^-16) would lose, are kept to 2^-57 each.
  glint::SplatSums tiny(1, 1);
  const Color value(1e-12f, 3e-15f, -2e-13f);
  for (int i = 0; i < 1000; ++i)
    tiny.add(0, 0, value);
  for (int c = 0; c < 3; ++c)
    CHECK(tiny.at(0, 0)[c] == Approx(1000.0 * double(value[c])).margin(1000.0 * 0x1p-57));
}

TEST_CASE("splat sums: values beyond their range or not finite are refused", "[splat]") {
  CHECK(glint::SplatSums::representable(Color(1.0f, -4e9f, 0.0f)));
  CHECK_FALSE(glint::SplatSums::representable(Color(0.0f, 4.3e9f, 0.0f)));
  CHECK_FALSE(glint::SplatSums::representable(Color(-5e9f, 0.0f, 0.0f)));
  CHECK_FALSE(
      glint::SplatSums::representable(Color(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f)));
  CHECK_FALSE(
      glint::SplatSums::representable(Color(0.0f, 0.0f, std::numeric_limits<float>::infinity())));
  // The largest values a pixel may take, 2^15 of the largest splats: no overflow.
  glint::SplatSums sums(1, 1);
  const float largest = std::nextafter(float(glint::SplatSums::kLargestSplat), 0.0f);
  for (int i = 0; i < 1 << 15; ++i)
    sums.add(0, 0, Color(largest, -largest, 0.0f));
  CHECK(sums.at(0, 0).x == Approx(double(largest) * 32768.0).epsilon(1e-12));
  CHECK(sums.at(0, 0).y == Approx(-double(largest) * 32768.0).epsilon(1e-12));
}

TEST_CASE("pixel sums: a pixel's total is its samples' sum plus its splats'", "[splat]") {
  glint::PixelSums sums(2, 2, true);
  REQUIRE(sums.has_splats());
  sums.at(1, 0) = glint::ColorSum(1.0, 2.0, 3.0);
  sums.splats().add(1, 0, Color(0.5f, 0.25f, -1.0f));
  CHECK(sums.total(1, 0) == glint::ColorSum(1.5, 2.25, 2.0));
  const glint::MeanImage image = glint::mean_image(sums, 2);
  CHECK(image.film.at(1, 0) == Color(0.75f, 1.125f, 1.0f));
  CHECK_FALSE(glint::PixelSums(2, 2).has_splats());
}
