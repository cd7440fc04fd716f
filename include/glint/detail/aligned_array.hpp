#pragma once
// A std::vector whose storage is aligned for 32-byte (AVX) loads, for the structure-of-arrays
// columns of the SIMD kernels, or to its element's own alignment where that is larger (a
// 64-byte AVX-512 vector).

#include <cstddef>
#include <new>
#include <vector>

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::detail {

template <typename T>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <typename U>
  AlignedAllocator(const AlignedAllocator<U>&) {}
  static constexpr std::size_t kAlignment = alignof(T) > 32 ? alignof(T) : 32;
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(kAlignment)));
  }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(kAlignment)); }
  bool operator==(const AlignedAllocator&) const { return true; }
};

template <typename T>
using AlignedArray = std::vector<T, AlignedAllocator<T>>;

}  // namespace glint::inline GLINT_ISA_NAMESPACE::detail
