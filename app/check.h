// The check pipeline for one scene: rasterize, trace the reference, compare, gate.
// A library function (not CLI code) so integration tests run exactly what `check` runs.
#pragma once

#include <string>
#include <vector>

#include "app/settings.h"
#include "compare/compare.h"
#include "core/framebuffer.h"
#include "rasterizer/coverage_audit.h"

namespace rc::app {

struct CheckResult {
  CompareReport report;
  Framebuffer raster, reference, heatmap;
  std::size_t triangles = 0;
  double rasterMs = 0.0, referenceMs = 0.0;
  CoverageAudit audit;  // of `raster`; its violations are among the report's reasons
};

// The audit in a line: its counts and time (check -v, the HTML report).
std::string auditLine(const CoverageAudit& audit);
// The gate's reasons for a coverage audit's violations (none when it found none).
std::vector<std::string> auditReasons(const CoverageAudit& audit);

// With wantPictures, `raster` and `reference` carry their RGB previews (channels R, G, B) and
// `heatmap` is made, for the pictures and EXR files; without, none of the three. rasterMs and
// referenceMs time the renders alone (one cold frame each; the reference's with its BVH build).
// The raster frame is audited (rasterizer/coverage_audit.h), and a violation fails the gate.
CheckResult checkScene(const Scene& scene, const RenderSettings& settings,
                       const Thresholds& thresholds, bool wantPictures);

}  // namespace rc::app
