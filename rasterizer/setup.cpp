// Triangle set-up in double: snapping, bounding box, anchored barycentric and depth planes.
#include "rasterizer/setup.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rc {
namespace {

// floor(a / 2^bits) and ceil(a / 2^bits): an arithmetic shift floors (C++20 defines >> on
// negative values as one), where a 64-bit division costs more than the rest of a set-up.
std::int64_t floorShift(std::int64_t a, int bits) { return a >> bits; }
std::int64_t ceilShift(std::int64_t a, int bits) { return -((-a) >> bits); }

// nearbyint in the default rounding mode (to nearest, ties to even) for |x| < 2^51: adding
// 1.5 * 2^52 leaves no fraction bits, so the sum rounds x as nearbyint does, and the
// subtraction is exact. Without SSE4.1's roundsd, std::nearbyint is a library call.
double roundToInteger(double x) { return (x + 0x1.8p52) - 0x1.8p52; }

// The vertices relative to the anchor pixel's centre, their 1/w, and the doubled signed area
// of the unsnapped triangle: what both halves of the set-up start from.
struct Anchored {
  double x[3], y[3], invW[3], area;
};

Anchored anchoredOf(const glm::dvec4 clip[3], const glm::dvec2 raster[3], int anchorX, int anchorY) {
  Anchored a;
  const double ax = anchorX + 0.5, ay = anchorY + 0.5;  // the anchor's centre, exact
  for (int i = 0; i < 3; ++i) {
    a.x[i] = raster[i].x - ax;
    a.y[i] = raster[i].y - ay;
    a.invW[i] = 1.0 / clip[i].w;
  }
  a.area = (a.x[1] - a.x[0]) * (a.y[2] - a.y[0]) - (a.y[1] - a.y[0]) * (a.x[2] - a.x[0]);
  return a;
}

// The numerators of l_i = E_i / area, with E_i the edge function of the edge opposite vertex
// i: its value at the anchor (p = 0) and its gradient, d(E_i)/dx = -(y_to - y_from), etc.
struct EdgeNumerators {
  double e0, ex, ey;
};

EdgeNumerators edgeNumerators(const Anchored& a, int i) {
  const int from = (i + 1) % 3, to = (i + 2) % 3;
  return {(a.x[to] - a.x[from]) * (0.0 - a.y[from]) - (a.y[to] - a.y[from]) * (0.0 - a.x[from]),
          -(a.y[to] - a.y[from]), a.x[to] - a.x[from]};
}

}  // namespace

template <typename Real>
bool setupCoverage(const glm::dvec4 clip[3], const glm::dvec2 raster[3], const SetupContext& ctx,
                   CoverageSetup<Real>& c) {
  const int bits = ctx.subpixelBits;
  const double scale = double(std::int64_t(1) << bits);
  std::int64_t xf[3], yf[3];
  for (int i = 0; i < 3; ++i) {
    // Round to nearest, ties to even: a pure function of the double input. The guard band
    // keeps |raster * scale| below 2^29 (clip.h), well inside roundToInteger's range.
    xf[i] = static_cast<std::int64_t>(roundToInteger(raster[i].x * scale));
    yf[i] = static_cast<std::int64_t>(roundToInteger(raster[i].y * scale));
  }
  // Under the camera contract (right-handed view space looking down -Z, raster y down) a
  // triangle counter-clockwise seen from the eye has a negative snapped area: a back face has a
  // positive one.
  const std::int64_t area = snappedArea(xf, yf);
  if (area == 0 || (ctx.cullBackFaces && area > 0)) return false;
  // Pixels whose centre (2x+1) * 2^(bits-1) lies within the snapped bounding box; nothing
  // more is computed for a triangle that has none (most sub-pixel triangles).
  const std::int64_t half = std::int64_t(1) << (bits - 1), one = std::int64_t(1) << bits;
  const auto [minXf, maxXf] = std::minmax({xf[0], xf[1], xf[2]});
  const auto [minYf, maxYf] = std::minmax({yf[0], yf[1], yf[2]});
  c.minX = int(std::max<std::int64_t>(0, ceilShift(minXf - half, bits)));
  c.minY = int(std::max<std::int64_t>(0, ceilShift(minYf - half, bits)));
  c.maxX = int(std::min<std::int64_t>(ctx.width - 1, floorShift(maxXf - half, bits)));
  c.maxY = int(std::min<std::int64_t>(ctx.height - 1, floorShift(maxYf - half, bits)));
  if (c.minX > c.maxX || c.minY > c.maxY) return false;
  EdgeFunctions edges{};
  makeEdgeFunctions(xf, yf, area, edges);
  c.flags = 0;
  for (int i = 0; i < 3; ++i) {  // each below 2^30 in magnitude (coverage.h)
    c.a[i] = std::int32_t(edges.a[i]), c.b[i] = std::int32_t(edges.b[i]);
    c.ox[i] = std::int32_t(edges.ox[i]), c.oy[i] = std::int32_t(edges.oy[i]);
    if (edges.bias[i] != 0) c.flags |= CoverageSetup<Real>::kNotTopLeft << i;
  }
  // |E_i| <= |a_i| |X - ox_i| + |b_i| |Y - oy_i| + 1 with |a_i| <= the box's height, |b_i| <=
  // its width, and X (Y) within the box widened by 9 (1) pixels: 8 lanes past its right side.
  const std::int64_t spanX = maxXf - minXf, spanY = maxYf - minYf;
  if (spanX < (std::int64_t(1) << 30) && spanY < (std::int64_t(1) << 30) &&
      spanY * (spanX + 9 * one) + spanX * (spanY + one) + 1 < (std::int64_t(1) << 31)) {
    c.flags |= CoverageSetup<Real>::kNarrow;
  }

  // Anchor: the pixel at the centre of the clipped bounding box.
  c.anchorX = c.minX + (c.maxX - c.minX) / 2;
  c.anchorY = c.minY + (c.maxY - c.minY) / 2;
  // The 1/w plane, sum_i l_i / w_i, at the anchor and its gradient: the sums of the edge
  // numerators weighted by 1/w_i, each divided by the area once (4 divisions; the
  // barycentric planes of setupShade take 12).
  const Anchored a = anchoredOf(clip, raster, c.anchorX, c.anchorY);
  // The snapped triangle has area; the unsnapped one can only lose it to a double rounding of
  // a needle far below the snapping grid. No barycentrics exist for it: drop it.
  if (!(a.area != 0.0)) return false;
  double s0 = 0.0, sx = 0.0, sy = 0.0;
  for (int i = 0; i < 3; ++i) {
    const EdgeNumerators e = edgeNumerators(a, i);
    s0 += e.e0 * a.invW[i];
    sx += e.ex * a.invW[i];
    sy += e.ey * a.invW[i];
  }
  const double invW0 = s0 / a.area, zx = sx / a.area, zy = sy / a.area;
  c.key0 = Real(ctx.keyA + ctx.keyB * invW0);
  c.keyX = Real(ctx.keyB * zx);
  c.keyY = Real(ctx.keyB * zy);
  return true;
}

template <typename Real>
void setupShade(const glm::dvec4 clip[3], const glm::dvec2 raster[3], unsigned innerEdges, bool clipped,
                const SetupContext& ctx, const CoverageSetup<Real>& c, ShadeSetup<Real>& s) {
  // The anchored barycentric planes l_i = l0 + lx dx + ly dy. The area is not zero: the
  // same computation let setupCoverage accept the triangle.
  const Anchored a = anchoredOf(clip, raster, c.anchorX, c.anchorY);
  double l0[3], lx[3], ly[3];
  for (int i = 0; i < 3; ++i) {
    const EdgeNumerators e = edgeNumerators(a, i);
    l0[i] = e.e0 / a.area;
    lx[i] = e.ex / a.area;
    ly[i] = e.ey / a.area;
  }
  for (int i = 0; i < 3; ++i) {
    s.w[i] = Real(clip[i].w);
    s.invW[i] = Real(a.invW[i]);
    s.l0[i] = Real(l0[i]);
    s.lx[i] = Real(lx[i]);
    s.ly[i] = Real(ly[i]);
    // |grad l_i| by sqrt of the sum of squares (hypot costs more than the rest of the set-up),
    // unless a square overflowed or underflowed.
    const double squares = lx[i] * lx[i] + ly[i] * ly[i];
    const double length = std::isnormal(squares) ? std::sqrt(squares) : std::hypot(lx[i], ly[i]);
    s.edgeHeight[i] = (innerEdges >> i) & 1u ? Real(-1) : Real(1.0 / length);
  }

  // The error bound of docs/numerics.md ("The rasterizer's bound"). u: the per-pixel unit
  // roundoff. Each l_i = l0 + lx dx + ly dy rounds its three coefficients, two products and
  // two sums: error <= 4 u (|l0| + (|lx| + |ly|) R) + O(u^2), with R the largest offset from
  // the anchor. delta bounds how far the double transform may have moved a vertex, in pixels;
  // l_i moves by at most |grad l_i| delta per unit of barycentric weight on each of the three
  // vertices.
  const double R = std::max({c.anchorX - c.minX, c.maxX - c.anchorX, c.anchorY - c.minY, c.maxY - c.anchorY, 0}) + 0.0;
  const double u = ctx.unitRoundoff;
  double epsL = 0.0, gradient = 0.0, lMax = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double g = std::fabs(lx[i]) + std::fabs(ly[i]);
    epsL = std::max(epsL, 4.0 * u * (std::fabs(l0[i]) + g * R));
    gradient = std::max(gradient, g);
    lMax = std::max(lMax, std::fabs(l0[i]) + g * R);
  }
  const double wMin = std::min({clip[0].w, clip[1].w, clip[2].w});
  const double wMax = std::max({clip[0].w, clip[1].w, clip[2].w});
  const double rho = wMax / wMin;
  double delta = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double ndc = std::max(std::fabs(clip[i].x), std::fabs(clip[i].y)) / clip[i].w;
    delta = std::max(delta, 0.5 * std::max(ctx.width, ctx.height) * ctx.clipError * (1.0 + ndc) / clip[i].w);
  }
  delta += 0x1p-50 * (std::max({std::fabs(raster[0].x), std::fabs(raster[1].x), std::fabs(raster[2].x),
                                std::fabs(raster[0].y), std::fabs(raster[1].y), std::fabs(raster[2].y)}) + 1.0);
  epsL += 3.0 * delta * gradient * (1.0 + lMax);
  // Perspective division: |db_i| <= rho (1 + 3 b_i) max|dl| <= 4 rho epsL (l within [0, 1]
  // up to the snapping band), plus about 6 u from forming q, its sum and the quotient; a
  // clipped sub-triangle's 3x3 map (columns summing to 1, entries in [0, 1]) at most triples
  // that and adds 4 u; the float output adds half an ulp of values below 2 (a barycentric
  // leaves [0, 1] only by the snapping band), 2^-23 relative for depth.
  const double perspective = 4.0 * rho * epsL * std::max(1.0, lMax) + 6.0 * u;
  s.baryBound = float((clipped ? 3.0 * perspective + 4.0 * u : perspective) + 0x1p-23);
  s.depthBound = float(6.0 * rho * epsL * std::max(1.0, lMax) + 6.0 * u + 0x1p-23);
}

template <typename Real>
bool setupTriangle(const glm::dvec4 clip[3], const glm::dvec2 raster[3], unsigned innerEdges,
                   bool clipped, const SetupContext& ctx, CoverageSetup<Real>& c, ShadeSetup<Real>& s) {
  if (!setupCoverage(clip, raster, ctx, c)) return false;
  setupShade(clip, raster, innerEdges, clipped, ctx, c, s);
  return true;
}

template bool setupCoverage<float>(const glm::dvec4[3], const glm::dvec2[3], const SetupContext&, CoverageSetup<float>&);
template bool setupCoverage<double>(const glm::dvec4[3], const glm::dvec2[3], const SetupContext&, CoverageSetup<double>&);
template void setupShade<float>(const glm::dvec4[3], const glm::dvec2[3], unsigned, bool, const SetupContext&,
                                const CoverageSetup<float>&, ShadeSetup<float>&);
template void setupShade<double>(const glm::dvec4[3], const glm::dvec2[3], unsigned, bool, const SetupContext&,
                                 const CoverageSetup<double>&, ShadeSetup<double>&);
template bool setupTriangle<float>(const glm::dvec4[3], const glm::dvec2[3], unsigned, bool,
                                   const SetupContext&, CoverageSetup<float>&, ShadeSetup<float>&);
template bool setupTriangle<double>(const glm::dvec4[3], const glm::dvec2[3], unsigned, bool,
                                    const SetupContext&, CoverageSetup<double>&, ShadeSetup<double>&);

}  // namespace rc
