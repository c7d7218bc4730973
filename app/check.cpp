// checkScene.
#include "app/check.h"

#include "compare/report.h"
#include "core/channels.h"
#include "core/clock.h"
#include "core/preview.h"
#include "raytracer_ref/reference.h"

namespace rc::app {

CheckResult checkScene(const Scene& scene, const RenderSettings& settings,
                       const Thresholds& thresholds, bool wantPictures) {
  CheckResult result;
  result.triangles = scene.mesh.triangleCount();
  long long start = nowNanoseconds();
  Rasterizer(settings.raster).render(scene, result.raster);
  result.rasterMs = millisecondsSince(start);
  start = nowNanoseconds();
  ReferenceTracer(scene, settings.reference).trace(result.reference);
  result.referenceMs = millisecondsSince(start);
  // The RGB previews are made only for the pictures and the EXR files, and are not timed: at
  // 1920x1080 they are six more planes (50 MB) to fault in and fill.
  if (wantPictures) {
    addPreview(result.raster);
    addPreview(result.reference);
  }
  result.audit = auditCoverage(scene, settings.raster, result.raster);
  result.report = compareImages(result.raster, scene.name + " (raster)", result.reference,
                                scene.name + " (reference)", thresholds,
                                wantPictures ? &result.heatmap : nullptr, settings.threads);
  for (std::string& reason : auditReasons(result.audit)) {
    result.report.reasons.push_back(std::move(reason));
    result.report.pass = false;
  }
  return result;
}

std::string auditLine(const CoverageAudit& a) {
  return "coverage audit: " + std::to_string(a.covered) + " covered pixels, " + std::to_string(a.onEdge) +
         " of them with the centre exactly on an edge; " +
         (a.violations() == 0 ? std::string("each covered by the triangle the top-left rule and the depth test give it")
                              : std::to_string(a.violations()) + " violation(s)") +
         (a.diagnosed == 0 ? std::string("; no diagnostics")
                           : "; edge.dist and depth.tie checked at " + std::to_string(a.diagnosed) + " pixels") +
         "; edge band " + formatNumber(a.edgeBand) + " px, at most " + formatNumber(a.edgeBandLimit) +
         " (" + formatNumber(a.ms) + " ms)";
}

std::vector<std::string> auditReasons(const CoverageAudit& audit) {
  const auto at = [](const CoverageAudit::Pixel& p) {
    return "first at (" + std::to_string(p.x) + ", " + std::to_string(p.y) + "): ";
  };
  const auto triangle = [](std::uint32_t t) {
    return t == channels::kNoTriangle ? std::string("nothing") : "triangle " + std::to_string(t);
  };
  std::vector<std::string> reasons;
  if (audit.notOwned > 0) {
    reasons.push_back("coverage audit: " + std::to_string(audit.notOwned) +
                      " pixel(s) written by a triangle that does not cover the centre under the top-left rule (" +
                      at(audit.firstNotOwned) + triangle(audit.firstNotOwned.written) + " written, " +
                      (audit.firstNotOwned.owner == channels::kNoTriangle ? std::string("no triangle owns it")
                                                                           : triangle(audit.firstNotOwned.owner) + " owns it") +
                      ")");
  }
  if (audit.lost > 0) {
    reasons.push_back("coverage audit: " + std::to_string(audit.lost) +
                      " pixel(s) left empty or to a farther triangle where a nearer one covers the centre (" +
                      at(audit.firstLost) + triangle(audit.firstLost.written) + " written, " +
                      triangle(audit.firstLost.owner) + " nearer)");
  }
  if (audit.offGrid > 0) {
    reasons.push_back("coverage audit: " + std::to_string(audit.offGrid) +
                      " triangle corner(s) snapped to a grid point other than the one nearest the raster position (first: " +
                      triangle(audit.firstOffGrid) + ")");
  }
  const auto diagnostic = [](const CoverageAudit::Diagnostic& d, const char* unit) {
    return "first found at (" + std::to_string(d.x) + ", " + std::to_string(d.y) + "), triangle " +
           std::to_string(d.triangle) + ": " + formatNumber(d.written) + unit + " written, " + formatNumber(d.audited) +
           unit;
  };
  if (audit.edgeDistanceShort > 0) {
    reasons.push_back("coverage audit: " + std::to_string(audit.edgeDistanceShort) +
                      " pixel(s) whose edge.dist falls short of the centre's distance from its triangle's edges, "
                      "which would explain away disagreements (" +
                      diagnostic(audit.firstEdgeDistanceShort, " px") + " from the edges)");
  }
  if (audit.boundWide > 0) {
    reasons.push_back("coverage audit: " + std::to_string(audit.boundWide) +
                      " pixel(s) whose bound.bary or bound.depth exceeds its triangle's error bound, which would pass "
                      "larger errors (" +
                      diagnostic(audit.firstBoundWide, "") + " the bound)");
  }
  if (audit.edgeBandWide()) {
    reasons.push_back("coverage audit: the header's edge band of " + formatNumber(audit.edgeBand) +
                      " px is wider than snapping and the transform allow (at most " +
                      formatNumber(audit.edgeBandLimit) + " px), which would explain away disagreements");
  }
  if (audit.cameraMismatch) {
    reasons.push_back("coverage audit: the header's camera line (rastercheck.camera) is not the scene's, and the "
                      "comparison takes its near and far planes");
  }
  if (audit.depthTieWide > 0) {
    reasons.push_back("coverage audit: " + std::to_string(audit.depthTieWide) +
                      " pixel(s) whose depth.tie exceeds its depth key's error bound, which would explain away "
                      "disagreements (" +
                      diagnostic(audit.firstDepthTieWide, "") + " the bound)");
  }
  return reasons;
}

}  // namespace rc::app
