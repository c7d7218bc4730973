// Per-triangle set-up: everything the pixel loops need, computed once per (sub-)triangle.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "rasterizer/clip.h"
#include "rasterizer/coverage.h"

namespace rc {

template <typename Real>
struct TriangleSetup {
  std::uint32_t triangle;    // source triangle index (the tri.id written)
  std::int32_t clipMap;      // index of the 3x3 map to source barycentrics; -1 = identity
  std::int64_t xFixed[3];    // snapped raster positions (subpixelBits fraction bits), for coverage
  std::int64_t yFixed[3];
  int minX, minY, maxX, maxY;  // pixels whose centres may be covered, inclusive, in the viewport
  Real x[3], y[3];           // unsnapped raster positions, for the barycentrics
  Real invArea;              // 1 / signed double area of (x, y)
  Real w[3], invW[3];        // clip w (= depth) of the vertices and its reciprocal
  Real zx, zy;               // gradient of 1/w over raster space (depth test)
};

// The sub-triangle's vertices in clip space, already inside the clip volume.
template <typename Real>
struct SetupContext {
  int width, height, subpixelBits;
};

// Projects, snaps and sets up one sub-triangle. Returns false when it covers no pixel centre
// (zero snapped area, or its bounding box holds no centre inside the viewport).
template <typename Real>
bool setupTriangle(const glm::vec<4, Real> clip[3], const glm::vec<2, Real> raster[3],
                   const SetupContext<Real>& ctx, TriangleSetup<Real>& s);

// Signed edge function of the edge opposite vertex i at p, from the unsnapped positions:
// l_i = edge(i) * invArea are the screen-space barycentrics.
template <typename Real>
inline Real edgeValue(const TriangleSetup<Real>& s, int i, Real px, Real py) {
  const int from = (i + 1) % 3, to = (i + 2) % 3;
  return (s.x[to] - s.x[from]) * (py - s.y[from]) - (s.y[to] - s.y[from]) * (px - s.x[from]);
}

// 1/w at p: the depth-test key (larger is nearer), linear in raster space.
template <typename Real>
inline Real inverseDepthAt(const TriangleSetup<Real>& s, Real px, Real py) {
  return s.invW[0] + s.zx * (px - s.x[0]) + s.zy * (py - s.y[0]);
}

}  // namespace rc
