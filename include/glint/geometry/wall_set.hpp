#pragma once
// Huge spheres (the walls and floors of a scene) as anchored spheres (ray_sphere.hpp), in
// structure-of-arrays form padded to a multiple of kBatchWidth (simd.hpp), scanned linearly
// like SphereSet: the same queries, hit order and origin-sphere rule, but a kernel whose error
// scales with the distance of a ray's origin from the anchor instead of with the radius. Anchoring
// every wall at its surface point nearest the camera makes the rays that matter most exact enough:
// a camera 0.001 above a floor of radius 1e9 stands on it instead of seeing through it.

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>

#include "glint/detail/aligned_array.hpp"
#include "glint/geometry/accelerator.hpp"
#include "glint/geometry/linear_scan.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_sphere.hpp"
#include "glint/geometry/simd.hpp"
#include "glint/geometry/sphere_kernel.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

class WallSet : public LinearScan<WallSet> {
 public:
  WallSet() = default;

  /// Adds a sphere known to the rest of the scene as `id`, anchored at its surface point
  /// nearest `reference` (where most rays start: the camera).
  void add(const Vec3& center, float radius, std::uint32_t id, const Vec3& reference) {
    add(anchor_sphere(center, radius, reference), id);
  }

  void add(const AnchoredSphere& sphere, std::uint32_t id) {
    const std::size_t slot = count_;
    if (slot == ax_.size()) grow();
    ax_[slot] = sphere.anchor.x;
    ay_[slot] = sphere.anchor.y;
    az_[slot] = sphere.anchor.z;
    mx_[slot] = sphere.offset.x;
    my_[slot] = sphere.offset.y;
    mz_[slot] = sphere.offset.z;
    r2_[slot] = sphere.radius_squared;
    ids_[slot] = id;
    ++count_;
  }

  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  AnchoredSphere anchored(std::size_t slot) const {
    return {{ax_[slot], ay_[slot], az_[slot]}, {mx_[slot], my_[slot], mz_[slot]}, r2_[slot]};
  }
  std::uint32_t id(std::size_t slot) const { return ids_[slot]; }

#ifdef GLINT_AVX2
  /// The storage as the 8-wide kernel reads it.
  avx2::AnchoredColumns columns() const {
    return {ax_.data(), ay_.data(), az_.data(),  mx_.data(), my_.data(),
            mz_.data(), r2_.data(), ids_.data(), count_};
  }
#endif

 private:
  void grow() {
    // Padding spheres have NaN anchors: the kernel's comparisons fail for them, so no ray
    // meets them (see the anchored quadratic, ray_sphere.hpp).
    const std::size_t new_size = ax_.size() + std::size_t(kBatchWidth);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (detail::AlignedArray<float>* column : {&ax_, &ay_, &az_})
      column->resize(new_size, nan);
    for (detail::AlignedArray<float>* column : {&mx_, &my_, &mz_, &r2_})
      column->resize(new_size, 0.0f);
    ids_.resize(new_size, kNoSphere);
  }

  detail::AlignedArray<float> ax_, ay_, az_, mx_, my_, mz_, r2_;
  detail::AlignedArray<std::uint32_t> ids_;
  std::size_t count_ = 0;
};

static_assert(SphereAccelerator<WallSet>);

}  // namespace glint::inline GLINT_ISA_NAMESPACE
