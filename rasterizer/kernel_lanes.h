// The tile kernels' vectors: eight lanes of float, int32 or (in 64 bytes) double and int64, as
// GCC vector extensions, with the loads, stores, mask tests and conversions every kernel stage
// uses. Comparisons and selects go through core/split_vectors.h with the target's register
// width (kWidth), since GCC lowers those on a vector wider than the registers lane by lane.
#pragma once

#include <emmintrin.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/split_vectors.h"

namespace rc::kernel {

// Vector values only ever pass between always-inlined functions, so the ABI of passing them
// (which differs with and without AVX) never matters.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

#define RC_KERNEL_INLINE inline __attribute__((always_inline))

typedef float f32x8 __attribute__((vector_size(32)));
typedef double f64x8 __attribute__((vector_size(64)));
typedef std::int32_t i32x8 __attribute__((vector_size(32)));
typedef std::uint32_t u32x8 __attribute__((vector_size(32)));
typedef std::int64_t i64x8 __attribute__((vector_size(64)));

template <typename Real>
struct Lanes;
template <>
struct Lanes<float> {
  using V = f32x8;
  using M = i32x8;  // comparison result of two V
};
template <>
struct Lanes<double> {
  using V = f64x8;
  using M = i64x8;
};

template <typename T>
RC_KERNEL_INLINE T load(const void* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <typename T>
RC_KERNEL_INLINE void store(void* p, const T& v) { std::memcpy(p, &v, sizeof v); }

RC_KERNEL_INLINE bool any(const i32x8& m) {
  std::uint64_t q[4];
  std::memcpy(q, &m, sizeof q);
  return (q[0] | q[1] | q[2] | q[3]) != 0;
}
// any() in one instruction where the caller is AVX2 or AVX-512 code (renderTile<Real, 32>
// or <Real, 64>): vptest sets ZF when every bit is 0. The generic form goes through memory,
// four loads and three ORs, 3 to 6% of the tiles' time. Written as asm since an AVX2 builtin cannot sit in code shared
// with the SSE2 build; the operand is a ymm register only once GCC has inlined it into AVX2
// code. Clang checks the operand's size before inlining and refuses it, so a clang build (the
// fuzzers') takes the generic forms, which give the same answers.
template <bool kAvx2>
RC_KERNEL_INLINE bool anyOf(const i32x8& m) {
#if !defined(__clang__)
  if constexpr (kAvx2) {
    bool nonzero;
    asm("vptest %1, %1" : "=@ccnz"(nonzero) : "x"(m));
    return nonzero;
  }
#endif
  return any(m);
}
// Bit k set when lane k of the mask is set (vmovmskps; SSE's movmskps on each half).
template <bool kAvx2>
RC_KERNEL_INLINE unsigned laneBits(const i32x8& m) {
#if !defined(__clang__)
  if constexpr (kAvx2) {
    int bits;
    asm("vmovmskps %1, %0" : "=r"(bits) : "x"(m));
    return unsigned(bits);
  }
#endif
  __m128 half[2];
  std::memcpy(half, &m, sizeof half);
  return unsigned(_mm_movemask_ps(half[0]) | (_mm_movemask_ps(half[1]) << 4));
}

template <typename M>
RC_KERNEL_INLINE M maskAs(const i32x8& m) { return __builtin_convertvector(m, M); }
template <typename M>
RC_KERNEL_INLINE i32x8 mask32(const M& m) { return __builtin_convertvector(m, i32x8); }

template <typename Real>
RC_KERNEL_INLINE typename Lanes<Real>::V iota() {
  return typename Lanes<Real>::V{0, 1, 2, 3, 4, 5, 6, 7};
}
RC_KERNEL_INLINE i32x8 iota32() { return i32x8{0, 1, 2, 3, 4, 5, 6, 7}; }

template <typename Real>
RC_KERNEL_INLINE f32x8 toFloat(const typename Lanes<Real>::V& v) {
  if constexpr (sizeof(Real) == 4) {
    return v;
  } else {
    return __builtin_convertvector(v, f32x8);
  }
}

// std::fabs of a scalar, or of each lane of a float vector (the sign bit cleared).
template <typename T>
RC_KERNEL_INLINE T absOf(const T& v) {
  if constexpr (std::is_arithmetic_v<T>) {
    return std::fabs(v);
  } else {
    u32x8 bits;
    std::memcpy(&bits, &v, sizeof bits);
    bits &= 0x7FFFFFFFu;
    T r;
    std::memcpy(&r, &bits, sizeof r);
    return r;
  }
}

#pragma GCC diagnostic pop

}  // namespace rc::kernel
