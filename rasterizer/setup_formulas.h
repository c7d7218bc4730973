// The set-up's floating-point formulas, written once for one value V: a double (setup.cpp, one
// triangle) or four lanes of doubles (setup_batch.cpp, four triangles). Both run the same
// operations in the same order, so the records agree bit for bit
// (SetupBatch.MatchesSetupCoverageAndSetupShadeBitForBit). Snapping and the integer edge
// functions stay apart: they take int64 scalars in one and double lanes in the other.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>

#include "core/lanes.h"
#include "rasterizer/setup.h"

// Vector values only pass between always-inlined functions (kernel_lanes.h).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc::formulas {

using lanes::absOf;
using lanes::f64x4;
using lanes::i64x4;
using lanes::stdMax;
using lanes::stdMin;

#define RC_FORMULA_INLINE inline __attribute__((always_inline))

// |(lx, ly)| from its squared length: sqrt of the sum of squares (hypot costs more than the
// rest of the set-up), unless a square overflowed or underflowed.
// kWidth, here and below: the caller's widest register in bytes (core/lanes.h's stdMax).
template <std::size_t kWidth>
RC_FORMULA_INLINE double lengthOf(double squares, double lx, double ly) {
  return std::isnormal(squares) ? std::sqrt(squares) : std::hypot(lx, ly);
}
template <std::size_t kWidth>
RC_FORMULA_INLINE f64x4 lengthOf(const f64x4& squares, const f64x4& lx, const f64x4& ly) {
  f64x4 length = lanes::sqrtOf(squares);
  const i64x4 normal = split::greaterEqual<kWidth>(squares, std::numeric_limits<double>::min()) &
                       split::lessEqual<kWidth>(squares, std::numeric_limits<double>::max());
  if (!(normal[0] & normal[1] & normal[2] & normal[3])) {
    for (int k = 0; k < 4; ++k) {
      if (!normal[k]) length[k] = std::hypot(lx[k], ly[k]);
    }
  }
  return length;
}

// The vertices relative to the anchor pixel's centre (ax, ay), their 1/w, and the doubled
// signed area of the unsnapped triangle: what both halves of the set-up start from. `noise`
// bounds the rounding of `area`: its two products' magnitudes times 16 u (the anchoring, the
// differences, the products and their difference each round once, 8 u in all, doubled).
template <typename V>
struct Anchored {
  V x[3], y[3], invW[3], area, noise;
};

template <typename V>
RC_FORMULA_INLINE Anchored<V> anchoredOf(const V rx[3], const V ry[3], const V w[3], const V& ax, const V& ay) {
  Anchored<V> a;
  for (int i = 0; i < 3; ++i) {
    a.x[i] = rx[i] - ax;
    a.y[i] = ry[i] - ay;
    a.invW[i] = 1.0 / w[i];
  }
  const V p = (a.x[1] - a.x[0]) * (a.y[2] - a.y[0]), q = (a.y[1] - a.y[0]) * (a.x[2] - a.x[0]);
  a.area = p - q;
  a.noise = 16.0 * 0x1p-53 * (absOf(p) + absOf(q));
  return a;
}

// The numerators of l_i = E_i / area, with E_i the edge function of the edge opposite vertex
// i: its value at the anchor (p = 0) and its gradient, d(E_i)/dx = -(y_to - y_from), etc.
template <typename V>
struct EdgeNumerators {
  V e0, ex, ey;
};

template <typename V>
RC_FORMULA_INLINE EdgeNumerators<V> edgeNumerators(const Anchored<V>& a, int i) {
  const int from = (i + 1) % 3, to = (i + 2) % 3;
  return {(a.x[to] - a.x[from]) * (0.0 - a.y[from]) - (a.y[to] - a.y[from]) * (0.0 - a.x[from]),
          -(a.y[to] - a.y[from]), a.x[to] - a.x[from]};
}

// The depth-key plane key0 + keyX dx + keyY dy, key = keyA + keyB / w: the 1/w plane, sum_i
// l_i / w_i, is the sums of the edge numerators weighted by 1/w_i, each divided by the area
// once (4 divisions; the barycentric planes take 12).
template <typename V>
struct KeyPlane {
  V key0, keyX, keyY;
};

template <typename V>
RC_FORMULA_INLINE KeyPlane<V> keyPlaneOf(const Anchored<V>& a, const SetupContext& ctx) {
  V s0{}, sx{}, sy{};
  for (int i = 0; i < 3; ++i) {
    const EdgeNumerators<V> e = edgeNumerators(a, i);
    s0 += e.e0 * a.invW[i];
    sx += e.ex * a.invW[i];
    sy += e.ey * a.invW[i];
  }
  const V invW0 = s0 / a.area, zx = sx / a.area, zy = sy / a.area;
  return {ctx.keyA + ctx.keyB * invW0, ctx.keyB * zx, ctx.keyB * zy};
}

// The anchored barycentric planes l_i = l0 + lx dx + ly dy, and 1 / |grad l_i|: pixels from
// l_i = 0 to l_i = 1.
template <typename V>
struct Planes {
  V l0[3], lx[3], ly[3], height[3];
};

template <std::size_t kWidth = 32, typename V>
RC_FORMULA_INLINE Planes<V> planesOf(const Anchored<V>& a) {
  Planes<V> p;
  for (int i = 0; i < 3; ++i) {
    const EdgeNumerators<V> e = edgeNumerators(a, i);
    p.l0[i] = e.e0 / a.area;
    p.lx[i] = e.ex / a.area;
    p.ly[i] = e.ey / a.area;
  }
  for (int i = 0; i < 3; ++i) {
    const V squares = p.lx[i] * p.lx[i] + p.ly[i] * p.ly[i];
    p.height[i] = 1.0 / lengthOf<kWidth>(squares, p.lx[i], p.ly[i]);
  }
  return p;
}

template <typename V>
struct Bounds {
  V bary, depth;
};

// The error bound of docs/numerics.md ("The rasterizer's bound"), before its rounding to float.
// u: the per-pixel unit roundoff. Each l_i = l0 + lx dx + ly dy rounds its three coefficients,
// two products and two sums: error <= 4 u (|l0| + (|lx| + |ly|) R) + O(u^2), with R the
// largest offset from the anchor. delta bounds how far the double transform may have moved a
// vertex, in pixels; l_i moves by at most |grad l_i| delta per unit of barycentric weight on
// each of the three vertices. (rx, ry): raster positions; (cx, cy, w): clip positions.
template <std::size_t kWidth = 32, typename V>
RC_FORMULA_INLINE Bounds<V> boundsOf(const Planes<V>& p, const V& R, const V rx[3], const V ry[3], const V cx[3],
                                     const V cy[3], const V w[3], const SetupContext& ctx, bool clipped) {
  const double u = ctx.unitRoundoff;
  V epsL{}, gradient{}, lMax{};
  for (int i = 0; i < 3; ++i) {
    const V g = absOf(p.lx[i]) + absOf(p.ly[i]);
    epsL = stdMax<kWidth>(epsL, 4.0 * u * (absOf(p.l0[i]) + g * R));
    gradient = stdMax<kWidth>(gradient, g);
    lMax = stdMax<kWidth>(lMax, absOf(p.l0[i]) + g * R);
  }
  const V wMin = stdMin<kWidth>(stdMin<kWidth>(w[0], w[1]), w[2]);
  const V wMax = stdMax<kWidth>(stdMax<kWidth>(w[0], w[1]), w[2]);
  const V rho = wMax / wMin;
  V delta{};
  for (int i = 0; i < 3; ++i) {
    const V ndc = stdMax<kWidth>(absOf(cx[i]), absOf(cy[i])) / w[i];
    delta = stdMax<kWidth>(delta, 0.5 * std::max(ctx.width, ctx.height) * ctx.clipError * (1.0 + ndc) / w[i]);
  }
  V largest = absOf(rx[0]);
  for (const V& v : {rx[1], rx[2], ry[0], ry[1], ry[2]}) largest = stdMax<kWidth>(largest, absOf(v));
  delta += 0x1p-50 * (largest + 1.0);
  epsL += 3.0 * delta * gradient * (1.0 + lMax);
  // Perspective division: |db_i| <= rho (1 + 3 b_i) max|dl| <= 4 rho epsL (l within [0, 1]
  // up to the snapping band), plus about 6 u from forming q, its sum and the quotient; a
  // clipped sub-triangle's 3x3 map (columns summing to 1, entries in [0, 1]) at most triples
  // that and adds 4 u; the float output adds half an ulp of values below 2 (a barycentric
  // leaves [0, 1] only by the snapping band), 2^-23 relative for depth.
  const V lFactor = stdMax<kWidth>(V{} + 1.0, lMax);
  const V perspective = 4.0 * rho * epsL * lFactor + 6.0 * u;
  Bounds<V> b;
  b.bary = perspective;
  if (clipped) b.bary = 3.0 * perspective + 4.0 * u;
  b.bary += 0x1p-23;
  b.depth = 6.0 * rho * epsL * lFactor + 6.0 * u + 0x1p-23;
  return b;
}

}  // namespace rc::formulas

#pragma GCC diagnostic pop
