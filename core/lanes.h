// Four lanes of doubles (GCC vector extensions) and the few operations the standard library
// offers only for one double, written so that every lane gets the bits the scalar function
// gives. Code written once for a value V that is either a double or an f64x4 runs the same
// operations in the same order on both (the build has -ffp-contract=off), so its lanes agree
// with its scalar runs bit for bit. Vector values pass only between always-inlined functions,
// so that a caller compiled with the AVX2 target attribute gets AVX2 code throughout.
#pragma once

#include <emmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/vec3.hpp>

#include "core/split_vectors.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc::lanes {

typedef double f64x4 __attribute__((vector_size(32)));
typedef std::int64_t i64x4 __attribute__((vector_size(32)));
// Four lanes of 32 bits: what four double lanes narrow to.
typedef float f32x4 __attribute__((vector_size(16)));
typedef std::int32_t i32x4 __attribute__((vector_size(16)));
typedef std::uint32_t u32x4 __attribute__((vector_size(16)));

#define RC_LANES_INLINE inline __attribute__((always_inline))

template <typename To, typename From>
RC_LANES_INLINE To bitsAs(const From& from) {
  static_assert(sizeof(To) == sizeof(From));
  To to;
  std::memcpy(&to, &from, sizeof to);
  return to;
}

// fabs, and std::max and std::min as the standard defines them (the first argument unless the
// second is larger, or smaller), so that every lane picks what the scalar code picks.
// kWidth, here and in select: the widest register of the caller's target, in bytes. Code
// compiled for the SSE2 baseline passes 16, so that its four-lane comparisons and selects run
// on two-lane halves; left at 32, GCC lowers them lane by lane, with a branch per lane
// (core/split_vectors.h). The double overloads take it too, so that code written once for both
// can pass it.
RC_LANES_INLINE double absOf(double v) { return std::fabs(v); }
template <std::size_t kWidth = 32>
RC_LANES_INLINE double stdMax(double a, double b) { return std::max(a, b); }
template <std::size_t kWidth = 32>
RC_LANES_INLINE double stdMin(double a, double b) { return std::min(a, b); }
RC_LANES_INLINE f64x4 absOf(const f64x4& v) {
  return bitsAs<f64x4>(bitsAs<i64x4>(v) & std::int64_t(0x7FFFFFFFFFFFFFFF));
}
template <std::size_t kWidth = 32>
RC_LANES_INLINE f64x4 stdMax(const f64x4& a, const f64x4& b) {
  return split::select<kWidth>(split::less<kWidth>(a, b), b, a);
}
template <std::size_t kWidth = 32>
RC_LANES_INLINE f64x4 stdMin(const f64x4& a, const f64x4& b) {
  return split::select<kWidth>(split::less<kWidth>(b, a), b, a);
}

// The correctly rounded square root (IEEE 754), so every lane equals std::sqrt of it.
RC_LANES_INLINE double sqrtOf(double v) { return std::sqrt(v); }
RC_LANES_INLINE f64x4 sqrtOf(const f64x4& v) {
  // Two SSE2 square roots on the halves, in registers: halves stored to memory and read back
  // whole cannot be forwarded, a stall that showed in the rasterizer's setupShade.
  const __m128d low = _mm_sqrt_pd(__builtin_shufflevector(v, v, 0, 1));
  const __m128d high = _mm_sqrt_pd(__builtin_shufflevector(v, v, 2, 3));
  return __builtin_shufflevector(low, high, 0, 1, 2, 3);
}

// Selects a where the mask (a comparison's result) is set, b elsewhere.
template <std::size_t kWidth = 32>
RC_LANES_INLINE double select(bool mask, double a, double b) { return mask ? a : b; }
template <std::size_t kWidth = 32>
RC_LANES_INLINE f64x4 select(const i64x4& mask, const f64x4& a, const f64x4& b) {
  return split::select<kWidth>(mask, a, b);
}

// A 3-vector of doubles or of lanes, with glm's operations in glm's order: dot is
// (x x' + y y') + z z', cross is (y z' - y' z, z x' - z' x, x y' - x' y).
template <typename V>
struct Vec3 {
  V x, y, z;
};

template <typename V>
RC_LANES_INLINE Vec3<V> operator+(const Vec3<V>& a, const Vec3<V>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename V>
RC_LANES_INLINE Vec3<V> operator-(const Vec3<V>& a, const Vec3<V>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename V, typename S>
RC_LANES_INLINE Vec3<V> operator*(const S& s, const Vec3<V>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <typename V>
RC_LANES_INLINE V dot(const Vec3<V>& a, const Vec3<V>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename V>
RC_LANES_INLINE Vec3<V> cross(const Vec3<V>& a, const Vec3<V>& b) {
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}
template <typename V>
RC_LANES_INLINE V length(const Vec3<V>& a) {
  return sqrtOf(dot(a, a));
}
// To and from glm's double vectors.
RC_LANES_INLINE Vec3<double> vec3Of(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
RC_LANES_INLINE glm::dvec3 dvec3Of(const Vec3<double>& v) { return {v.x, v.y, v.z}; }

// Every lane the same value (not 0 + v, which turns -0 into +0).
RC_LANES_INLINE f64x4 splat(double v) { return f64x4{v, v, v, v}; }
RC_LANES_INLINE Vec3<f64x4> splat(const Vec3<double>& a) { return {splat(a.x), splat(a.y), splat(a.z)}; }

}  // namespace rc::lanes

#pragma GCC diagnostic pop
