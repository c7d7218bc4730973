// Triangle set-up in double: snapping, bounding box, anchored barycentric and depth planes.
#include "rasterizer/setup.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rasterizer/orientation.h"
#include "rasterizer/setup_formulas.h"

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

// setup_formulas.h's anchoredOf for one triangle, anchored at pixel (anchorX, anchorY).
formulas::Anchored<double> anchoredOf(const glm::dvec4 clip[3], const glm::dvec2 raster[3], int anchorX, int anchorY) {
  const double rx[3] = {raster[0].x, raster[1].x, raster[2].x}, ry[3] = {raster[0].y, raster[1].y, raster[2].y};
  const double w[3] = {clip[0].w, clip[1].w, clip[2].w};
  return formulas::anchoredOf(rx, ry, w, anchorX + 0.5, anchorY + 0.5);  // the anchor's centre, exact
}

// The depth-key plane of a set-up whose box is made, at its anchor. False when the unsnapped
// area in double is within its own rounding (Anchored::noise) of 0: the snapped triangle (or,
// without snapping, the exact one) has area, and the double one can only lose it to a needle
// far below a pixel. No barycentrics exist for it in any precision: it is dropped. (Until
// session 50 only an area of exactly 0 was: a needle one ulp from collinear, seen from 45 away
// at 2 subpixel bits, kept an area of its rounding, planes of 1e15, and wrote Inf barycentrics
// and a NaN depth in float.)
template <typename Real>
bool setupPlanes(const glm::dvec4 clip[3], const glm::dvec2 raster[3], const SetupContext& ctx, CoverageSetup<Real>& c) {
  const formulas::Anchored<double> a = anchoredOf(clip, raster, c.anchorX(), c.anchorY());
  if (!(std::fabs(a.area) > a.noise)) return false;
  const formulas::KeyPlane<double> key = formulas::keyPlaneOf(a, ctx);
  c.key0 = Real(key.key0);
  c.keyX = Real(key.keyX);
  c.keyY = Real(key.keyY);
  return true;
}

// setupCoverage without snapping (subpixelBits 0): the orientation is exact (orientation.h),
// the box holds every pixel whose centre may lie in the unsnapped triangle (rounding of
// min - 0.5 and max - 0.5 only widens it), and the edges' fill-rule flags follow the exact
// signs of the vertex differences. The snapped vertices stay 0; the tiles read the raster
// positions instead (tile_coverage.h's coverRowsUnsnapped).
template <typename Real>
bool setupUnsnapped(const glm::dvec2 raster[3], const SetupContext& ctx, CoverageSetup<Real>& c) {
  const int area = orientation(raster[0].x, raster[0].y, raster[1].x, raster[1].y, raster[2].x, raster[2].y);
  if (area == 0 || (ctx.cullBackFaces && area > 0)) return false;
  const auto [minX, maxX] = std::minmax({raster[0].x, raster[1].x, raster[2].x});
  const auto [minY, maxY] = std::minmax({raster[0].y, raster[1].y, raster[2].y});
  // The guard band keeps |raster| below 2^21 pixels (pipeline.cpp), well inside int.
  c.minX = int(std::max(0.0, std::ceil(minX - 0.5)));
  c.minY = int(std::max(0.0, std::ceil(minY - 0.5)));
  c.maxX = int(std::min(double(ctx.width - 1), std::floor(maxX - 0.5)));
  c.maxY = int(std::min(double(ctx.height - 1), std::floor(maxY - 0.5)));
  if (c.minX > c.maxX || c.minY > c.maxY) return false;
  c.flags = area > 0 ? CoverageSetup<Real>::kPositive : 0u;
  for (int i = 0; i < 3; ++i) {
    c.x[i] = 0, c.y[i] = 0;
    // coverage.h's rule on the signs of a = sign (y_from - y_to) and b = sign (x_to - x_from).
    const glm::dvec2 from = raster[(i + 1) % 3], to = raster[(i + 2) % 3];
    const int a = area * ((from.y > to.y) - (from.y < to.y)), b = area * ((to.x > from.x) - (to.x < from.x));
    if (!(a > 0 || (a == 0 && b > 0))) c.flags |= CoverageSetup<Real>::kNotTopLeft << i;
  }
  return true;
}

}  // namespace

template <typename Real>
bool setupCoverage(const glm::dvec4 clip[3], const glm::dvec2 raster[3], const SetupContext& ctx,
                   CoverageSetup<Real>& c) {
  const int bits = ctx.subpixelBits;
  if (bits == 0) {
    if (!setupUnsnapped(raster, ctx, c)) return false;
    return setupPlanes(clip, raster, ctx, c);
  }
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
  c.flags = area > 0 ? CoverageSetup<Real>::kPositive : 0u;
  for (int i = 0; i < 3; ++i) {  // each below 2^29 in magnitude (coverage.h)
    c.x[i] = std::int32_t(xf[i]), c.y[i] = std::int32_t(yf[i]);
    if (edges.bias[i] != 0) c.flags |= CoverageSetup<Real>::kNotTopLeft << i;
  }
  // |E_i| <= |a_i| |X - ox_i| + |b_i| |Y - oy_i| + 1 with |a_i| <= the box's height, |b_i| <=
  // its width, and X (Y) within the box widened by 9 (1) pixels: 8 lanes past its right side.
  const std::int64_t spanX = maxXf - minXf, spanY = maxYf - minYf;
  if (spanX < (std::int64_t(1) << 30) && spanY < (std::int64_t(1) << 30) &&
      spanY * (spanX + 9 * one) + spanX * (spanY + one) + 1 < (std::int64_t(1) << 31)) {
    c.flags |= CoverageSetup<Real>::kNarrow;
  }

  return setupPlanes(clip, raster, ctx, c);
}

template <typename Real>
void setupShade(const glm::dvec4 clip[3], const glm::dvec2 raster[3], unsigned innerEdges, bool clipped,
                const SetupContext& ctx, const CoverageSetup<Real>& c, ShadeSetup<Real>& s) {
  // The anchored barycentric planes. The area is not zero: the same computation let
  // setupCoverage accept the triangle.
  const formulas::Anchored<double> a = anchoredOf(clip, raster, c.anchorX(), c.anchorY());
  const formulas::Planes<double> p = formulas::planesOf(a);
  for (int i = 0; i < 3; ++i) {
    s.w[i] = Real(clip[i].w);
    s.invW[i] = Real(a.invW[i]);
    s.l0[i] = Real(p.l0[i]);
    s.lx[i] = Real(p.lx[i]);
    s.ly[i] = Real(p.ly[i]);
    s.edgeHeight[i] = (innerEdges >> i) & 1u ? -Real(p.height[i]) : Real(p.height[i]);  // tile_resolve.h
  }
  const double R = std::max({c.anchorX() - c.minX, c.maxX - c.anchorX(), c.anchorY() - c.minY, c.maxY - c.anchorY(), 0}) + 0.0;
  const double rx[3] = {raster[0].x, raster[1].x, raster[2].x}, ry[3] = {raster[0].y, raster[1].y, raster[2].y};
  const double cx[3] = {clip[0].x, clip[1].x, clip[2].x}, cy[3] = {clip[0].y, clip[1].y, clip[2].y};
  const double w[3] = {clip[0].w, clip[1].w, clip[2].w};
  const formulas::Bounds<double> bounds = formulas::boundsOf(p, R, rx, ry, cx, cy, w, ctx, clipped);
  s.baryBound = float(bounds.bary);
  s.depthBound = float(bounds.depth);
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
