// Triangle set-up in double: snapping, bounding box, anchored barycentric and depth planes.
#include "rasterizer/setup.h"

#include <algorithm>
#include <cmath>

namespace rc {
namespace {

// floor(a / b) and ceil(a / b) for b > 0.
std::int64_t floorDiv(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
std::int64_t ceilDiv(std::int64_t a, std::int64_t b) { return -floorDiv(-a, b); }

}  // namespace

template <typename Real>
bool setupTriangle(const glm::dvec4 clip[3], const glm::dvec2 raster[3], const SetupContext& ctx,
                   TriangleSetup<Real>& s) {
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

  s.anchorX = int(std::floor(raster[0].x));
  s.anchorY = int(std::floor(raster[0].y));
  double x[3], y[3], invW[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = raster[i].x - s.anchorX;  // exact: Sterbenz-style, same binade or integer shift
    y[i] = raster[i].y - s.anchorY;
    invW[i] = 1.0 / clip[i].w;
    s.x[i] = Real(x[i]);
    s.y[i] = Real(y[i]);
    s.w[i] = Real(clip[i].w);
    s.invW[i] = Real(invW[i]);
  }
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  // The snapped triangle has area; the unsnapped one can only lose it to a double rounding of
  // a needle far below the snapping grid. No barycentrics exist for it: drop it.
  if (!(area != 0.0)) return false;
  s.invArea = Real(1.0 / area);
  // d(l_i)/dx = -(y_to - y_from) / area, d(l_i)/dy = (x_to - x_from) / area.
  double zx = 0.0, zy = 0.0;
  for (int i = 0; i < 3; ++i) {
    const int from = (i + 1) % 3, to = (i + 2) % 3;
    zx += -(y[to] - y[from]) / area * invW[i];
    zy += (x[to] - x[from]) / area * invW[i];
  }
  s.zx = Real(zx);
  s.zy = Real(zy);
  return true;
}

template bool setupTriangle<float>(const glm::dvec4[3], const glm::dvec2[3], const SetupContext&,
                                   TriangleSetup<float>&);
template bool setupTriangle<double>(const glm::dvec4[3], const glm::dvec2[3], const SetupContext&,
                                    TriangleSetup<double>&);

}  // namespace rc
