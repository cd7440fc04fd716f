#pragma once
// Spheres in structure-of-arrays form, padded to a multiple of the SIMD width, and the closest
// hit / any hit queries over them. The loops are written so that each lane of a vector
// register handles one sphere; with AVX2 enabled, an explicit 8-wide kernel is used, and the
// scalar loop stays as the reference the SIMD kernel is tested against.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "glint/geometry/ray.hpp"
#include "glint/geometry/ray_sphere.hpp"

#if defined(__AVX2__) && defined(__FMA__) && !defined(GLINT_NO_SIMD)
#include <immintrin.h>
#define GLINT_SPHERE_SET_AVX2 1
#endif

namespace glint {

struct SphereHit {
  float t = kInfinity;
  std::uint32_t sphere = kNoSphere;
};

class SphereSet {
 public:
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
    ids_[slot] = static_cast<std::int32_t>(id);
    ++count_;
  }

  std::size_t size() const { return count_; }
  Vec3 center(std::size_t slot) const { return {cx_[slot], cy_[slot], cz_[slot]}; }
  float radius_squared(std::size_t slot) const { return r2_[slot]; }
  std::uint32_t id(std::size_t slot) const { return static_cast<std::uint32_t>(ids_[slot]); }

  /// Nearest hit with t in (ray.t_min, min(ray.t_max, hit.t)); updates `hit` and returns true
  /// if one is found. The ray's origin sphere is skipped: the caller handles it (see Ray).
  bool closest_hit(const Ray& ray, SphereHit& hit) const {
#ifdef GLINT_SPHERE_SET_AVX2
    return closest_hit_avx2(ray, hit);
#else
    return closest_hit_scalar(ray, hit);
#endif
  }

  /// Whether anything but the origin sphere blocks the ray in (ray.t_min, ray.t_max).
  bool any_hit(const Ray& ray) const {
    SphereHit hit;
    hit.t = ray.t_max;
#ifdef GLINT_SPHERE_SET_AVX2
    return closest_hit_avx2(ray, hit, /*stop_at_first=*/true);
#else
    return closest_hit_scalar(ray, hit, /*stop_at_first=*/true);
#endif
  }

  /// The portable reference kernel; also what builds without AVX2 use.
  bool closest_hit_scalar(const Ray& ray, SphereHit& hit, bool stop_at_first = false) const {
    float best = min_of(ray.t_max, hit.t);
    std::uint32_t best_index = kNoSphere;
    for (std::size_t i = 0; i < count_; ++i) {
      if (id(i) == ray.origin_sphere) continue;
      SphereRoots roots;
      if (!intersect_sphere(ray.origin, ray.direction, center(i), std::sqrt(r2_[i]), roots))
        continue;
      const float t = roots.near > ray.t_min ? roots.near : roots.far;
      if (t > ray.t_min && t < best) {
        best = t;
        best_index = id(i);
        if (stop_at_first) break;
      }
    }
    if (best_index == kNoSphere) return false;
    hit.t = best;
    hit.sphere = best_index;
    return true;
  }

#ifdef GLINT_SPHERE_SET_AVX2
  bool closest_hit_avx2(const Ray& ray, SphereHit& hit, bool stop_at_first = false) const {
    const __m256 ox = _mm256_set1_ps(ray.origin.x), oy = _mm256_set1_ps(ray.origin.y),
                 oz = _mm256_set1_ps(ray.origin.z);
    const __m256 dx = _mm256_set1_ps(ray.direction.x), dy = _mm256_set1_ps(ray.direction.y),
                 dz = _mm256_set1_ps(ray.direction.z);
    const __m256 t_min = _mm256_set1_ps(ray.t_min);
    const __m256 zero = _mm256_setzero_ps();
    const __m256 sign_mask = _mm256_set1_ps(-0.0f);
    const __m256i excluded = _mm256_set1_epi32(static_cast<int>(ray.origin_sphere));
    __m256 best = _mm256_set1_ps(min_of(ray.t_max, hit.t));
    __m256i best_index = _mm256_set1_epi32(-1);
    bool found_any = false;
    for (std::size_t base = 0; base < count_; base += kLanes) {
      const __m256 fx = _mm256_sub_ps(ox, _mm256_load_ps(&cx_[base]));
      const __m256 fy = _mm256_sub_ps(oy, _mm256_load_ps(&cy_[base]));
      const __m256 fz = _mm256_sub_ps(oz, _mm256_load_ps(&cz_[base]));
      const __m256 r2 = _mm256_load_ps(&r2_[base]);
      const __m256 b = _mm256_fmadd_ps(fx, dx, _mm256_fmadd_ps(fy, dy, _mm256_mul_ps(fz, dz)));
      const __m256 px = _mm256_fnmadd_ps(b, dx, fx);
      const __m256 py = _mm256_fnmadd_ps(b, dy, fy);
      const __m256 pz = _mm256_fnmadd_ps(b, dz, fz);
      const __m256 perp2 = _mm256_fmadd_ps(px, px, _mm256_fmadd_ps(py, py, _mm256_mul_ps(pz, pz)));
      const __m256 discriminant = _mm256_sub_ps(r2, perp2);
      const __m256 has_roots = _mm256_cmp_ps(discriminant, zero, _CMP_GE_OQ);
      const __m256 c = _mm256_sub_ps(
          _mm256_fmadd_ps(fx, fx, _mm256_fmadd_ps(fy, fy, _mm256_mul_ps(fz, fz))), r2);
      // The roots sum to -2b and multiply to c: from outside (c > 0) a sphere behind the
      // origin (b > 0) has no positive root. Most groups in a room hold only spheres the ray
      // misses or has behind it, and skip the square root and the division.
      const __m256 ahead_or_inside =
          _mm256_or_ps(_mm256_cmp_ps(b, zero, _CMP_LT_OQ), _mm256_cmp_ps(c, zero, _CMP_LE_OQ));
      if (_mm256_movemask_ps(_mm256_and_ps(has_roots, ahead_or_inside)) == 0) continue;
      const __m256 root = _mm256_sqrt_ps(_mm256_max_ps(discriminant, zero));
      // q = -(b + copysign(root, b))
      const __m256 signed_root = _mm256_or_ps(root, _mm256_and_ps(b, sign_mask));
      const __m256 q = _mm256_xor_ps(_mm256_add_ps(b, signed_root), sign_mask);
      const __m256 t0 = _mm256_div_ps(c, q);
      const __m256 t_near = _mm256_min_ps(t0, q);
      const __m256 t_far = _mm256_max_ps(t0, q);
      const __m256 near_ok = _mm256_cmp_ps(t_near, t_min, _CMP_GT_OQ);
      const __m256 t = _mm256_blendv_ps(t_far, t_near, near_ok);
      const __m256i ids = _mm256_load_si256(reinterpret_cast<const __m256i*>(&ids_[base]));
      const __m256 not_excluded = _mm256_castsi256_ps(
          _mm256_xor_si256(_mm256_cmpeq_epi32(ids, excluded), _mm256_set1_epi32(-1)));
      const __m256 closer = _mm256_and_ps(
          _mm256_and_ps(has_roots, not_excluded),
          _mm256_and_ps(_mm256_cmp_ps(t, t_min, _CMP_GT_OQ), _mm256_cmp_ps(t, best, _CMP_LT_OQ)));
      if (_mm256_movemask_ps(closer) == 0) continue;
      found_any = true;
      best = _mm256_blendv_ps(best, t, closer);
      best_index = _mm256_castps_si256(
          _mm256_blendv_ps(_mm256_castsi256_ps(best_index), _mm256_castsi256_ps(ids), closer));
      if (stop_at_first) break;
    }
    if (!found_any) return false;
    // Horizontal minimum by three permute/min steps; then the lane holding it. Exact ties
    // between lanes (coincident spheres) take the lowest id, as the scalar loop does.
    __m256 smallest = _mm256_min_ps(best, _mm256_permute_ps(best, 0b10110001));
    smallest = _mm256_min_ps(smallest, _mm256_permute_ps(smallest, 0b01001110));
    smallest = _mm256_min_ps(smallest, _mm256_permute2f128_ps(smallest, smallest, 1));
    const int lanes = _mm256_movemask_ps(_mm256_cmp_ps(best, smallest, _CMP_EQ_OQ));
    alignas(32) std::int32_t indices[kLanes];
    _mm256_store_si256(reinterpret_cast<__m256i*>(indices), best_index);
    std::int32_t best_i = -1;
    for (int mask = lanes; mask != 0; mask &= mask - 1) {
      const std::int32_t candidate = indices[__builtin_ctz(static_cast<unsigned>(mask))];
      if (candidate >= 0 && (best_i < 0 || candidate < best_i)) best_i = candidate;
    }
    const float best_t = _mm256_cvtss_f32(smallest);
    if (best_i < 0) return false;
    hit.t = best_t;
    hit.sphere = static_cast<std::uint32_t>(best_i);
    return true;
  }
#endif

 private:
  void grow() {
    // Padding lanes hold spheres of squared radius -1: their discriminant is always negative,
    // so no ray ever hits them.
    const std::size_t new_size = cx_.size() + kLanes;
    cx_.resize(new_size, 0.0f);
    cy_.resize(new_size, 0.0f);
    cz_.resize(new_size, 0.0f);
    r2_.resize(new_size, -1.0f);
    ids_.resize(new_size, -1);
  }

  template <typename T>
  struct AlignedAllocator {
    using value_type = T;
    AlignedAllocator() = default;
    template <typename U>
    AlignedAllocator(const AlignedAllocator<U>&) {}
    T* allocate(std::size_t n) {
      return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(32)));
    }
    void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(32)); }
    bool operator==(const AlignedAllocator&) const { return true; }
  };
  using FloatArray = std::vector<float, AlignedAllocator<float>>;

  FloatArray cx_, cy_, cz_, r2_;
  std::vector<std::int32_t, AlignedAllocator<std::int32_t>> ids_;
  std::size_t count_ = 0;
};

}  // namespace glint
