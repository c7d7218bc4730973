// Exact coverage: vertices snapped to a fixed-point grid with `subpixelBits` fraction bits,
// int64 edge functions, and the top-left fill rule, so a pixel centre on an edge shared by two
// triangles belongs to exactly one of them (meshoptimizer's rasterizer and D3D's rules).
//
// Range: snapped coordinates satisfy |X| <= 2^29 (the guard band in clip.h ensures it), so
// coordinate differences fit in 31 bits, products in 61 bits and the sum of two in 62 bits:
// every edge value is exact in int64.
#pragma once

#include <cstdint>

namespace rc {

struct EdgeFunctions {
  // E_i(p) = a[i] * (p.x - ox[i]) + b[i] * (p.y - oy[i]) for the edge opposite vertex i,
  // sign-normalised so E_i > 0 inside; p in fixed point. Inside iff E_i + bias[i] >= 0 for
  // all i, where bias is 0 on top and left edges (a centre exactly on them is in) and -1 on
  // the others (a centre exactly on them is out).
  std::int64_t a[3], b[3], ox[3], oy[3], bias[3];
};

// Twice the signed area of the snapped triangle (x[i], y[i]), raster space with y down:
// positive when it is clockwise on screen.
inline std::int64_t snappedArea(const std::int64_t x[3], const std::int64_t y[3]) {
  return (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
}

// a, b, ox and oy of edge i (opposite vertex i) of the snapped triangle, sign-normalised by
// `sign`, the sign of its snappedArea (+1 or -1). T is the coordinates' integer type.
template <typename T>
inline void setEdge(const T x[3], const T y[3], std::int64_t sign, int i, EdgeFunctions& e) {
  const int from = (i + 1) % 3, to = (i + 2) % 3;
  // (to - from) x (p - from): a = -(dy), b = dx, sign-normalised.
  e.a[i] = sign * (std::int64_t(y[from]) - y[to]);
  e.b[i] = sign * (std::int64_t(x[to]) - x[from]);
  e.ox[i] = x[from];
  e.oy[i] = y[from];
}

// Edge functions of the snapped triangle, given its snappedArea (not zero).
inline void makeEdgeFunctions(const std::int64_t x[3], const std::int64_t y[3], std::int64_t area,
                              EdgeFunctions& e) {
  const std::int64_t sign = area > 0 ? 1 : -1;
  for (int i = 0; i < 3; ++i) {
    setEdge(x, y, sign, i, e);
    // With positive orientation in y-down raster space, a top edge runs horizontally in +x
    // (a == 0, b > 0) and a left edge runs upwards (dy < 0, i.e. a > 0).
    // (Integer arithmetic: GCC 12 turned the boolean form into a byte store and a 64-bit
    // reload, a store-forwarding stall that cost a sixth of the whole set-up.)
    const std::int64_t topLeft = std::int64_t(e.a[i] > 0) | (std::int64_t(e.a[i] == 0) & std::int64_t(e.b[i] > 0));
    e.bias[i] = topLeft - 1;
  }
}

// As above, from the vertices alone. Returns false for a zero-area triangle, which covers
// nothing.
inline bool makeEdgeFunctions(const std::int64_t x[3], const std::int64_t y[3], EdgeFunctions& e) {
  const std::int64_t area = snappedArea(x, y);
  if (area == 0) return false;
  makeEdgeFunctions(x, y, area, e);
  return true;
}

// Fixed-point position of pixel centre coordinate `pixel` (x + 0.5) with `bits` fraction bits.
inline std::int64_t pixelCenterFixed(int pixel, int bits) {
  return (2 * std::int64_t(pixel) + 1) << (bits - 1);
}

}  // namespace rc
