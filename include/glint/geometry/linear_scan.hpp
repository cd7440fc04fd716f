#pragma once
// The queries of a set of spheres scanned linearly (SphereSet, WallSet), written once over the
// set's own storage: the scalar reference, the 8-wide AVX2 scan, and the choice between them.
// A set derives from LinearScan<itself> and provides size(), the accessors test_spheres reads
// for its kind of sphere, and, with AVX2, columns() for the 8-wide kernel.

#include <cstddef>

#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

template <class Set>
class LinearScan {
 public:
  /// See SphereAccelerator.
  bool closest_hit(const Ray& ray, SphereHit& hit) const {
#ifdef GLINT_AVX2
    return closest_hit_avx2(ray, hit);
#else
    return closest_hit_scalar(ray, hit);
#endif
  }

  /// See SphereAccelerator.
  bool any_hit(const Ray& ray) const {
#ifdef GLINT_AVX2
    return any_hit_avx2(ray);
#else
    return any_hit_scalar(ray);
#endif
  }

  /// The queries with the scalar kernel, the reference for the SIMD one.
  bool closest_hit_scalar(const Ray& ray, SphereHit& hit) const {
    SphereHit best = hit_to_beat(ray, hit);
    if (!test_spheres(RayLane(ray), set(), 0, set().size(), best, /*stop_at_first=*/false))
      return false;
    hit = best;
    return true;
  }
  bool any_hit_scalar(const Ray& ray) const {
    SphereHit best = hit_to_beat(ray, SphereHit{});
    return test_spheres(RayLane(ray), set(), 0, set().size(), best, /*stop_at_first=*/true);
  }

#ifdef GLINT_AVX2
  /// The queries with the 8-wide kernel.
  bool closest_hit_avx2(const Ray& ray, SphereHit& hit) const {
    SphereHit best = hit_to_beat(ray, hit);
    if (!avx2::closest_hit(ray, best, set().columns())) return false;
    hit = best;
    return true;
  }
  bool any_hit_avx2(const Ray& ray) const {
    return avx2::any_hit(ray, hit_to_beat(ray, SphereHit{}), set().columns());
  }
#endif

 private:
  const Set& set() const {
    return static_cast<const Set&>(*this);
  }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
