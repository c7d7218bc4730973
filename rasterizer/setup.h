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

#include <cstdint>
#include <glm/glm.hpp>

#include "rasterizer/coverage.h"

namespace rc {

// Where a set-up came from: all setupShade needs besides the CoverageSetup. A whole triangle
// takes its vertices from the frame's per-vertex arrays; a clipped sub-triangle has its own
// ClippedTriangle record in its block.
struct SetupSource {
  std::uint32_t triangle;  // source triangle index (the tri.id written)
  std::int32_t clipped;    // index of its ClippedTriangle in the block; -1 = the whole triangle
};

// What the coverage and depth pass reads for every (set-up, tile) pair, kept apart from the
// resolve's data so that pass streams through half the memory, and what the tiles' setupShade
// starts from. It holds the snapped vertices, not the edge functions made from them (edges()
// makes those, a dozen integer operations per record and tile), and the anchor is a function
// of the box: so a float record, its source included, is 64 bytes, one cache line.
template <typename Real>
struct alignas(sizeof(Real) == 4 ? 64 : 8) CoverageSetup {
  int minX, minY, maxX, maxY;  // pixels whose centres may be covered, inclusive, in the viewport
  // The snapped vertices (coverage.h: subpixelBits fraction bits, |coordinates| < 2^29).
  std::int32_t x[3], y[3];
  std::uint32_t flags;         // kNotTopLeft << i: edge i is not top-left; kNarrow, kPositive (below)
  Real key0, keyX, keyY;       // depth-test key plane (larger is nearer)
  SetupSource source;          // set by the caller of setupCoverage

  // The pixel whose centre the planes are anchored at: the centre of the box, rounded down
  // (the box is never empty, so the halved width is a shift).
  int anchorX() const { return minX + int(unsigned(maxX - minX) >> 1); }
  int anchorY() const { return minY + int(unsigned(maxY - minY) >> 1); }

  static constexpr std::uint32_t kNotTopLeft = 1u;  // shifted by the edge number
  // Every edge value over the bounding box, and up to 8 pixels right of it, is below 2^31:
  // exact in int32 lanes.
  static constexpr std::uint32_t kNarrow = 8u;
  // The snapped area is positive (coverage.h's snappedArea): the edge functions keep the sign
  // of the vertex differences; otherwise they are negated.
  static constexpr std::uint32_t kPositive = 16u;

  // coverage.h's makeEdgeFunctions, with the fill rule's biases from the flags.
  EdgeFunctions edges() const {
    EdgeFunctions e{};
    const std::int64_t sign = flags & kPositive ? 1 : -1;
    for (int i = 0; i < 3; ++i) {
      setEdge(x, y, sign, i, e);
      e.bias[i] = (flags >> i) & kNotTopLeft ? -1 : 0;
    }
    return e;
  }
};
static_assert(sizeof(CoverageSetup<float>) == 64, "a float record is one cache line");

// A clipped sub-triangle, all in double: the same record serves either precision's frame.
struct ClippedTriangle {
  // Columns: source barycentrics of the sub-vertices, from the clipper. The resolve rounds them
  // to its Real where it applies them (a set-up promoted to double, tile_promote.h, does not).
  glm::dmat3 map;
  glm::dvec4 clip[3];
  glm::dvec2 raster[3];
  unsigned innerEdges;       // as for setupTriangle
};

// What resolve reads for the pixels a set-up wins.
template <typename Real>
struct ShadeSetup {
  std::uint32_t triangle;    // source triangle index (the tri.id written)
  std::int32_t clipMap;      // index of the ClippedTriangle whose map gives source barycentrics;
                             // -1 = identity
  Real l0[3], lx[3], ly[3];  // screen-space barycentric planes: l_i = l0 + lx dx + ly dy
  Real w[3], invW[3];        // clip w (= depth) of the vertices and its reciprocal
  Real edgeHeight[3];        // 1 / |grad l_i|: pixels from l_i = 0 to l_i = 1; negated for a
                             // diagonal inside a clipped polygon (tile_resolve.h's diagnosticsOf)
  float baryBound;           // bound on the barycentrics' error (docs/numerics.md)
  float depthBound;          // bound on depth.z's relative error
};

// A float set-up whose bound on its barycentrics' or its depth's error exceeds this learns next
// to nothing in float: the bounds are first order in the error of sum_i l_i / w_i, and there
// that error is no longer small against the sum, which may even cancel to 0 (an Inf
// barycentric). The tiles resolve such a set-up's pixels again in double (tile_promote.h).
inline constexpr float kPromoteAbove = 0.5f;

struct SetupContext {
  int width, height, subpixelBits;
  double unitRoundoff;  // of the per-pixel arithmetic: 2^-24 (float) or 2^-53 (double)
  double clipError;     // bound on the absolute error of the double world-to-clip transform
  double keyA, keyB;    // depth key = keyA + keyB / w
  bool cullBackFaces;   // setupCoverage rejects clockwise (back-facing) sub-triangles
};

// The two halves of the set-up. setupCoverage snaps and sets up what the coverage and depth
// pass needs, and returns false when the sub-triangle covers no pixel centre (zero snapped
// area, or no centre of the viewport inside its bounding box) or is culled as a back face.
// setupShade, given a set-up that setupCoverage accepted, computes what resolve needs; the
// tiles call it only for the set-ups that win a pixel (docs/rasterizer.md), and it gives the
// same bits wherever it runs.
template <typename Real>
bool setupCoverage(const glm::dvec4 clip[3], const glm::dvec2 raster[3], const SetupContext& ctx,
                   CoverageSetup<Real>& c);
template <typename Real>
void setupShade(const glm::dvec4 clip[3], const glm::dvec2 raster[3], unsigned innerEdges, bool clipped,
                const SetupContext& ctx, const CoverageSetup<Real>& c, ShadeSetup<Real>& s);

// Both halves at once: snaps and sets up one sub-triangle from its clip-space vertices and
// raster positions. `innerEdges` has bit i set when the edge opposite vertex i runs inside the source triangle
// (a diagonal of a clipped polygon's fan); `clipped` when the sub-triangle came from clipping.
// Returns false when it covers no pixel centre (zero snapped area, or no centre of the
// viewport inside its bounding box).
template <typename Real>
bool setupTriangle(const glm::dvec4 clip[3], const glm::dvec2 raster[3], unsigned innerEdges,
                   bool clipped, const SetupContext& ctx, CoverageSetup<Real>& c, ShadeSetup<Real>& s);

// The per-pixel formulas, for pixel offsets (dx, dy) from the anchor (small integers, exact in
// float), are in tile_resolve.h and tile_gather.h, evaluated eight pixels at a time:
//   screen barycentrics  l_i = l0_i + lx_i dx + ly_i dy
//   depth-test key       key0 + keyX dx + keyY dy (larger is nearer)
//   edge distance        min over the edges of |l_i| edgeHeight_i (a polygon's diagonals only
//                        for a centre across them)
//   depth tie            5 u (|key0| + |keyX dx| + |keyY dy|) w / keyB: the key's error bound
//                        (a rounding of each coefficient, product and sum) as the relative
//                        depth difference the test cannot resolve at depth w.

}  // namespace rc
