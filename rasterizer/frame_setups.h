// Every set-up of a frame, for the checks that decide coverage again apart from the tile kernels
// (coveredPixels in rasterizer.h, the coverage audit in coverage_audit.h).
#pragma once

#include <functional>

#include <glm/glm.hpp>

#include "rasterizer/rasterizer.h"
#include "rasterizer/setup.h"

namespace rc {

// Visits the set-up of every (sub-)triangle a frame of `scene` would rasterize, in set-up order:
// the transform, clipping, culling and snapping of Rasterizer::render, with its raster positions
// (unsnapped: the vertices', or a clipped sub-triangle's own).
template <typename Real>
using SetupVisitor = std::function<void(const CoverageSetup<Real>&, const glm::dvec2 (&raster)[3])>;

template <typename Real>
void forEachSetup(const Scene& scene, const RasterOptions& options, const SetupVisitor<Real>& visit);

extern template void forEachSetup<float>(const Scene&, const RasterOptions&, const SetupVisitor<float>&);
extern template void forEachSetup<double>(const Scene&, const RasterOptions&, const SetupVisitor<double>&);

}  // namespace rc
