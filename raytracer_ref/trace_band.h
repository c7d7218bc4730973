// The reference's per-pixel work on a band of rows: rays through 4x4 pixel blocks in coherent
// packets of 16 (rtcIntersect16), then each block row of 4 hits recomputed in double in four
// lanes (core/lanes.h) and written. Compiled like the rasterizer's kernels: once for the
// x86-64 baseline and once with the AVX2 target attribute; both give the same bits, those of
// the formulas in ray_triangle.h run on one double.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "scenes/scene.h"

namespace rc::reference {

constexpr int kBlock = 4;  // a packet is kBlock x kBlock pixels; a lane row is one block row

// The output planes, in this order, float planes as their bits: tri.id, bary.b0..b2,
// depth.z, bound.bary, bound.depth, edge.dist, then each attribute's components in turn and
// its spread (channels::spreadChannel).
enum : int {
  kIdPlane = 0,
  kBaryPlane = 1,
  kDepthPlane = 4,
  kBaryBoundPlane = 5,
  kDepthBoundPlane = 6,
  kEdgeDistancePlane = 7,
  kAttributePlanes = 8,
};

struct BandInput {
  RTCScene scene;
  const Camera* camera;
  const Mesh* mesh;
  const std::uint32_t* source;  // Embree primID -> mesh triangle; null: the same index
  const double* rightOffsets;   // rightOffsetsOf(camera)
  bool clipCuts;                // a vertex lies nearer than near or beyond far: measure the cuts
  std::vector<std::uint32_t*> planes;  // each width x height values
  struct Attribute {
    const float* values;  // the mesh's, vertex-major
    int components;
  };
  std::vector<Attribute> attributes;  // their planes follow kAttributePlanes in this order
};

// Camera::rightOffset of each column's pixel centre, padded to whole blocks: every ray's
// direction is Camera::directionFromOffsets of its column's part and its row's.
std::vector<double> rightOffsetsOf(const Camera& camera);

// Traces rows [y0, y1) (y0 a multiple of 4) and writes every pixel of them, misses too.
// Returns the largest |Embree's barycentrics - the double ones| over their hits (0 when
// `source` is set: a split triangle's (u, v) are not the mesh triangle's).
double traceBandSse2(const BandInput& in, int y0, int y1);
double traceBandAvx2(const BandInput& in, int y0, int y1);

}  // namespace rc::reference
