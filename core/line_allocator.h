// Allocator for buffers read and written in 32-byte vectors: storage aligned to a 64-byte
// cache line. From malloc's 16-byte alignment, half of such accesses straddle two lines; the
// tiles' staging rows and packed records, and the reference's staging strips, are read that
// way (docs/rasterizer-speed.md, "Buffers aligned to cache lines").
#pragma once

#include <cstddef>
#include <new>

namespace rc {

template <typename T>
struct LineAllocator {
  using value_type = T;
  static constexpr std::size_t kLine = 64;

  LineAllocator() = default;
  template <typename U>
  LineAllocator(const LineAllocator<U>&) {}

  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{kLine})); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t{kLine}); }

  template <typename U>
  bool operator==(const LineAllocator<U>&) const { return true; }
};

}  // namespace rc
