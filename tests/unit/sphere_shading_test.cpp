// The built-in sphere shadings against the definitions they implement, worked out in double
// precision from the angles: the octant colours from the signs of the direction, the checker
// from sectors of 45 degrees of longitude (atan2(z, x)) and latitude (acos(y)), away from the
// sectors' edges, where float rounding may decide either way.

#include <catch2/catch.hpp>
#include <cmath>

#include "glint/math/random.hpp"
#include "glint/math/sampling.hpp"
#include "glint/policy/sphere_shading.hpp"

using glint::BuiltinShading;
using glint::Color;
using glint::Vec3;

TEST_CASE("the checker alternates over sectors of 45 degrees of longitude and latitude",
          "[shading][unit]") {
  const Color base(0.2f, 0.5f, 0.9f);
  glint::Pcg32 rng(12, 34);
  int checked = 0, complement = 0;
  for (int k = 0; k < 200000; ++k) {
    const Vec3 d = glint::sample_uniform_sphere(glint::Vec2(rng.next_float(), rng.next_float()));
    const double longitude = std::atan2(double(d.z), double(d.x)) + M_PI;  // [0, 2 pi]
    const double latitude = std::acos(std::fmax(-1.0, std::fmin(1.0, double(d.y))));
    const double u = longitude / (M_PI / 4), v = latitude / (M_PI / 4);
    // Away from the edges by more than rounding can move a direction.
    if (std::abs(u - std::round(u)) < 1e-4 || std::abs(v - std::round(v)) < 1e-4) continue;
    const bool odd = ((int(u) + int(v)) & 1) != 0;
    const Color expected = odd ? Color(1.0f) - base : base;
    const Color got = BuiltinShading::color(glint::ShadingKind::checker, base, {d});
    INFO("direction " << d.x << ", " << d.y << ", " << d.z << ": sectors " << int(u) << ", "
                      << int(v));
    REQUIRE(got == expected);
    ++checked;
    complement += odd;
  }
  CHECK(checked > 190000);
  // Each parity covers half the sphere.
  CHECK(std::abs(complement - checked / 2) < checked / 50);
}

TEST_CASE("octant shading colours each octant by the signs of the direction", "[shading][unit]") {
  const Color base(1.0f, 0.5f, 0.25f);
  Color seen[8];
  for (int octant = 0; octant < 8; ++octant) {
    const Vec3 d((octant & 1) ? 0.5f : -0.5f, (octant & 2) ? 0.5f : -0.5f,
                 (octant & 4) ? 0.5f : -0.5f);
    seen[octant] = BuiltinShading::color(glint::ShadingKind::octants, base, {d});
    for (int other = 0; other < octant; ++other)
      CHECK(seen[octant] != seen[other]);
  }
  CHECK(BuiltinShading::color(glint::ShadingKind::uniform, base, {Vec3(0.0f, 1.0f, 0.0f)}) == base);
}
