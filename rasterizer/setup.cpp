// Triangle set-up: snapping, bounding box, unsnapped barycentric and depth planes.
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
bool setupTriangle(const glm::vec<4, Real> clip[3], const glm::vec<2, Real> raster[3],
                   const SetupContext<Real>& ctx, TriangleSetup<Real>& s) {
  const int bits = ctx.subpixelBits;
  const Real scale = Real(std::int64_t(1) << bits);
  for (int i = 0; i < 3; ++i) {
    // Round to nearest, ties to even (the default mode): a pure function of the float input.
    s.xFixed[i] = static_cast<std::int64_t>(std::nearbyint(raster[i].x * scale));
    s.yFixed[i] = static_cast<std::int64_t>(std::nearbyint(raster[i].y * scale));
    s.x[i] = raster[i].x;
    s.y[i] = raster[i].y;
    s.w[i] = clip[i].w;
    s.invW[i] = Real(1) / clip[i].w;
  }
  EdgeFunctions edges{};
  if (!makeEdgeFunctions(s.xFixed, s.yFixed, edges)) return false;  // zero area: no pixels

  // Pixels whose centre (2x+1) * 2^(bits-1) lies within the snapped bounding box.
  const std::int64_t half = std::int64_t(1) << (bits - 1), one = std::int64_t(1) << bits;
  const auto [minXf, maxXf] = std::minmax({s.xFixed[0], s.xFixed[1], s.xFixed[2]});
  const auto [minYf, maxYf] = std::minmax({s.yFixed[0], s.yFixed[1], s.yFixed[2]});
  s.minX = int(std::max<std::int64_t>(0, ceilDiv(minXf - half, one)));
  s.minY = int(std::max<std::int64_t>(0, ceilDiv(minYf - half, one)));
  s.maxX = int(std::min<std::int64_t>(ctx.width - 1, floorDiv(maxXf - half, one)));
  s.maxY = int(std::min<std::int64_t>(ctx.height - 1, floorDiv(maxYf - half, one)));
  if (s.minX > s.maxX || s.minY > s.maxY) return false;

  Real area = (s.x[1] - s.x[0]) * (s.y[2] - s.y[0]) - (s.y[1] - s.y[0]) * (s.x[2] - s.x[0]);
  if (!(area != Real(0))) {
    // The unsnapped triangle rounds to zero area although the snapped one does not: take the
    // snapped positions (exactly representable) so barycentrics stay finite.
    for (int i = 0; i < 3; ++i) {
      s.x[i] = Real(s.xFixed[i]) / scale;
      s.y[i] = Real(s.yFixed[i]) / scale;
    }
    area = (s.x[1] - s.x[0]) * (s.y[2] - s.y[0]) - (s.y[1] - s.y[0]) * (s.x[2] - s.x[0]);
    // Still zero only when snapped positions beyond 2^24 grid steps do not fit Real (float
    // far out in the guard band): such a needle cannot be interpolated, so it is dropped.
    if (!(area != Real(0))) return false;
  }
  s.invArea = Real(1) / area;
  // d(l_i)/dx = -(y_to - y_from) / area, d(l_i)/dy = (x_to - x_from) / area.
  s.zx = s.zy = Real(0);
  for (int i = 0; i < 3; ++i) {
    const int from = (i + 1) % 3, to = (i + 2) % 3;
    s.zx += -(s.y[to] - s.y[from]) * s.invArea * s.invW[i];
    s.zy += (s.x[to] - s.x[from]) * s.invArea * s.invW[i];
  }
  return true;
}

template bool setupTriangle<float>(const glm::vec<4, float>[3], const glm::vec<2, float>[3],
                                   const SetupContext<float>&, TriangleSetup<float>&);
template bool setupTriangle<double>(const glm::vec<4, double>[3], const glm::vec<2, double>[3],
                                    const SetupContext<double>&, TriangleSetup<double>&);

}  // namespace rc
