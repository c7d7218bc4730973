// Double-precision barycentrics and distance of a ray against a triangle, with their error
// bounds (docs/numerics.md), and the one place where Embree's (u, v) become barycentrics.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <limits>

#include "core/lanes.h"

// Vector values pass only between always-inlined functions (core/lanes.h).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc {

// Embree: p = (1 - u - v) p0 + u p1 + v p2, so (b0, b1, b2) = (1 - u - v, u, v), for one hit
// or four lanes of them (u and v already widened to double).
template <typename V>
RC_LANES_INLINE lanes::Vec3<V> baryFromEmbreeUv(const V& u, const V& v) {
  return {1.0 - u - v, u, v};
}
inline glm::dvec3 baryFromEmbreeUv(float u, float v) { return lanes::dvec3Of(baryFromEmbreeUv(double(u), double(v))); }

struct DoubleHit {
  bool valid;         // false when the ray is parallel to the triangle's plane
  glm::dvec3 b;       // barycentrics of the ray's point on the plane; b0 = 1 - b1 - b2
  double t;           // ray parameter of that point: o + t d
  double baryBound;   // bound on |b - exact| from the double arithmetic below
  double depthBound;  // bound on |t - exact| / |t|
};

// Moeller-Trumbore in double, relative to vertex 0: e1 = v1 - v0, e2 = v2 - v0, P = d x e2,
// det = e1 . P, T = o - v0, b1 = T . P / det, Q = T x e1, b2 = d . Q / det, t = e2 . Q / det.
// Each dot product of computed vectors errs by at most about 4 u times the product of their
// lengths, so with L the longest edge: |db| <= 16 u |d| L (|T| + 3 L) / |det|, a bound that
// grows with the triangle's conditioning L^2 / 2A, with 1 / |cos(ray, normal)| and with the
// distance |T| relative to L, exactly as the derivation in docs/numerics.md.
//
// Everything but P, det, b1, b2, |d| and the terms with det depends on the triangle and the
// ray's origin alone: TriangleFrame holds those parts, so that the many rays from one origin
// (a camera's) that hit one triangle compute them once. Splitting changes no operation or
// its order, so the result is the same to the bit. V is a double or four lanes of them
// (core/lanes.h): each lane gets the bits the double code gives.
template <typename V>
struct TriangleFrame {
  lanes::Vec3<V> e1, e2, T, Q;
  V tNumerator;  // e2 . Q
  V L;           // longest edge
  V lengthT, lengthE1, lengthE2;
  V depthBoundT;  // |e2| |T| |e1| / |e2 . Q|: the depth bound's part without det
};

// kWidth: the caller's widest register in bytes, for the comparisons and selects (core/lanes.h).
template <std::size_t kWidth = 32, typename V>
RC_LANES_INLINE TriangleFrame<V> triangleFrame(const lanes::Vec3<V>& o, const lanes::Vec3<V>& v0,
                                               const lanes::Vec3<V>& v1, const lanes::Vec3<V>& v2) {
  using lanes::length;
  TriangleFrame<V> f;
  f.e1 = v1 - v0;
  f.e2 = v2 - v0;
  f.T = o - v0;
  f.Q = lanes::cross(f.T, f.e1);
  f.tNumerator = lanes::dot(f.e2, f.Q);
  // std::max({a, b, c}) keeps the first of equal largest values, as stdMax does.
  f.L = lanes::stdMax<kWidth>(lanes::stdMax<kWidth>(length(f.e1), length(f.e2)), length(f.e2 - f.e1));
  f.lengthT = length(f.T);
  f.lengthE1 = length(f.e1);
  f.lengthE2 = length(f.e2);
  f.depthBoundT = f.lengthE2 * f.lengthT * f.lengthE1 / lanes::absOf(f.tNumerator);
  return f;
}

// A hit's values; `valid` is false (a zero lane) where the ray is parallel to the plane, and
// there the other values are meaningless.
template <typename V, typename Mask>
struct LaneHit {
  Mask valid;
  lanes::Vec3<V> b;
  V t, baryBound, depthBound;
};

template <std::size_t kWidth>
RC_LANES_INLINE bool finiteNonZero(double det) { return det != 0.0 && std::isfinite(det); }
template <std::size_t kWidth>
RC_LANES_INLINE lanes::i64x4 finiteNonZero(const lanes::f64x4& det) {
  return split::notEqual<kWidth>(det, 0.0) &
         split::lessEqual<kWidth>(lanes::absOf(det), std::numeric_limits<double>::max());
}

template <std::size_t kWidth = 32, typename V>
RC_LANES_INLINE auto intersectRay(const TriangleFrame<V>& f, const lanes::Vec3<V>& d) {
  constexpr double u = 0x1p-53;
  const lanes::Vec3<V> P = lanes::cross(d, f.e2);
  const V det = lanes::dot(f.e1, P);
  const auto valid = finiteNonZero<kWidth>(det);
  const V safeDet = lanes::select<kWidth>(valid, det, V{} + 1.0);  // no division by 0 in any lane
  const V inv = 1.0 / safeDet;
  const V b1 = lanes::dot(f.T, P) * inv;
  const V b2 = lanes::dot(d, f.Q) * inv;
  const V lengthD = lanes::length(d);
  const V baryBound = 16.0 * u * lengthD * f.L * (f.lengthT + 3.0 * f.L) / lanes::absOf(safeDet);
  const V depthBound = 8.0 * u * (f.depthBoundT + f.lengthE1 * lengthD * f.lengthE2 / lanes::absOf(safeDet));
  return LaneHit<V, decltype(valid)>{valid, {1.0 - b1 - b2, b1, b2}, f.tNumerator * inv, baryBound, depthBound};
}

// One ray from o along d against the triangle (v0, v1, v2).
inline DoubleHit intersectRayTriangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& v0,
                                      const glm::dvec3& v1, const glm::dvec3& v2) {
  using lanes::vec3Of;
  const auto hit = intersectRay(triangleFrame(vec3Of(o), vec3Of(v0), vec3Of(v1), vec3Of(v2)), vec3Of(d));
  if (!hit.valid) return {false, glm::dvec3(0.0), 0.0, 0.0, 0.0};
  return {true, lanes::dvec3Of(hit.b), hit.t, hit.baryBound, hit.depthBound};
}

}  // namespace rc

#pragma GCC diagnostic pop
