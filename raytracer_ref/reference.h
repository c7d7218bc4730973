// The ray-traced reference: one Embree ray through each pixel centre decides which triangle
// is hit; barycentrics, depth and attributes are then recomputed in double for that triangle
// and the camera's double-precision ray. Same entry shape as the rasterizer.
#pragma once

#include <string>

#include "core/framebuffer.h"
#include "scenes/scene.h"

namespace rc {

struct ReferenceOptions {
  int threads = 0;           // worker threads; 0 = all cores
  std::string isa = "avx2";  // Embree ISA pinned in the device config: sse2, sse4.2, avx, avx2,
                             // avx512; results differ between ISAs, so it is never left to Embree
};

// Throws usageError when the CPU lacks the pinned ISA, internalError when Embree fails.
Framebuffer renderReference(const Scene& scene, const ReferenceOptions& options);

}  // namespace rc
