// The CPU rasterizer: transform -> clip -> setup -> bin -> coverage + depth -> resolve.
// Same entry shape as the reference: (const Scene&, const Options&) -> Framebuffer.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/framebuffer.h"
#include "scenes/scene.h"

namespace rc {

enum class Interpolation {
  kPerspective,  // screen-space weights divided by w and renormalised (the seed notes)
  kAffine,       // screen-space weights used as they are: the classic bug, a wrong baseline
};
enum class Precision { kFloat, kDouble };
// The depth test's key, A + B / w with larger nearer, evaluated in the per-pixel precision:
enum class DepthMapping {
  kInverseW,  // A = 0, B = 1: 1/w itself, relative resolution u at any depth
  kStandard,  // minus OpenGL/D3D depth d = f / (f - n) (1 - n / w) (d = 1 - n / w with an
              // infinite far plane): in float, 2^-24 z / n relative near d = 1
};

const char* interpolationName(Interpolation mode);
const char* precisionName(Precision precision);
const char* depthMappingName(DepthMapping mapping);

struct RasterOptions {
  Interpolation interpolation = Interpolation::kPerspective;  // how barycentrics are recovered
  Precision precision = Precision::kFloat;  // arithmetic of clipping, setup and per-pixel work
  int subpixelBits = 8;  // fixed-point fraction bits of snapped vertices for coverage (1..16)
  DepthMapping depthMapping = DepthMapping::kInverseW;
  int threads = 0;       // worker threads; 0 = all cores
};

// Renders tri.id, bary.b0..b2, depth.z and every mesh attribute (attr.<name>.<c>), the
// diagnostics bound.bary, bound.depth, edge.dist and depth.tie (docs/numerics.md), plus an
// RGB preview. Throws usageError when subpixelBits does not fit the image size.
Framebuffer rasterize(const Scene& scene, const RasterOptions& options);

// Every (source triangle, pixel index) pair the coverage stage produces, before the depth
// test, in set-up order: the same transform, clipping, snapping and fill rule as rasterize.
// For tests against an exact oracle (tests/oracle/).
std::vector<std::pair<std::uint32_t, std::uint32_t>> coveredPixels(const Scene& scene,
                                                                   const RasterOptions& options);

}  // namespace rc
