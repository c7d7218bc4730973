// Double-precision barycentrics and distance of a ray against a triangle, with their error
// bounds (docs/numerics.md), and the one place where Embree's (u, v) become barycentrics.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace rc {

// Embree: p = (1 - u - v) p0 + u p1 + v p2, so (b0, b1, b2) = (1 - u - v, u, v).
inline glm::dvec3 baryFromEmbreeUv(float u, float v) {
  return {1.0 - double(u) - double(v), double(u), double(v)};
}

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
// its order, so the result is the same to the bit.
struct TriangleFrame {
  glm::dvec3 e1, e2, T, Q;
  double tNumerator;  // e2 . Q
  double L;           // longest edge
  double lengthT, lengthE1, lengthE2;
  double depthBoundT;  // |e2| |T| |e1| / |e2 . Q|: the depth bound's part without det
};

inline TriangleFrame triangleFrame(const glm::dvec3& o, const glm::dvec3& v0, const glm::dvec3& v1,
                                   const glm::dvec3& v2) {
  TriangleFrame f;
  f.e1 = v1 - v0;
  f.e2 = v2 - v0;
  f.T = o - v0;
  f.Q = glm::cross(f.T, f.e1);
  f.tNumerator = glm::dot(f.e2, f.Q);
  f.L = std::max({glm::length(f.e1), glm::length(f.e2), glm::length(f.e2 - f.e1)});
  f.lengthT = glm::length(f.T);
  f.lengthE1 = glm::length(f.e1);
  f.lengthE2 = glm::length(f.e2);
  f.depthBoundT = f.lengthE2 * f.lengthT * f.lengthE1 / std::fabs(f.tNumerator);
  return f;
}

inline DoubleHit intersectRay(const TriangleFrame& f, const glm::dvec3& d) {
  constexpr double u = 0x1p-53;
  const glm::dvec3 P = glm::cross(d, f.e2);
  const double det = glm::dot(f.e1, P);
  if (!(det != 0.0) || !std::isfinite(det)) return {false, glm::dvec3(0.0), 0.0, 0.0, 0.0};
  const double inv = 1.0 / det;
  const double b1 = glm::dot(f.T, P) * inv;
  const double b2 = glm::dot(d, f.Q) * inv;
  const double lengthD = glm::length(d);
  const double baryBound = 16.0 * u * lengthD * f.L * (f.lengthT + 3.0 * f.L) / std::fabs(det);
  const double depthBound = 8.0 * u * (f.depthBoundT + f.lengthE1 * lengthD * f.lengthE2 / std::fabs(det));
  return {true, {1.0 - b1 - b2, b1, b2}, f.tNumerator * inv, baryBound, depthBound};
}

inline DoubleHit intersectRayTriangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& v0,
                                      const glm::dvec3& v1, const glm::dvec3& v2) {
  return intersectRay(triangleFrame(o, v0, v1, v2), d);
}

}  // namespace rc
