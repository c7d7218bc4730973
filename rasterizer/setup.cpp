// Triangle set-up in double: snapping, bounding box, anchored barycentric and depth planes.
#include "rasterizer/setup.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rc {
namespace {

// floor(a / b) and ceil(a / b) for b > 0.
std::int64_t floorDiv(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
std::int64_t ceilDiv(std::int64_t a, std::int64_t b) { return -floorDiv(-a, b); }

}  // namespace

template <typename Real>
bool setupTriangle(const glm::dvec4 clip[3], const glm::dvec2 raster[3], unsigned innerEdges,
                   bool clipped, const SetupContext& ctx, TriangleSetup<Real>& s) {
  const int bits = ctx.subpixelBits;
  const double scale = std::ldexp(1.0, bits);
  std::int64_t xf[3], yf[3];
  for (int i = 0; i < 3; ++i) {
    // Round to nearest, ties to even (the default mode): a pure function of the double input.
    xf[i] = static_cast<std::int64_t>(std::nearbyint(raster[i].x * scale));
    yf[i] = static_cast<std::int64_t>(std::nearbyint(raster[i].y * scale));
    s.xFixed[i] = static_cast<std::int32_t>(xf[i]);
    s.yFixed[i] = static_cast<std::int32_t>(yf[i]);
  }
  EdgeFunctions edges{};
  if (!makeEdgeFunctions(xf, yf, edges)) return false;  // zero snapped area: no pixels

  // Pixels whose centre (2x+1) * 2^(bits-1) lies within the snapped bounding box.
  const std::int64_t half = std::int64_t(1) << (bits - 1), one = std::int64_t(1) << bits;
  const auto [minXf, maxXf] = std::minmax({xf[0], xf[1], xf[2]});
  const auto [minYf, maxYf] = std::minmax({yf[0], yf[1], yf[2]});
  s.minX = int(std::max<std::int64_t>(0, ceilDiv(minXf - half, one)));
  s.minY = int(std::max<std::int64_t>(0, ceilDiv(minYf - half, one)));
  s.maxX = int(std::min<std::int64_t>(ctx.width - 1, floorDiv(maxXf - half, one)));
  s.maxY = int(std::min<std::int64_t>(ctx.height - 1, floorDiv(maxYf - half, one)));
  if (s.minX > s.maxX || s.minY > s.maxY) return false;

  // Anchor: the pixel at the centre of the clipped bounding box; every offset is at most R.
  s.anchorX = s.minX + (s.maxX - s.minX) / 2;
  s.anchorY = s.minY + (s.maxY - s.minY) / 2;
  const double R = std::max({s.anchorX - s.minX, s.maxX - s.anchorX, s.anchorY - s.minY, s.maxY - s.anchorY, 0}) + 0.0;
  const double ax = s.anchorX + 0.5, ay = s.anchorY + 0.5;  // the anchor's centre, exact
  double x[3], y[3], invW[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = raster[i].x - ax;
    y[i] = raster[i].y - ay;
    invW[i] = 1.0 / clip[i].w;
    s.w[i] = Real(clip[i].w);
    s.invW[i] = Real(invW[i]);
  }
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  // The snapped triangle has area; the unsnapped one can only lose it to a double rounding of
  // a needle far below the snapping grid. No barycentrics exist for it: drop it.
  if (!(area != 0.0)) return false;
  // l_i(p) = E_i(p) / area with E_i the edge function of the edge opposite vertex i:
  // at the anchor (p = 0) and its gradient d(l_i)/dx = -(y_to - y_from) / area, etc.
  double l0[3], lx[3], ly[3], zx = 0.0, zy = 0.0;
  for (int i = 0; i < 3; ++i) {
    const int from = (i + 1) % 3, to = (i + 2) % 3;
    l0[i] = ((x[to] - x[from]) * (0.0 - y[from]) - (y[to] - y[from]) * (0.0 - x[from])) / area;
    lx[i] = -(y[to] - y[from]) / area;
    ly[i] = (x[to] - x[from]) / area;
    s.l0[i] = Real(l0[i]);
    s.lx[i] = Real(lx[i]);
    s.ly[i] = Real(ly[i]);
    zx += lx[i] * invW[i];
    zy += ly[i] * invW[i];
    s.edgeHeight[i] = (innerEdges >> i) & 1u ? Real(-1) : Real(1.0 / std::hypot(lx[i], ly[i]));
  }
  double invW0 = 0.0;  // 1/w at the anchor
  for (int i = 0; i < 3; ++i) invW0 += l0[i] * invW[i];
  s.key0 = Real(ctx.keyA + ctx.keyB * invW0);
  s.keyX = Real(ctx.keyB * zx);
  s.keyY = Real(ctx.keyB * zy);

  // The error bound of docs/numerics.md ("The rasterizer's bound"). u: the per-pixel unit
  // roundoff. Each l_i = l0 + lx dx + ly dy rounds its three coefficients, two products and
  // two sums: error <= 4 u (|l0| + (|lx| + |ly|) R) + O(u^2). delta bounds how far the double
  // transform may have moved a vertex, in pixels; l_i moves by at most |grad l_i| delta per
  // unit of barycentric weight on each of the three vertices.
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
  return true;
}

template bool setupTriangle<float>(const glm::dvec4[3], const glm::dvec2[3], unsigned, bool,
                                   const SetupContext&, TriangleSetup<float>&);
template bool setupTriangle<double>(const glm::dvec4[3], const glm::dvec2[3], unsigned, bool,
                                    const SetupContext&, TriangleSetup<double>&);

}  // namespace rc
