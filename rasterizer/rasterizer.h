// The CPU rasterizer: transform -> clip -> setup -> bin -> coverage + depth -> resolve.
// Same entry shape as the reference: (const Scene&, const Options&) -> Framebuffer.
#pragma once

#include "core/framebuffer.h"
#include "scenes/scene.h"

namespace rc {

enum class Interpolation {
  kPerspective,  // screen-space weights divided by w and renormalised (the seed notes)
  kAffine,       // screen-space weights used as they are: the classic bug, a wrong baseline
};
enum class Precision { kFloat, kDouble };

const char* interpolationName(Interpolation mode);
const char* precisionName(Precision precision);

struct RasterOptions {
  Interpolation interpolation = Interpolation::kPerspective;  // how barycentrics are recovered
  Precision precision = Precision::kFloat;  // arithmetic of clipping, setup and per-pixel work
  int subpixelBits = 8;  // fixed-point fraction bits of snapped vertices for coverage (1..16)
  int threads = 0;       // worker threads; 0 = all cores
};

// Renders tri.id, bary.b0..b2, depth.z and every mesh attribute (attr.<name>.<c>), plus an
// RGB preview. Throws usageError when subpixelBits does not fit the image size.
Framebuffer rasterize(const Scene& scene, const RasterOptions& options);

}  // namespace rc
