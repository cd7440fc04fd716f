#pragma once
// An allocator whose large allocations are pages of their own, mapped from the system and
// unmapped when freed, where the system has mmap: memory freed is returned at once, whatever the
// C library's allocator would keep for later. For large buffers freed while others grow (the
// merge candidates of one pass, moved chunk by chunk into one array), so that they are held
// once. Small ones come from operator new, which reuses them without faulting pages in again.

#include <cstddef>
#include <memory>
#include <new>

#if __has_include(<sys/mman.h>)
#include <sys/mman.h>
#endif

#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::detail {

template <typename T>
struct PageAllocator {
  using value_type = T;
  PageAllocator() = default;
  template <typename U>
  PageAllocator(const PageAllocator<U>&) {}

  /// Allocations from this size on are mapped.
  static constexpr std::size_t kMappedBytes = std::size_t(1) << 18;
  /// Mappings from this size on ask for large pages.
  static constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
#if __has_include(<sys/mman.h>)
    if (n * sizeof(T) >= kMappedBytes) {
      void* p = ::mmap(nullptr, n * sizeof(T), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS,
                       -1, 0);
      if (p == MAP_FAILED) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
      // Large pages where the system offers them: a grid of candidates is read at random, and
      // a mapping of 2 MiB pages takes 512 times fewer page faults and TLB entries. A hint
      // only: nothing changes where it is refused.
      if (n * sizeof(T) >= kHugePageBytes) ::madvise(p, n * sizeof(T), MADV_HUGEPAGE);
#endif
      return static_cast<T*>(p);
    }
#endif
    return std::allocator<T>().allocate(n);
  }
  void deallocate(T* p, std::size_t n) {
#if __has_include(<sys/mman.h>)
    if (n * sizeof(T) >= kMappedBytes) {
      ::munmap(p, n * sizeof(T));
      return;
    }
#endif
    std::allocator<T>().deallocate(p, n);
  }
  bool operator==(const PageAllocator&) const {
    return true;
  }
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::detail
