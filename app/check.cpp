// checkScene.
#include "app/check.h"

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
  result.report = compareImages(result.raster, scene.name + " (raster)", result.reference,
                                scene.name + " (reference)", thresholds,
                                wantPictures ? &result.heatmap : nullptr, settings.threads);
  return result;
}

}  // namespace rc::app
