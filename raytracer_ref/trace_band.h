// The reference's per-pixel work on a band of rows: rays through 4x4 pixel blocks in coherent
// packets of 16 (rtcIntersect16), then each block row of 4 hits recomputed in double in four
// lanes (core/lanes.h) and written. Compiled like the rasterizer's kernels: once for the
// x86-64 baseline and once with the AVX2 target attribute; both give the same bits, those of
// the formulas in ray_triangle.h run on one double.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <cstdint>
#include <vector>

#include "scenes/scene.h"

namespace rc::reference {

// Where each channel of the output goes, all planes of width x height values.
struct Planes {
  std::uint32_t* id;
  float* bary[3];
  float* depth;
  float* baryBound;
  float* depthBound;
  float* edgeDistance;
  struct Attribute {
    const float* values;  // the mesh's, vertex-major
    int components;
    std::array<float*, 4> out;
  };
  std::vector<Attribute> attributes;
};

struct BandInput {
  RTCScene scene;
  const Camera* camera;
  const Mesh* mesh;
  const std::uint32_t* source;  // Embree primID -> mesh triangle; null: the same index
  const double* rightOffsets;   // camera.rightOffset of each column's pixel centre, padded to 4
  Planes planes;
};

// Traces rows [y0, y1) (y0 a multiple of 4) and writes every pixel of them, misses too.
// Returns the largest |Embree's barycentrics - the double ones| over their hits (0 when
// `source` is set: a split triangle's (u, v) are not the mesh triangle's).
double traceBandSse2(const BandInput& in, int y0, int y1);
double traceBandAvx2(const BandInput& in, int y0, int y1);

}  // namespace rc::reference
