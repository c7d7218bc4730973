// An independent analytic answer for tests: the barycentrics and depth of the point where a
// pixel's camera ray meets a triangle's plane, by Cramer's rule in long double. It shares no
// code with either renderer beyond the camera contract itself.
#pragma once

#include <cmath>

#include "scenes/scene.h"

namespace rc::testing {

struct Analytic {
  long double b[3];
  long double depth;
};

// Solves o + t d = v0 + b1 (v1 - v0) + b2 (v2 - v0).
inline Analytic analyticHit(const Scene& scene, std::uint32_t triangle, int x, int y) {
  const CameraRay ray = scene.camera.rayThroughPixel(x, y);
  const glm::uvec3 t = scene.mesh.triangles[triangle];
  long double v[3][3], o[3], d[3], f[3];
  for (int k = 0; k < 3; ++k) {
    v[0][k] = scene.mesh.positions[t.x][k];
    v[1][k] = scene.mesh.positions[t.y][k];
    v[2][k] = scene.mesh.positions[t.z][k];
    o[k] = ray.origin[k];
    d[k] = ray.direction[k];
    f[k] = scene.camera.forward()[k];
  }
  // Columns: e1, e2, -d; right-hand side: o - v0.
  long double m[3][3], rhs[3];
  for (int k = 0; k < 3; ++k) {
    m[k][0] = v[1][k] - v[0][k];
    m[k][1] = v[2][k] - v[0][k];
    m[k][2] = -d[k];
    rhs[k] = o[k] - v[0][k];
  }
  auto det = [](long double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const long double denominator = det(m);
  long double solution[3];
  for (int c = 0; c < 3; ++c) {
    long double mc[3][3];
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) mc[r][k] = k == c ? rhs[r] : m[r][k];
    }
    solution[c] = det(mc) / denominator;
  }
  const long double tHit = solution[2];
  const long double forwardDotD = d[0] * f[0] + d[1] * f[1] + d[2] * f[2];
  return {{1.0L - solution[0] - solution[1], solution[0], solution[1]}, tHit * forwardDotD};
}

}  // namespace rc::testing
