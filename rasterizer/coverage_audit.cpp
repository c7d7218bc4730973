// auditCoverage: the rules of coverage.h and the depth test, decided again pixel by pixel.
#include "rasterizer/coverage_audit.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <vector>

#include "core/channels.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/plane_allocator.h"
#include "rasterizer/clip.h"
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
  PlaneVector<std::uint8_t> flags;  // kOwned, kOnEdge; kDiagnosed and what some owning set-up met
  PlaneVector<double> writtenHigh;  // the written triangle's depth key there, plus its error bound
  PlaneVector<double> otherLow;     // the nearest other owner's key, less its error bound
  PlaneVector<std::uint32_t> otherOwner;
  static constexpr std::uint8_t kOwned = 1, kOnEdge = 2;
  // A covered pixel's diagnostics were held to the set-ups of its triangle that cover it, and
  // those one of them met. Snapping can turn a sub-triangle of a clipped polygon over, so that it
  // overlaps its neighbour: two set-ups of the written triangle then cover the pixel, and the
  // diagnostics are those of the one that won the depth test, which the audit, with keys equal
  // up to rounding (one plane), cannot name. They must meet one of them.
  static constexpr std::uint8_t kDiagnosed = 4, kBoundMet = 8, kEdgeDistanceMet = 16, kDepthTieMet = 32;
  static constexpr std::uint8_t kAllMet = kBoundMet | kEdgeDistanceMet | kDepthTieMet;

  explicit PixelState(std::size_t n)
      : flags(n, 0), writtenHigh(n, -std::numeric_limits<double>::infinity()),
        otherLow(n, -std::numeric_limits<double>::infinity()), otherOwner(n, channels::kNoTriangle) {}
};

// The frame's diagnostic planes, null when it has none.
struct Diagnostics {
  const float* edgeDistance = nullptr;
  const float* depthTie = nullptr;
  const float* depth = nullptr;
  const float* baryBound = nullptr;
  const float* depthBound = nullptr;
};

// A set-up's unsnapped edges, for the edge distances: the distance of p from edge i, signed
// (positive inside), is E_i(p) sign(area) / |edge i|, with E_i the edge function of the double
// raster positions, the planes' l_i = E_i / area times the edge height |area| / |edge i|.
struct UnsnappedEdges {
  glm::dvec2 v[3];
  double scale[3] = {};  // sign(area) / |edge i|; 0: a triangle of zero area (no set-up has one)
  unsigned inner = 0;
  double R = 0.0;         // the largest pixel offset from the anchor in the box
  double ownError = 0.0;  // of signedDistance, in double, for a centre in the image

  template <typename Real>
  explicit UnsnappedEdges(const VisitedSetup<Real>& s) : inner(s.innerEdges) {
    for (int i = 0; i < 3; ++i) v[i] = s.raster[i];
    const double area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
    double longest = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double length = glm::length(v[(i + 2) % 3] - v[(i + 1) % 3]);
      longest = std::max(longest, length);
      if (area != 0.0 && length > 0.0) scale[i] = (area > 0.0 ? 1.0 : -1.0) / length;
    }
    const CoverageSetup<Real>& c = s.coverage;
    const int ax = c.anchorX(), ay = c.anchorY();
    R = std::max({ax - c.minX, c.maxX - ax, ay - c.minY, c.maxY - ay, 0});
    // A cross product of differences, each a few roundings of magnitudes up to the centre's
    // distance from a vertex (at most the image's diagonal plus the vertex's own magnitude) and
    // the longest edge.
    const double reach = 2.0 * (s.context.width + s.context.height) + glm::length(v[0]) + 2.0 * longest;
    ownError = 64.0 * 0x1p-53 * reach;
  }
  double signedDistance(int i, double px, double py) const {
    const glm::dvec2 from = v[(i + 1) % 3], to = v[(i + 2) % 3];
    return ((to.x - from.x) * (py - from.y) - (to.y - from.y) * (px - from.x)) * scale[i];
  }
};

// The pixel's diagnostics against one set-up that owns it: each met, or its values written and
// audited. The rasterizer evaluates l_i |grad l_i|^-1 in Real from planes anchored at the box's
// centre: its error is under 4 u (|l0| h + 2 R) + 2 u d pixels (docs/numerics.md, "The
// rasterizer's bound", with |l0| h <= d + 2 R), counted here as 16 u (d + 2 R + 1), plus the
// float output's 2^-23 d and this double evaluation's own error. A diagonal inside a clipped
// polygon counts only for a centre beyond it (tile_resolve.h's diagnosticsOf), here as soon as
// the centre may be beyond it.
struct HeldDiagnostics {
  std::uint8_t met = 0;  // PixelState::kBoundMet, kEdgeDistanceMet, kDepthTieMet
  CoverageAudit::Diagnostic bound, edgeDistance, depthTie;
};

template <typename Real>
HeldDiagnostics holdDiagnostics(const VisitedSetup<Real>& s, const UnsnappedEdges& edges, const ShadeSetup<Real>& shade,
                                int px, int py, std::size_t p, double keyTerms, const Diagnostics& diag) {
  HeldDiagnostics held;
  const std::uint32_t triangle = s.coverage.source.triangle;
  // The error bounds: at most the set-up's own, which setupShade gives every pixel it wins.
  if (!(diag.baryBound[p] <= shade.baryBound && diag.depthBound[p] <= shade.depthBound)) {
    const bool bary = !(diag.baryBound[p] <= shade.baryBound);
    held.bound = {px, py, triangle, bary ? diag.baryBound[p] : diag.depthBound[p], bary ? shade.baryBound : shade.depthBound};
  } else {
    held.met |= PixelState::kBoundMet;
  }
  const double u = s.context.unitRoundoff, R = edges.R, ownError = edges.ownError;
  const double cx = px + 0.5, cy = py + 0.5;
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (edges.scale[i] == 0.0) return {PixelState::kAllMet, {}, {}, {}};  // no set-up has zero area
    const double d = edges.signedDistance(i, cx, cy);
    if (edges.inner & (1u << i)) {
      const double slack = 16.0 * u * (std::fabs(d) + 2.0 * R + 1.0) + ownError;
      if (d < slack) nearest = std::min(nearest, std::max(d, 0.0));
    } else {
      nearest = std::min(nearest, std::fabs(d));
    }
  }
  const double tolerance = 16.0 * u * (nearest + 2.0 * R + 1.0) + 0x1p-23 * nearest + ownError;
  const double written = diag.edgeDistance[p];
  if (!(written >= nearest - tolerance)) {
    held.edgeDistance = {px, py, triangle, written, nearest};
  } else {
    held.met |= PixelState::kEdgeDistanceMet;
  }
  // depth.tie: 5 u (|key0| + |keyX dx| + |keyY dy|) depth / keyB, times 1 + 2^-16 for its own
  // roundings (rasterizer.cpp's tieScale); here in double, from the depth written, which lies
  // within 2^-24 of the one the rasterizer multiplied by. Where that depth is negative (a
  // snapped set-up covering a centre its unsnapped plane puts behind the eye), so is the tie,
  // and the slack is taken from its magnitude.
  const double tie = 5.0 * u / s.context.keyB * (1.0 + 0x1p-16) * keyTerms * double(diag.depth[p]);
  const double wide = tie + std::fabs(tie) * (16.0 * u + 0x1p-22);
  const double tieWritten = diag.depthTie[p];
  if (!(tieWritten <= wide)) {
    held.depthTie = {px, py, triangle, tieWritten, tie};
  } else {
    held.met |= PixelState::kDepthTieMet;
  }
  return held;
}

// The first pass (firsts null) decides coverage and the depth test at every centre the set-up
// covers, and marks which diagnostics it meets; the second, run only when some pixel met none of
// its owners' (firsts non-null), records the first such of each kind, in set-up order.
template <typename Real, typename Triangle>
void auditSetup(const VisitedSetup<Real>& s, const Triangle& t, const std::uint32_t* written, int width,
                const Diagnostics& diag, PixelState& state, CoverageAudit* firsts) {
  if (t.orientation == 0) return;
  const CoverageSetup<Real>& c = s.coverage;
  // What the diagnostics are held to, made once for a set-up that owns a pixel.
  std::optional<UnsnappedEdges> edges;
  ShadeSetup<Real> shade{};
  // The depth key the tile kernels compute in Real, here in double, and the bound on their
  // error (setup.h: 5 u (|key0| + |keyX dx| + |keyY dy|)).
  const double u = s.context.unitRoundoff;
  const double key0 = c.key0, keyX = c.keyX, keyY = c.keyY;
  const int anchorX = c.anchorX(), anchorY = c.anchorY();
  for (int py = t.y0; py <= t.y1; ++py) {
    for (int px = t.x0; px <= t.x1; ++px) {
      bool inside = true, onEdge = false;
      for (int i = 0; i < 3 && inside; ++i) {
        const int side = t.side(i, px, py);
        inside = side > 0 || (side == 0 && t.topLeft[i]);
        onEdge = onEdge || side == 0;
      }
      if (!inside) continue;
      const double kx = keyX * (px - anchorX), ky = keyY * (py - anchorY);
      const double terms = std::fabs(key0) + std::fabs(kx) + std::fabs(ky);
      const double key = key0 + kx + ky, bound = 5.0 * u * terms;
      const std::size_t p = std::size_t(py) * std::size_t(width) + std::size_t(px);
      const bool owns = c.source.triangle == written[p];
      if (!firsts) {
        if (owns) {
          state.flags[p] |= PixelState::kOwned | (onEdge ? PixelState::kOnEdge : 0);
          state.writtenHigh[p] = std::max(state.writtenHigh[p], key + bound);
        } else if (key - bound > state.otherLow[p]) {
          state.otherLow[p] = key - bound;
          state.otherOwner[p] = c.source.triangle;
        }
      }
      const std::uint8_t unmet = PixelState::kAllMet & ~state.flags[p];
      if (!owns || !diag.edgeDistance || (firsts && unmet == 0)) continue;
      if (!edges) {
        edges.emplace(s);
        setupShade(s.clip, s.raster, s.innerEdges, c.source.clipped >= 0, s.context, c, shade);
      }
      const HeldDiagnostics held = holdDiagnostics(s, *edges, shade, px, py, p, terms, diag);
      if (!firsts) {
        state.flags[p] |= PixelState::kDiagnosed | held.met;
        continue;
      }
      // Each kind's first: a pixel no owner met it at; `written` is its own there.
      const auto first = [&](std::uint8_t kind, const CoverageAudit::Diagnostic& value, CoverageAudit::Diagnostic& into) {
        if ((unmet & kind) && into.x < 0) into = value;
      };
      first(PixelState::kBoundMet, held.bound, firsts->firstBoundWide);
      first(PixelState::kEdgeDistanceMet, held.edgeDistance, firsts->firstEdgeDistanceShort);
      first(PixelState::kDepthTieMet, held.depthTie, firsts->firstDepthTieWide);
    }
  }
}

template <typename Real>
void auditSetups(const Scene& scene, const RasterOptions& options, const std::uint32_t* written,
                 const Diagnostics& diag, PixelState& state, CoverageAudit& audit, CoverageAudit* firsts) {
  const int width = scene.camera.width(), height = scene.camera.height();
  forEachSetup<Real>(scene, options, [&](const VisitedSetup<Real>& s) {
    const CoverageSetup<Real>& c = s.coverage;
    if (options.subpixelBits != 0) {
      const SnappedTriangle t(c.x, c.y, options.subpixelBits, width, height);
      const int off = firsts ? 0 : cornersOffGrid(c.x, c.y, s.raster, options.subpixelBits);
      if (off) {
        if (audit.offGrid == 0) audit.firstOffGrid = c.source.triangle;
        audit.offGrid += std::size_t(off);
      }
      auditSetup(s, t, written, width, diag, state, firsts);
    } else {
      auditSetup(s, ExactTriangle(s.raster, width, height), written, width, diag, state, firsts);
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

namespace {

// Bounds, from the scene and the camera alone, on where the rasterizer's double transform may put
// a vertex it draws. Each clip coordinate it computes lies within clipError of the exact
// transform (clip.h), and so within twice that of the one computed here.
struct DrawnVertexBounds {
  glm::dmat4 clipFromWorld;
  double clipError, zNear, zFar, guard, side;

  // How far the rasterizer may have moved a vertex drawn at clip w >= wLow with |ndc| <= ndc,
  // in pixels (the rasterizer's rasterShift, docs/numerics.md): (side / 2) clipError (1 + ndc)
  // / w, plus the viewport mapping's 2^-50 |raster|, |raster| <= (|ndc| + 1) side / 2.
  double shift(double wLow, double ndc) const {
    return 0.5 * side * clipError * (1.0 + ndc) / wLow + 0x1p-50 * (0.5 * (ndc + 1.0) * side + 1.0);
  }
  // The worst case for anything drawn: w at the near plane, |ndc| at the guard band.
  double worstShift() const { return shift(zNear, guard); }

  glm::dvec4 clipOf(const glm::vec3& p) const { return clipFromWorld * glm::dvec4(glm::dvec3(p), 1.0); }
  double slack(const glm::dvec4& c) const {
    return 2.0 * clipError + 0x1p-40 * (std::fabs(c.x) + std::fabs(c.y) + std::fabs(c.w)) * (1.0 + guard);
  }
  // Surely inside the view volume for the rasterizer too (outcode 0), or surely outside plane i
  // (ClipVolume::distance, its outcode bit i set), whatever its rounding.
  bool surelyInside(const glm::dvec4& c) const {
    const double e = slack(c);
    return c.w - e >= zNear && (std::isinf(zFar) || c.w + e <= zFar) &&
           std::max(std::fabs(c.x), std::fabs(c.y)) + e <= guard * (c.w - e);
  }
  unsigned surelyOutside(const glm::dvec4& c) const {
    const double e = slack(c), low = c.w - e, high = c.w + e;
    return unsigned(high < zNear) | unsigned(!std::isinf(zFar) && low > zFar) << 1 |
           unsigned(c.x - e > guard * std::max(high, 0.0)) << 2 | unsigned(c.x + e < -guard * std::max(high, 0.0)) << 3 |
           unsigned(c.y - e > guard * std::max(high, 0.0)) << 4 | unsigned(c.y + e < -guard * std::max(high, 0.0)) << 5;
  }
  // A vertex the rasterizer finds inside: its w at least near, and at least the w here less the
  // slack; |ndc| at most the guard band's.
  double vertexShift(const glm::dvec4& c) const {
    const double e = slack(c), w = std::max(c.w - e, zNear);
    return shift(w, std::min(guard, (std::max(std::fabs(c.x), std::fabs(c.y)) + e) / w));
  }
  // Any point of a clipped triangle that is drawn: clip coordinates are linear over the
  // triangle, so its w is at least the vertices' least (and near); with every w positive, its
  // |ndc| is a weighted mean of theirs, at most their largest (and the guard band's). But the
  // clipper computes each new vertex in double, between two others (clip.h), and may put it past
  // the plane by a few u of their |w|: 128 u of the largest |w| covers the six planes. Where
  // that matters, on a triangle whose w spans 5e7 to -4e7 across a near plane of 0.1 (huge,
  // seen through 179 degrees), a vertex came out at w = 0.1 - 6e-9.
  double clippedShift(const glm::dvec4 (&c)[3]) const {
    double w = std::numeric_limits<double>::infinity(), ndc = 0.0, largestW = 0.0;
    bool ahead = true;
    for (const glm::dvec4& v : c) {
      const double e = slack(v), low = v.w - e;
      w = std::min(w, low);
      largestW = std::max(largestW, std::fabs(v.w) + e);
      ahead = ahead && low > 0.0;
      if (ahead) ndc = std::max(ndc, (std::max(std::fabs(v.x), std::fabs(v.y)) + e) / low);
    }
    // Not below half the near plane: a rasterizer whose clipped vertices stray that far draws
    // them wrongly, and the audit says so.
    const double interpolation = 128.0 * 0x1p-53 * largestW;
    const double low = std::max(std::max(w, zNear) - interpolation, 0.5 * zNear);
    return shift(low, (ahead ? std::min(ndc, guard) : guard) + interpolation / low);
  }
};

}  // namespace

double edgeBandCeiling(const Scene& scene, const RasterOptions& options) {
  const int bits = options.subpixelBits;
  const double side = std::max(scene.camera.width(), scene.camera.height());
  const double snapping = bits == 0 ? 0.0 : 0.7072 * std::ldexp(1.0, -bits);
  // The largest world coordinate is taken here from the scene, not from the frame's transform.
  double largest = 1.0;
  for (const glm::vec3& p : scene.mesh.positions) {
    largest = std::max({largest, std::fabs(double(p.x)), std::fabs(double(p.y)), std::fabs(double(p.z))});
  }
  const glm::dmat4 clipFromWorld = scene.camera.clipFromWorld();
  const DrawnVertexBounds bounds{clipFromWorld,     clipErrorBound(clipFromWorld, largest), scene.camera.zNear(),
                                 scene.camera.zFar(), 2.0 * guardBandPixels(bits) / side, side};
  // The rasterizer bounds every vertex inside the view volume at once, from the nearest w and
  // the guard band, when that adds at most a thousandth of snapping's steps (Pipeline::edgeBand);
  // otherwise it takes them one by one, as this does, and the vertices of every clipped
  // sub-triangle, which lie in their triangle.
  double shift = std::min(bounds.worstShift(), 0.5e-3 * snapping);
  const auto& positions = scene.mesh.positions;
  std::vector<bool> inside(positions.size());  // a bit a vertex: no page faults to speak of at 1M triangles
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const glm::dvec4 c = bounds.clipOf(positions[v]);
    inside[v] = bounds.surelyInside(c);
    if (!bounds.surelyOutside(c)) shift = std::max(shift, bounds.vertexShift(c));
  }
  for (const glm::uvec3& t : scene.mesh.triangles) {
    if (inside[t.x] && inside[t.y] && inside[t.z]) continue;
    const glm::dvec4 c[3] = {bounds.clipOf(positions[t.x]), bounds.clipOf(positions[t.y]), bounds.clipOf(positions[t.z])};
    if (bounds.surelyOutside(c[0]) & bounds.surelyOutside(c[1]) & bounds.surelyOutside(c[2])) continue;
    shift = std::max(shift, bounds.clippedShift(c));
  }
  // The slack: a clipped vertex's w may round below near, or below its triangle's least w.
  return (snapping + 2.0 * shift) * (1.0 + 0x1p-30);
}

CoverageAudit auditCoverage(const Scene& scene, const RasterOptions& options, const Framebuffer& frame) {
  const long long start = nowNanoseconds();
  const Channel* ids = frame.find(channels::kTriangleId);
  if (!ids || frame.width() != scene.camera.width() || frame.height() != scene.camera.height()) {
    throw internalError("auditCoverage: the frame is not a render of " + scene.name);
  }
  const std::uint32_t* written = ids->uints.data();
  const std::size_t n = std::size_t(frame.width()) * std::size_t(frame.height());
  PixelState state(n);
  CoverageAudit audit;
  Diagnostics diag;
  const Channel* edgeDistance = frame.find(channels::kEdgeDistance);
  const Channel* depthTie = frame.find(channels::kDepthTie);
  const Channel* depth = frame.find(channels::kDepth);
  const Channel* baryBound = frame.find(channels::kBaryBound);
  const Channel* depthBound = frame.find(channels::kDepthBound);
  if (edgeDistance && depthTie && depth && baryBound && depthBound) {
    diag = {edgeDistance->floats.data(), depthTie->floats.data(), depth->floats.data(), baryBound->floats.data(),
            depthBound->floats.data()};
  }
  const auto pass = [&](CoverageAudit* firsts) {
    if (options.precision == Precision::kFloat) {
      auditSetups<float>(scene, options, written, diag, state, audit, firsts);
    } else {
      auditSetups<double>(scene, options, written, diag, state, audit, firsts);
    }
  };
  pass(nullptr);
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint8_t f = state.flags[p];
    if (!(f & PixelState::kDiagnosed)) continue;
    ++audit.diagnosed;
    audit.boundWide += !(f & PixelState::kBoundMet);
    audit.edgeDistanceShort += !(f & PixelState::kEdgeDistanceMet);
    audit.depthTieWide += !(f & PixelState::kDepthTieMet);
  }
  if (audit.boundWide + audit.edgeDistanceShort + audit.depthTieWide > 0) pass(&audit);
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
  if (const auto band = frame.attributes.find(channels::header::kEdgeBand); band != frame.attributes.end()) {
    const char* text = band->second.c_str();
    char* end = nullptr;
    audit.edgeBand = std::strtod(text, &end);
    audit.edgeBandLimit = edgeBandCeiling(scene, options);
    // Unreadable or negative: no band to trust, which fails.
    if (end == text || *end != '\0' || !(audit.edgeBand >= 0.0)) audit.edgeBand = std::numeric_limits<double>::infinity();
  }
  const auto camera = frame.attributes.find(channels::header::kCamera);
  audit.cameraMismatch = camera == frame.attributes.end() || camera->second != scene.camera.describe();
  audit.ms = millisecondsSince(start);
  return audit;
}

}  // namespace rc
