// Per-triangle set-up: everything the pixel loops need, computed once per (sub-)triangle.
//
// Precision per stage (docs/rasterizer.md): everything per triangle (transform, clipping,
// projection, snapping and these coefficients) is computed in double; only the per-pixel
// arithmetic runs in Real (float or double). Positions are stored relative to an integer
// pixel anchor near vertex 0, so a pixel's offset (x - anchorX) + 0.5 is exact and the float
// path loses only relative rounding (about u K), not ulp(|raster position|) / triangle height.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "rasterizer/coverage.h"

namespace rc {

template <typename Real>
struct TriangleSetup {
  std::uint32_t triangle;    // source triangle index (the tri.id written)
  std::int32_t clipMap;      // index of the 3x3 map to source barycentrics; -1 = identity
  std::int32_t xFixed[3];    // snapped raster positions (subpixelBits fraction bits); |.| < 2^29
  std::int32_t yFixed[3];
  int minX, minY, maxX, maxY;  // pixels whose centres may be covered, inclusive, in the viewport
  int anchorX, anchorY;      // integer pixel near vertex 0
  Real x[3], y[3];           // unsnapped raster positions minus the anchor
  Real invArea;              // 1 / signed double area of (x, y)
  Real w[3], invW[3];        // clip w (= depth) of the vertices and its reciprocal
  Real zx, zy;               // gradient of 1/w over raster space (depth test)
};

struct SetupContext {
  int width, height, subpixelBits;
};

// Snaps and sets up one sub-triangle from its clip-space vertices and raster positions.
// Returns false when it covers no pixel centre (zero snapped area, or no centre of the
// viewport inside its bounding box).
template <typename Real>
bool setupTriangle(const glm::dvec4 clip[3], const glm::dvec2 raster[3], const SetupContext& ctx,
                   TriangleSetup<Real>& s);

// The pixel centre of (x, y) relative to the anchor: exact in float while |offset| < 2^23.
template <typename Real>
inline Real centerX(const TriangleSetup<Real>& s, int x) { return Real(x - s.anchorX) + Real(0.5); }
template <typename Real>
inline Real centerY(const TriangleSetup<Real>& s, int y) { return Real(y - s.anchorY) + Real(0.5); }

// Signed edge function of the edge opposite vertex i at anchored p, from unsnapped positions:
// l_i = edgeValue(i) * invArea are the screen-space barycentrics.
template <typename Real>
inline Real edgeValue(const TriangleSetup<Real>& s, int i, Real px, Real py) {
  const int from = (i + 1) % 3, to = (i + 2) % 3;
  return (s.x[to] - s.x[from]) * (py - s.y[from]) - (s.y[to] - s.y[from]) * (px - s.x[from]);
}

// 1/w at anchored p: the depth-test key (larger is nearer), linear in raster space.
template <typename Real>
inline Real inverseDepthAt(const TriangleSetup<Real>& s, Real px, Real py) {
  return s.invW[0] + s.zx * (px - s.x[0]) + s.zy * (py - s.y[0]);
}

}  // namespace rc
