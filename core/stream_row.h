// Copying a finished row of a plane out of a small staging buffer with non-temporal stores
// (SSE's movntdq, in every x86-64) when the destination is 16-byte aligned. Planes are written
// once per frame and not read back in it, so skipping the read-for-ownership halves the
// memory traffic; copying plane by plane keeps whole cache lines together for the
// write-combining buffers. The writer ends its work with a store fence (_mm_sfence) so the
// stores are visible before it reports done.
#pragma once

#include <emmintrin.h>

#include <cstdint>

namespace rc {

inline __attribute__((always_inline)) void streamRow(std::uint32_t* to, const std::uint32_t* from, int n) {
  int k = 0;
  if ((reinterpret_cast<std::uintptr_t>(to) & 15u) == 0) {
    for (; k + 4 <= n; k += 4) {
      _mm_stream_si128(reinterpret_cast<__m128i*>(to + k), _mm_loadu_si128(reinterpret_cast<const __m128i*>(from + k)));
    }
  }
  for (; k < n; ++k) to[k] = from[k];
}

// streamRow for code shared between an SSE2 build and an AVX2 one (kAvx2: the caller is
// inlined into a function with the AVX2 target). There, a row of 64 values (a tile row of the
// rasterizer, a strip row of the reference) at a 32-byte aligned address takes eight 32-byte
// stores inline: a third of the instructions of the 16-byte loop, and no call. Written as asm
// (vmovntdq) since an AVX2 intrinsic cannot sit in the shared code; clang checks the operand
// before inlining and refuses it, so a clang build (the fuzzers') takes streamRow.
template <bool kAvx2>
inline __attribute__((always_inline)) void streamRowOf(std::uint32_t* to, const std::uint32_t* from, int n) {
#if !defined(__clang__)
  if constexpr (kAvx2) {
    typedef std::uint32_t Row8 __attribute__((vector_size(32)));
    if (n == 64 && (reinterpret_cast<std::uintptr_t>(to) & 31u) == 0) {
      for (int k = 0; k < 64; k += 8) {
        Row8 v;
        __builtin_memcpy(&v, from + k, sizeof v);
        asm volatile("vmovntdq %1, %0" : "=m"(*reinterpret_cast<Row8*>(to + k)) : "x"(v));
      }
      return;
    }
  }
#endif
  streamRow(to, from, n);
}

}  // namespace rc
