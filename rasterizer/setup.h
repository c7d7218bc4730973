// Per-triangle set-up: everything the pixel loops need, computed once per (sub-)triangle.
//
// Precision per stage (docs/rasterizer.md): everything per triangle (transform, clipping,
// projection, snapping and these coefficients) is computed in double; only the per-pixel
// arithmetic runs in Real (float or double). Every per-pixel quantity is a plane, evaluated
// as value-at-anchor + gradient . offset, where the anchor is the pixel at the centre of the
// triangle's bounding box clipped to the image: offsets are small exact integers, so the
// float path loses only u (|value at anchor| + |gradient| |offset|), not ulp(|raster
// position|) of vertices that may lie 10^6 pixels away (docs/numerics.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
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
  int anchorX, anchorY;      // the pixel whose centre the planes are anchored at
  Real l0[3], lx[3], ly[3];  // screen-space barycentric planes: l_i = l0 + lx dx + ly dy
  Real w[3], invW[3];        // clip w (= depth) of the vertices and its reciprocal
  Real key0, keyX, keyY;     // depth-test key plane (larger is nearer)
  Real edgeHeight[3];        // 1 / |grad l_i|: pixels from l_i = 0 to l_i = 1; -1 for an edge
                             // inside a clipped polygon, which is no edge of the source
  float baryBound;           // bound on the barycentrics' error (docs/numerics.md)
  float depthBound;          // bound on depth.z's relative error
};

struct SetupContext {
  int width, height, subpixelBits;
  double unitRoundoff;  // of the per-pixel arithmetic: 2^-24 (float) or 2^-53 (double)
  double clipError;     // bound on the absolute error of the double world-to-clip transform
  double keyA, keyB;    // depth key = keyA + keyB / w
};

// Snaps and sets up one sub-triangle from its clip-space vertices and raster positions.
// `innerEdges` has bit i set when the edge opposite vertex i runs inside the source triangle
// (a diagonal of a clipped polygon's fan); `clipped` when the sub-triangle came from clipping.
// Returns false when it covers no pixel centre (zero snapped area, or no centre of the
// viewport inside its bounding box).
template <typename Real>
bool setupTriangle(const glm::dvec4 clip[3], const glm::dvec2 raster[3], unsigned innerEdges,
                   bool clipped, const SetupContext& ctx, TriangleSetup<Real>& s);

// Offsets of pixel (x, y) from the anchor: small integers, exact in float.
template <typename Real>
inline Real offsetX(const TriangleSetup<Real>& s, int x) { return Real(x - s.anchorX); }
template <typename Real>
inline Real offsetY(const TriangleSetup<Real>& s, int y) { return Real(y - s.anchorY); }

// Screen-space barycentrics at offset (dx, dy).
template <typename Real>
inline void screenBarycentrics(const TriangleSetup<Real>& s, Real dx, Real dy, Real l[3]) {
  for (int i = 0; i < 3; ++i) l[i] = s.l0[i] + s.lx[i] * dx + s.ly[i] * dy;
}

// Distance in pixels from the centre to the nearest source edge, from its screen barycentrics.
template <typename Real>
inline float edgeDistanceAt(const TriangleSetup<Real>& s, const Real l[3]) {
  Real nearest = std::numeric_limits<Real>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (s.edgeHeight[i] >= Real(0)) nearest = std::min(nearest, std::fabs(l[i]) * s.edgeHeight[i]);
  }
  return float(nearest);
}

// The depth-test key at offset (dx, dy) (larger is nearer).
template <typename Real>
inline Real depthKeyAt(const TriangleSetup<Real>& s, Real dx, Real dy) {
  return s.key0 + s.keyX * dx + s.keyY * dy;
}

// Bound on the error of depthKeyAt (a rounding of each coefficient, of each product and of
// each sum), turned into the relative depth difference the test cannot resolve at depth w:
// |d key / d w| w = keyB / w.
template <typename Real>
inline float depthTieAt(const TriangleSetup<Real>& s, Real dx, Real dy, double unitRoundoff, double keyB,
                        double w) {
  const double terms = std::fabs(double(s.key0)) + std::fabs(double(s.keyX) * double(dx)) +
                       std::fabs(double(s.keyY) * double(dy));
  return float(5.0 * unitRoundoff * terms * w / keyB);
}

}  // namespace rc
