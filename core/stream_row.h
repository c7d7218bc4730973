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

}  // namespace rc
