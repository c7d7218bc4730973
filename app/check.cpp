// checkScene.
#include "app/check.h"

namespace rc::app {

CheckResult checkScene(const Scene& scene, const RenderSettings& settings,
                       const Thresholds& thresholds, bool wantHeatmap) {
  CheckResult result;
  result.triangles = scene.mesh.triangleCount();
  long long start = nowNanoseconds();
  result.raster = rasterize(scene, settings.raster);
  result.rasterMs = millisecondsSince(start);
  start = nowNanoseconds();
  result.reference = renderReference(scene, settings.reference);
  result.referenceMs = millisecondsSince(start);
  result.report = compareImages(result.raster, scene.name + " (raster)", result.reference,
                                scene.name + " (reference)", thresholds,
                                wantHeatmap ? &result.heatmap : nullptr, settings.threads);
  return result;
}

}  // namespace rc::app
