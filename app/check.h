// The check pipeline for one scene: rasterize, trace the reference, compare, gate.
// A library function (not CLI code) so integration tests run exactly what `check` runs.
#pragma once

#include <string>

#include "app/options.h"
#include "compare/compare.h"
#include "core/framebuffer.h"

namespace rc::app {

struct CheckResult {
  CompareReport report;
  Framebuffer raster, reference, heatmap;
  std::size_t triangles = 0;
  double rasterMs = 0.0, referenceMs = 0.0;
};

// With wantPictures, `raster` and `reference` carry their RGB previews (channels R, G, B) and
// `heatmap` is made, for the pictures and EXR files; without, none of the three. rasterMs and
// referenceMs time the renders alone (one cold frame each; the reference's with its BVH build).
CheckResult checkScene(const Scene& scene, const RenderSettings& settings,
                       const Thresholds& thresholds, bool wantPictures);

}  // namespace rc::app
