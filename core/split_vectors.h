// Comparisons and selects on GCC vector-extension values wider than the target's registers.
// GCC 12 splits arithmetic on such a value into register-wide pieces, but lowers a comparison,
// and a select by a mask (m ? a : b), lane by lane: scalar compares, and a branch per lane in a
// select (tree-vect-generic). In the rasterizer's SSE2 build every 8-lane float or int vector
// (32 bytes) is wider than its registers, and in the AVX2 build every 8-lane double or int64
// vector (64 bytes) is. These helpers do the split themselves: a value wider than kWidth bytes
// (the target's widest register) goes in two halves, each compared or selected natively, and
// the halves are put back together. A comparison or a select gives the same bits either way;
// only the instructions change. A value of kWidth bytes or fewer takes the plain operator.
#pragma once

#include <cstddef>
#include <cstring>
#include <type_traits>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc::split {

#define RC_SPLIT_INLINE inline __attribute__((always_inline))

template <typename E, std::size_t kBytes>
struct VectorOf {
  typedef E type __attribute__((vector_size(kBytes)));
};
template <typename V>
using ElementOf = std::remove_cvref_t<decltype(V{}[0])>;
template <typename V>
using HalfOf = typename VectorOf<ElementOf<V>, sizeof(V) / 2>::type;

// Halves through memcpy, which GCC turns into register moves; __builtin_shufflevector on a
// vector wider than the registers is lowered lane by lane too.
template <typename V>
RC_SPLIT_INLINE HalfOf<V> lowOf(const V& v) {
  HalfOf<V> h;
  std::memcpy(&h, &v, sizeof h);
  return h;
}
template <typename V>
RC_SPLIT_INLINE HalfOf<V> highOf(const V& v) {
  HalfOf<V> h;
  std::memcpy(&h, reinterpret_cast<const char*>(&v) + sizeof h, sizeof h);
  return h;
}
template <typename H>
RC_SPLIT_INLINE typename VectorOf<ElementOf<H>, 2 * sizeof(H)>::type joined(const H& low, const H& high) {
  typename VectorOf<ElementOf<H>, 2 * sizeof(H)>::type v;
  std::memcpy(&v, &low, sizeof low);
  std::memcpy(reinterpret_cast<char*>(&v) + sizeof low, &high, sizeof high);
  return v;
}

enum class Op { kLess, kGreater, kLessEqual, kGreaterEqual, kEqual, kNotEqual };

template <Op kOp, typename A, typename B>
RC_SPLIT_INLINE auto compareNative(A a, B b) {
  if constexpr (kOp == Op::kLess) return a < b;
  else if constexpr (kOp == Op::kGreater) return a > b;
  else if constexpr (kOp == Op::kLessEqual) return a <= b;
  else if constexpr (kOp == Op::kGreaterEqual) return a >= b;
  else if constexpr (kOp == Op::kEqual) return a == b;
  else return a != b;
}

// a op b lane by lane: the comparison's usual result (a mask of 0 or -1 lanes, or a bool for two
// scalars). b may be a scalar against a vector a; it then stands for every lane, and is
// compared against each half as a scalar (a vector built from it would go through memory).
template <std::size_t kWidth, Op kOp, typename V, typename B>
RC_SPLIT_INLINE auto compare(V a, B b) {
  if constexpr (std::is_arithmetic_v<V> || sizeof(V) <= kWidth) {
    return compareNative<kOp>(a, b);
  } else if constexpr (std::is_arithmetic_v<B>) {
    return joined(compare<kWidth, kOp>(lowOf(a), b), compare<kWidth, kOp>(highOf(a), b));
  } else {
    return joined(compare<kWidth, kOp>(lowOf(a), lowOf(b)), compare<kWidth, kOp>(highOf(a), highOf(b)));
  }
}

template <std::size_t kWidth, typename V, typename B>
RC_SPLIT_INLINE auto less(V a, B b) { return compare<kWidth, Op::kLess>(a, b); }
template <std::size_t kWidth, typename V, typename B>
RC_SPLIT_INLINE auto greater(V a, B b) { return compare<kWidth, Op::kGreater>(a, b); }
template <std::size_t kWidth, typename V, typename B>
RC_SPLIT_INLINE auto lessEqual(V a, B b) { return compare<kWidth, Op::kLessEqual>(a, b); }
template <std::size_t kWidth, typename V, typename B>
RC_SPLIT_INLINE auto greaterEqual(V a, B b) { return compare<kWidth, Op::kGreaterEqual>(a, b); }
template <std::size_t kWidth, typename V, typename B>
RC_SPLIT_INLINE auto equal(V a, B b) { return compare<kWidth, Op::kEqual>(a, b); }
template <std::size_t kWidth, typename V, typename B>
RC_SPLIT_INLINE auto notEqual(V a, B b) { return compare<kWidth, Op::kNotEqual>(a, b); }

// V{} + s, every lane s (and +0 for -0, as that sum gives): a vector wider than the registers
// is built from two register-wide ones; built whole, GCC stores it lane by lane to memory.
template <std::size_t kWidth, typename V, typename S>
RC_SPLIT_INLINE V splat(S s) {
  if constexpr (sizeof(V) <= kWidth) {
    return V{} + s;
  } else {
    const HalfOf<V> half = splat<kWidth, HalfOf<V>>(s);
    return joined(half, half);
  }
}

// m ? a : b lane by lane, m a comparison's result with lanes as wide as a's.
template <std::size_t kWidth, typename M, typename V>
RC_SPLIT_INLINE V select(M m, V a, V b) {
  static_assert(sizeof(M) == sizeof(V));
  if constexpr (sizeof(V) <= kWidth) {
    return m ? a : b;
  } else {
    return joined(select<kWidth>(lowOf(m), lowOf(a), lowOf(b)), select<kWidth>(highOf(m), highOf(a), highOf(b)));
  }
}

#undef RC_SPLIT_INLINE

}  // namespace rc::split

#pragma GCC diagnostic pop
