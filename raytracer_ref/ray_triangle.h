// Double-precision barycentrics and distance of a ray against a triangle, and the one place
// where Embree's (u, v) become barycentrics.
#pragma once

#include <glm/glm.hpp>

namespace rc {

// Embree: p = (1 - u - v) p0 + u p1 + v p2, so (b0, b1, b2) = (1 - u - v, u, v).
inline glm::dvec3 baryFromEmbreeUv(float u, float v) {
  return {1.0 - double(u) - double(v), double(u), double(v)};
}

struct DoubleHit {
  bool valid;    // false when the ray is parallel to the triangle's plane (no unique point)
  glm::dvec3 b;  // barycentrics of the ray's point on the plane; sum to 1
  double t;      // ray parameter of that point: o + t d
};

// Signed volumes (Pluecker form, symmetric in the vertices): V_i = d . ((v_j - o) x (v_k - o))
// for (i, j, k) cyclic, b_i = V_i / sum V. Translating to the ray origin first keeps the
// arithmetic relative to the eye. t comes from the plane: n . (v0 - o) / n . d.
inline DoubleHit intersectRayTriangle(const glm::dvec3& o, const glm::dvec3& d,
                                      const glm::dvec3& v0, const glm::dvec3& v1,
                                      const glm::dvec3& v2) {
  const glm::dvec3 a = v0 - o, b = v1 - o, c = v2 - o;
  const double V0 = glm::dot(d, glm::cross(b, c));
  const double V1 = glm::dot(d, glm::cross(c, a));
  const double V2 = glm::dot(d, glm::cross(a, b));
  const double sum = V0 + V1 + V2;
  const glm::dvec3 n = glm::cross(v1 - v0, v2 - v0);
  const double nd = glm::dot(n, d);
  if (!(sum != 0.0) || !(nd != 0.0)) return {false, glm::dvec3(0.0), 0.0};
  return {true, glm::dvec3(V0, V1, V2) / sum, glm::dot(n, a) / nd};
}

}  // namespace rc
