// Allocators for image planes and meshes. A 1080p float plane is 8 MB; faulting it in 4 KB pages cost more
// than rasterizing it (measured: 60% of a 100k-triangle frame). Large planes are aligned to
// 2 MB and advised to use transparent huge pages, which cuts page faults by 512x where the
// kernel allows it (THP "madvise" or "always") and changes nothing where it does not. Planes
// from 256 KB up take this path (an 800x600 plane is 1.9 MB; its padding is under 2 MB).
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

namespace rc {

// Large blocks aligned to 2 MB and advised to use transparent huge pages; elements are
// value-initialised as std::allocator's are (so resize() zeroes floats).
template <typename T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePage = std::size_t(2) << 20;
  static constexpr std::size_t kSmall = std::size_t(256) << 10;

  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kSmall) {
      void* p = nullptr;
      if constexpr (alignof(T) > alignof(std::max_align_t)) {
        // aligned_alloc wants a non-zero multiple of the alignment.
        p = std::aligned_alloc(alignof(T), (bytes / alignof(T) + 1) * alignof(T));
      } else {
        p = std::malloc(bytes ? bytes : 1);  // aligned for max_align_t
      }
      if (!p) throw std::bad_alloc();
      return static_cast<T*>(p);
    }
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
    madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure leaves ordinary pages
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) { std::free(p); }

  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
};

// The same memory for image planes, whose resize() leaves new elements default-initialised
// (for floats: unwritten), so a renderer that writes every pixel does not pay for a fill
// first; assign(n, value) still fills.
template <typename T>
struct PlaneAllocator : HugePageAllocator<T> {
  PlaneAllocator() = default;
  template <typename U>
  PlaneAllocator(const PlaneAllocator<U>&) {}

  template <typename U>
  void construct(U* p) noexcept { ::new (static_cast<void*>(p)) U; }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) { ::new (static_cast<void*>(p)) U(static_cast<Args&&>(args)...); }

  template <typename U>
  bool operator==(const PlaneAllocator<U>&) const { return true; }
};

// A vector in such memory: image planes and the other per-pixel or per-vertex arrays.
template <typename T>
using PlaneVector = std::vector<T, PlaneAllocator<T>>;

// A vector in such memory whose new elements are value-initialised, as std::vector's are: a
// mesh's arrays (scenes/mesh.h), which loaders grow and resize.
template <typename T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace rc
