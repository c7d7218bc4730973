// The coverage audit: does a frame obey the coverage rules the rasterizer documents, on its own
// snapped vertices? The reference cannot tell. A pixel centre exactly on an edge that two
// triangles share is on both as far as a ray is concerned, so the gate's comparison with Embree
// explains any owner there as an edge-band disagreement, and a rasterizer with a broken fill
// rule passes it (docs/numerics.md, "The coverage audit").
//
// The audit decides every pixel centre again, apart from the tile kernels: for each set-up of
// the frame (the same transform, clipping, culling and snapping), an exact edge test (int64 on
// the snapped vertices; without snapping, the exact orientation of the raster positions) and
// the top-left rule, written from their definitions. Then the depth test: among the triangles
// that own a centre, the written one must be the nearest, within the depth keys' error bounds.
// And the snapping: each snapped vertex must be the grid point nearest its raster position, so
// that the geometry it audits is the one the edge band (docs/numerics.md) allows for.
// Last, the two diagnostics the gate explains disagreements by (docs/channels.md): each pixel's
// edge.dist must not fall short of its centre's distance from the edges of the set-up that owns
// it, and its depth.tie must not exceed that set-up's depth-key error bound. Both are the
// rasterizer's own word, and a diagnostic too lenient would change no pixel and explain away
// whatever the comparison should fail. So would a wider error bound (bound.bary, bound.depth)
// than the set-up's own (setupShade, the formula of docs/numerics.md: the oracle test holds that
// formula to the exact errors both ways). So would a wider edge band in the frame's header (the
// distance from an edge within which a disagreement is explained): it must not exceed what
// snapping and the double transform allow, worked out again from the scene and the camera. And
// so would a camera line in the header other than the scene's: the comparison takes its near and
// far planes for clipping ties.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "core/framebuffer.h"
#include "rasterizer/rasterizer.h"

namespace rc {

struct CoverageAudit {
  std::size_t covered = 0;  // pixels the frame covers
  std::size_t onEdge = 0;   // of those, centres exactly on an edge of the set-up that owns them:
                            // the fill rule chose their owner
  std::size_t notOwned = 0;  // covered by a triangle that does not own the centre
  std::size_t lost = 0;      // left empty, or to a farther triangle, where a nearer one owns the centre
  // Corners of set-ups snapped to a grid point other than the one nearest their raster position
  // (cornersOffGrid), and the first one's triangle.
  std::size_t offGrid = 0;
  std::uint32_t firstOffGrid = 0;
  // The first violation of each kind in row order (x < 0: none): the triangle written
  // (channels::kNoTriangle when empty) and, for a lost pixel, the nearest triangle that owns
  // the centre.
  struct Pixel {
    int x = -1, y = -1;
    std::uint32_t written = 0, owner = 0;
  } firstNotOwned, firstLost;
  // Covered pixels whose diagnostics were checked (0 for a frame without them), those whose
  // edge.dist is shorter than the centre's distance from the owning set-up's edges, and those
  // whose depth.tie is wider than its depth key's bound; each beyond the rounding of the
  // rasterizer's own evaluation. Where two set-ups of the written triangle cover the centre
  // (snapped sub-triangles of a clipped polygon that overlap), meeting either's is enough. The
  // first found of each in set-up order, with the value written and the audit's.
  std::size_t diagnosed = 0, edgeDistanceShort = 0, depthTieWide = 0;
  // Covered pixels whose bound.bary or bound.depth is wider than the owning set-up's bound.
  std::size_t boundWide = 0;
  struct Diagnostic {
    int x = -1, y = -1;
    std::uint32_t triangle = 0;
    double written = 0.0, audited = 0.0;
  } firstEdgeDistanceShort, firstDepthTieWide, firstBoundWide;
  // The header's edge band (0: none written) and the widest it may be (edgeBandCeiling).
  double edgeBand = 0.0, edgeBandLimit = 0.0;
  bool edgeBandWide() const { return edgeBand > edgeBandLimit; }
  // The header's camera line (channels::header::kCamera) differs from the scene camera's.
  bool cameraMismatch = false;
  double ms = 0.0;  // the audit's wall-clock time

  std::size_t violations() const {
    return notOwned + lost + offGrid + edgeDistanceShort + depthTieWide + boundWide + (edgeBandWide() ? 1 : 0) +
           (cameraMismatch ? 1 : 0);
  }
};

// How many of a set-up's three corners, snapped to (x[i], y[i]) with `bits` fraction bits, are
// not the grid point nearest their raster position: farther than half a grid step from it in x
// or in y (round to nearest; a tie may go either way).
int cornersOffGrid(const std::int32_t x[3], const std::int32_t y[3], const glm::dvec2 (&raster)[3], int bits);

// The widest edge band a frame of `scene` rendered with `options` may claim (docs/numerics.md,
// "Disagreements"): snapping's sqrt(2)/2 grid steps, plus twice the farthest the double transform
// may move any vertex drawn, from the scene's own transform of its vertices and the camera alone:
// vertex by vertex inside the view volume, and for a triangle the view volume clips, at the
// least w of its vertices (or near) and the largest |ndc| (or the guard band's).
double edgeBandCeiling(const Scene& scene, const RasterOptions& options);

// Audits `frame`, a frame Rasterizer::render made of `scene` with `options` (its tri.id channel).
CoverageAudit auditCoverage(const Scene& scene, const RasterOptions& options, const Framebuffer& frame);

}  // namespace rc
