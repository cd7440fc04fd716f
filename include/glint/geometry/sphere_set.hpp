#pragma once
// Spheres in structure-of-arrays form, padded to a multiple of eight, scanned linearly by the
// leaf kernel: 8-wide with AVX2 (see simd.hpp), else sphere by sphere.

#include <cstddef>
#include <cstdint>

#include "glint/detail/aligned_array.hpp"
#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"

namespace glint {

class SphereSet {
 public:
  /// The storage is padded to a multiple of this many spheres.
  static constexpr std::size_t kLanes = 8;

  SphereSet() = default;

  /// Adds a sphere known to the rest of the scene as `id` (what hits report, and what
  /// Ray::origin_sphere refers to).
  void add(const Vec3& center, float radius, std::uint32_t id) {
    const std::size_t slot = count_;
    if (slot == cx_.size()) grow();
    cx_[slot] = center.x;
    cy_[slot] = center.y;
    cz_[slot] = center.z;
    r2_[slot] = radius * radius;
    ids_[slot] = id;
    ++count_;
  }

  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  Vec3 center(std::size_t slot) const { return {cx_[slot], cy_[slot], cz_[slot]}; }
  float radius_squared(std::size_t slot) const { return r2_[slot]; }
  std::uint32_t id(std::size_t slot) const { return ids_[slot]; }

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
    if (!test_spheres(ray, *this, 0, count_, best, /*stop_at_first=*/false)) return false;
    hit = best;
    return true;
  }
  bool any_hit_scalar(const Ray& ray) const {
    SphereHit best = hit_to_beat(ray, SphereHit{});
    return test_spheres(ray, *this, 0, count_, best, /*stop_at_first=*/true);
  }

#ifdef GLINT_AVX2
  static_assert(kLanes == avx2::kWidth);

  /// The queries with the 8-wide kernel.
  bool closest_hit_avx2(const Ray& ray, SphereHit& hit) const {
    SphereHit best = hit_to_beat(ray, hit);
    if (!avx2::closest_hit(ray, best, columns())) return false;
    hit = best;
    return true;
  }
  bool any_hit_avx2(const Ray& ray) const {
    return avx2::any_hit(ray, hit_to_beat(ray, SphereHit{}), columns());
  }

  /// The storage as the 8-wide kernel reads it.
  avx2::SphereColumns columns() const {
    return {cx_.data(), cy_.data(), cz_.data(), r2_.data(), ids_.data(), count_};
  }
#endif

 private:
  void grow() {
    // Padding spheres have squared radius -1: no ray meets them.
    const std::size_t new_size = cx_.size() + kLanes;
    cx_.resize(new_size, 0.0f);
    cy_.resize(new_size, 0.0f);
    cz_.resize(new_size, 0.0f);
    r2_.resize(new_size, -1.0f);
    ids_.resize(new_size, kNoSphere);
  }

  detail::AlignedArray<float> cx_, cy_, cz_, r2_;
  detail::AlignedArray<std::uint32_t> ids_;
  std::size_t count_ = 0;
};

static_assert(SphereAccelerator<SphereSet>);

}  // namespace glint
