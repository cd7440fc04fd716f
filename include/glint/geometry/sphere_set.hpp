#pragma once
// Spheres in structure-of-arrays form, padded to a multiple of kBatchWidth (simd.hpp), scanned
// linearly by the leaf kernel: 8-wide with AVX2, else sphere by sphere (linear_scan.hpp).

#include <cstddef>
#include <cstdint>

#include "glint/detail/aligned_array.hpp"
#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/linear_scan.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class SphereSet : public LinearScan<SphereSet> {
 public:
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

#ifdef GLINT_AVX2
  /// The storage as the 8-wide kernel reads it.
  avx2::SphereColumns columns() const {
    return {cx_.data(), cy_.data(), cz_.data(), r2_.data(), ids_.data(), count_};
  }
#endif

 private:
  void grow() {
    // Padding spheres have squared radius -1: no ray meets them.
    const std::size_t new_size = cx_.size() + std::size_t(kBatchWidth);
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

}  // namespace glint::inline GLINT_ISA_NAMESPACE
