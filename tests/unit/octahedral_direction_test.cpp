// OctahedralDirection (math/octahedral_direction.hpp): every direction comes back within the
// angle that 16 bits per coordinate of the octahedral map allow, of unit length, and the axes
// nearly exactly.

#include "glint/math/octahedral_direction.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "glint/math/random.hpp"
#include "random_vectors.hpp"

namespace {

/// The angle between unit vectors a and b, in double, accurate for small angles.
double angle_between(const glint::Vec3& a, const glint::Vec3& b) {
  const glm::dvec3 da(a), db(b);
  return 2.0 * std::atan2(glm::length(da - db), glm::length(da + db));
}

}  // namespace

TEST_CASE("octahedral direction: within 8e-5 radians, of unit length", "[octahedral]") {
  glint::Pcg32 rng(99u, 4u);
  double worst = 0.0;
  for (int i = 0; i < 1000000; ++i) {
    const glint::Vec3 d = glint::test::random_unit_vector(rng);
    const glint::OctahedralDirection code(d);
    const glint::Vec3 back = code.direction();
    worst = std::max(worst, angle_between(d, back));
    REQUIRE(std::fabs(glm::length(glm::dvec3(back)) - 1.0) < 1e-6);
  }
  // 16 bits over [-1, 1]: steps of 2 / 65535, half a step per coordinate, stretched by at most
  // about 3 where the map is least even (6.4e-5 is the worst of these directions).
  CHECK(worst < 8e-5);
  CHECK(worst > 1e-5);  // the test can see the quantization at all
  for (const glint::Vec3 axis :
       {glint::Vec3(1, 0, 0), glint::Vec3(-1, 0, 0), glint::Vec3(0, 1, 0), glint::Vec3(0, -1, 0),
        glint::Vec3(0, 0, 1), glint::Vec3(0, 0, -1)})
    CHECK(angle_between(glint::OctahedralDirection(axis).direction(), axis) < 3e-5);
}
