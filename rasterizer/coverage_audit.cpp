// auditCoverage: the rules of coverage.h and the depth test, decided again pixel by pixel.
#include "rasterizer/coverage_audit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/channels.h"
#include "core/error.h"
#include "core/plane_allocator.h"
#include "rasterizer/frame_setups.h"
#include "rasterizer/orientation.h"

namespace rc {
namespace {

int sign(std::int64_t v) { return (v > 0) - (v < 0); }

// One set-up's triangle as the audit sees it: per edge i (from vertex i + 1 to vertex i + 2),
// which side of it a pixel centre lies on, and whether the edge is top or left.
struct AuditTriangle {
  int orientation = 0;  // the sign of the area: +1 clockwise on a y-down screen, 0: covers nothing
  bool topLeft[3] = {};
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // the pixels whose centres may be inside, in the image

  // The fill rule from its definition: an edge's inward normal (the gradient of its edge
  // function, (ny, nx) below) points right on a left edge, and straight down (y down) on a top
  // edge; a centre exactly on the edge is inside only for those.
  void setTopLeft(int i, int nx, int ny) { topLeft[i] = nx > 0 || (nx == 0 && ny > 0); }
  void setBox(double minX, double minY, double maxX, double maxY, int width, int height) {
    x0 = int(std::max(0.0, std::floor(minX) - 1.0)), x1 = int(std::min(double(width - 1), std::floor(maxX) + 1.0));
    y0 = int(std::max(0.0, std::floor(minY) - 1.0)), y1 = int(std::min(double(height - 1), std::floor(maxY) + 1.0));
  }
};

// Snapped vertices: every edge value exact in int64 (coverage.h's range).
struct SnappedTriangle : AuditTriangle {
  std::int64_t x[3], y[3];
  int bits;

  SnappedTriangle(const std::int32_t* sx, const std::int32_t* sy, int subpixelBits, int width, int height) : bits(subpixelBits) {
    for (int i = 0; i < 3; ++i) x[i] = sx[i], y[i] = sy[i];
    orientation = sign((x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]));
    for (int i = 0; i < 3; ++i) {
      const int from = (i + 1) % 3, to = (i + 2) % 3;
      setTopLeft(i, orientation * sign(y[from] - y[to]), orientation * sign(x[to] - x[from]));
    }
    const double unit = std::ldexp(1.0, -bits);
    setBox(double(*std::min_element(x, x + 3)) * unit, double(*std::min_element(y, y + 3)) * unit,
           double(*std::max_element(x, x + 3)) * unit, double(*std::max_element(y, y + 3)) * unit, width, height);
  }
  // The side of edge i the centre of pixel (px, py) lies on: +1 inside, 0 on it.
  int side(int i, int px, int py) const {
    const int from = (i + 1) % 3, to = (i + 2) % 3;
    const std::int64_t cx = (2 * std::int64_t(px) + 1) << (bits - 1), cy = (2 * std::int64_t(py) + 1) << (bits - 1);
    return orientation * sign((x[to] - x[from]) * (cy - y[from]) - (y[to] - y[from]) * (cx - x[from]));
  }
};

// Unsnapped raster positions: signs decided exactly (orientation.h).
struct ExactTriangle : AuditTriangle {
  glm::dvec2 v[3];

  ExactTriangle(const glm::dvec2 (&raster)[3], int width, int height) {
    for (int i = 0; i < 3; ++i) v[i] = raster[i];
    orientation = rc::orientation(v[1].x, v[1].y, v[2].x, v[2].y, v[0].x, v[0].y);
    for (int i = 0; i < 3; ++i) {
      const glm::dvec2 from = v[(i + 1) % 3], to = v[(i + 2) % 3];
      // The sign of a difference of two doubles is exact.
      setTopLeft(i, orientation * ((from.y > to.y) - (from.y < to.y)), orientation * ((to.x > from.x) - (to.x < from.x)));
    }
    setBox(std::min({v[0].x, v[1].x, v[2].x}), std::min({v[0].y, v[1].y, v[2].y}), std::max({v[0].x, v[1].x, v[2].x}),
           std::max({v[0].y, v[1].y, v[2].y}), width, height);
  }
  int side(int i, int px, int py) const {
    const glm::dvec2 from = v[(i + 1) % 3], to = v[(i + 2) % 3];
    return orientation * rc::orientation(from.x, from.y, to.x, to.y, px + 0.5, py + 0.5);
  }
};

// What the audit keeps per pixel.
// (In huge pages, as the frame's planes: in 4 KB pages, faulting the 44 MB of a 1920x1080 frame in
// took longer than the audit's work.)
struct PixelState {
  PlaneVector<std::uint8_t> flags;  // kOwned, kOnEdge
  PlaneVector<double> writtenHigh;  // the written triangle's depth key there, plus its error bound
  PlaneVector<double> otherLow;     // the nearest other owner's key, less its error bound
  PlaneVector<std::uint32_t> otherOwner;
  static constexpr std::uint8_t kOwned = 1, kOnEdge = 2;

  explicit PixelState(std::size_t n)
      : flags(n, 0), writtenHigh(n, -std::numeric_limits<double>::infinity()),
        otherLow(n, -std::numeric_limits<double>::infinity()), otherOwner(n, channels::kNoTriangle) {}
};

template <typename Real, typename Triangle>
void auditSetup(const CoverageSetup<Real>& c, const Triangle& t, const std::uint32_t* written, int width, PixelState& state) {
  if (t.orientation == 0) return;
  // The depth key the tile kernels compute in Real, here in double, and the bound on their
  // error (setup.h: 5 u (|key0| + |keyX dx| + |keyY dy|)).
  constexpr double u = std::is_same_v<Real, float> ? 0x1p-24 : 0x1p-53;
  const double key0 = c.key0, keyX = c.keyX, keyY = c.keyY;
  const int anchorX = c.anchorX(), anchorY = c.anchorY();
  for (int py = t.y0; py <= t.y1; ++py) {
    for (int px = t.x0; px <= t.x1; ++px) {
      bool inside = true, onEdge = false;
      for (int i = 0; i < 3 && inside; ++i) {
        const int s = t.side(i, px, py);
        inside = s > 0 || (s == 0 && t.topLeft[i]);
        onEdge = onEdge || s == 0;
      }
      if (!inside) continue;
      const double kx = keyX * (px - anchorX), ky = keyY * (py - anchorY);
      const double key = key0 + kx + ky, bound = 5.0 * u * (std::fabs(key0) + std::fabs(kx) + std::fabs(ky));
      const std::size_t p = std::size_t(py) * std::size_t(width) + std::size_t(px);
      if (c.source.triangle == written[p]) {
        state.flags[p] |= PixelState::kOwned | (onEdge ? PixelState::kOnEdge : 0);
        state.writtenHigh[p] = std::max(state.writtenHigh[p], key + bound);
      } else if (key - bound > state.otherLow[p]) {
        state.otherLow[p] = key - bound;
        state.otherOwner[p] = c.source.triangle;
      }
    }
  }
}

template <typename Real>
void auditSetups(const Scene& scene, const RasterOptions& options, const std::uint32_t* written, PixelState& state,
                 CoverageAudit& audit) {
  const int width = scene.camera.width(), height = scene.camera.height();
  forEachSetup<Real>(scene, options, [&](const CoverageSetup<Real>& c, const glm::dvec2 (&raster)[3]) {
    if (options.subpixelBits != 0) {
      const SnappedTriangle t(c.x, c.y, options.subpixelBits, width, height);
      if (const int off = cornersOffGrid(c.x, c.y, raster, options.subpixelBits)) {
        if (audit.offGrid == 0) audit.firstOffGrid = c.source.triangle;
        audit.offGrid += std::size_t(off);
      }
      auditSetup(c, t, written, width, state);
    } else {
      auditSetup(c, ExactTriangle(raster, width, height), written, width, state);
    }
  });
}

}  // namespace

int cornersOffGrid(const std::int32_t x[3], const std::int32_t y[3], const glm::dvec2 (&raster)[3], int bits) {
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    // r 2^bits is exact in double, and so is its difference from an integer below 2^29.
    const double dx = double(x[i]) - std::ldexp(raster[i].x, bits), dy = double(y[i]) - std::ldexp(raster[i].y, bits);
    count += !(std::fabs(dx) <= 0.5 && std::fabs(dy) <= 0.5);
  }
  return count;
}

CoverageAudit auditCoverage(const Scene& scene, const RasterOptions& options, const Framebuffer& frame) {
  const auto start = std::chrono::steady_clock::now();
  const Channel* ids = frame.find(channels::kTriangleId);
  if (!ids || frame.width() != scene.camera.width() || frame.height() != scene.camera.height()) {
    throw internalError("auditCoverage: the frame is not a render of " + scene.name);
  }
  const std::uint32_t* written = ids->uints.data();
  const std::size_t n = std::size_t(frame.width()) * std::size_t(frame.height());
  PixelState state(n);
  CoverageAudit audit;
  if (options.precision == Precision::kFloat) {
    auditSetups<float>(scene, options, written, state, audit);
  } else {
    auditSetups<double>(scene, options, written, state, audit);
  }
  for (std::size_t p = 0; p < n; ++p) {
    const bool covered = written[p] != channels::kNoTriangle;
    const bool owned = state.flags[p] & PixelState::kOwned;
    const bool hasOther = state.otherOwner[p] != channels::kNoTriangle;
    const auto note = [&](std::size_t& count, CoverageAudit::Pixel& first) {
      if (count++ == 0) first = {int(p % std::size_t(frame.width())), int(p / std::size_t(frame.width())), written[p], state.otherOwner[p]};
    };
    if (covered) {
      ++audit.covered;
      audit.onEdge += owned && (state.flags[p] & PixelState::kOnEdge);
      if (!owned) {
        note(audit.notOwned, audit.firstNotOwned);
      } else if (hasOther && state.otherLow[p] > state.writtenHigh[p]) {
        note(audit.lost, audit.firstLost);
      }
    } else if (hasOther) {
      note(audit.lost, audit.firstLost);
    }
  }
  audit.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return audit;
}

}  // namespace rc
