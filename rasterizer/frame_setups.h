// Every set-up of a frame, for the checks that decide coverage again apart from the tile kernels
// (coveredPixels in rasterizer.h, the coverage audit in coverage_audit.h).
#pragma once

#include <functional>

#include <glm/glm.hpp>

#include "rasterizer/rasterizer.h"
#include "rasterizer/setup.h"

namespace rc {

// One set-up of a frame as forEachSetup visits it.
template <typename Real>
struct VisitedSetup {
  const CoverageSetup<Real>& coverage;
  glm::dvec2 raster[3];    // unsnapped: the vertices', or a clipped sub-triangle's own
  glm::dvec4 clip[3];      // the same vertices' clip positions
  unsigned innerEdges;     // bit i: edge i (opposite vertex i) is a diagonal inside a clipped polygon
  const SetupContext& context;
};

// Visits the set-up of every (sub-)triangle a frame of `scene` would rasterize, in set-up order:
// the transform, clipping, culling and snapping of Rasterizer::render.
template <typename Real>
using SetupVisitor = std::function<void(const VisitedSetup<Real>&)>;

template <typename Real>
void forEachSetup(const Scene& scene, const RasterOptions& options, const SetupVisitor<Real>& visit);

extern template void forEachSetup<float>(const Scene&, const RasterOptions&, const SetupVisitor<float>&);
extern template void forEachSetup<double>(const Scene&, const RasterOptions&, const SetupVisitor<double>&);

}  // namespace rc
