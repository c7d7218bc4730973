// The per-tile pixel kernels' interface: what the rasterizer hands a tile (set-ups, bins, output
// planes) and the entry points, one per precision and instruction set (tile_kernel.cpp). Per
// tile: coverage + depth test into a tile-local visibility buffer (tile_coverage.h), then
// resolve (barycentrics, depth, attributes and diagnostics of each pixel's winner: tile_resolve.h
// and tile_gather.h), eight pixels of a row at a time in GCC vector extensions (kernel_lanes.h).
// The same source is compiled for SSE2 (any x86-64), AVX2 and AVX-512 (the rasterizer picks one
// at run time); each lane runs the formulas of setup.h and interpolate.h in the same order,
// without FMA, so all give the same bits (Rasterizer.OutputBitsAreIdenticalOnEveryKernelIsa).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "rasterizer/setup.h"

namespace rc::kernel {

constexpr int kTileShift = 6;
constexpr int kTileSize = 1 << kTileShift;  // 64
constexpr int kLanes = 8;
// The coverage pass prefetches the set-up this many bins ahead: a tile's bins skip through its
// blocks' arrays, which the hardware prefetcher does not follow (7% of the tiles' time at 1M).
constexpr std::size_t kPrefetchAhead = 8;
// coverRows runs a box one chunk wide and at most this many rows high as exactly 2 or this
// many rows, so the visibility buffers reach kFixedRows - 1 rows past the tile.
constexpr int kFixedRows = 4;
constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;
// A set-up is named by (block << kBlockShift) | index within its block: set-ups stay in their
// blocks (no concatenation), and the names still sort in triangle order.
constexpr int kBlockShift = 20;
constexpr std::uint32_t kLocalMask = (1u << kBlockShift) - 1u;

struct Outputs {
  int width;
  std::uint32_t* id;
  float* bary[3];
  float* depth;
  float* baryBound;     // the four diagnostics are null when they are not written
  float* depthBound;
  float* edgeDistance;
  float* depthTie;
  struct Attribute {
    const float* values;  // per vertex, `components` each
    int components;
    float* out[4];
  };
  std::vector<Attribute> attributes;
  int attributeComponents;  // sum of components
  // A float frame's pixels resolved again in double (tile_promote.h), counted by the tiles;
  // null in a double frame.
  std::atomic<std::uint64_t>* promotedPixels;
};

template <typename Real>
struct Input {
  const CoverageSetup<Real>* const* coverage;       // per block
  const ClippedTriangle* const* clipped;      // per block
  const glm::uvec3* triangles;                      // the mesh's
  const glm::dvec4* vertexClip;                     // per mesh vertex: setupShade's inputs
  const glm::dvec2* vertexRaster;
  const SetupContext* context;
  int subpixelBits;
  bool perspective;
  bool gatheredResolve;  // RasterOptions::gatheredResolve
  Real tieScale;  // depth.tie = tieScale (|key0| + |keyX dx| + |keyY dy|) depth (setup.h)
};

// One tile: pixels [x0, x1] x [y0, y1], set-ups bins[0..count) in triangle order.
struct TileJob {
  const std::uint32_t* bins;
  std::size_t count;
  int x0, y0, x1, y1;
};

// Entry points, one per (precision, instruction set); tile_kernel.cpp.
void renderTileSse2(const Input<float>&, const Outputs&, const TileJob&);
void renderTileSse2(const Input<double>&, const Outputs&, const TileJob&);
void renderTileAvx2(const Input<float>&, const Outputs&, const TileJob&);
void renderTileAvx2(const Input<double>&, const Outputs&, const TileJob&);
void renderTileAvx512(const Input<float>&, const Outputs&, const TileJob&);
void renderTileAvx512(const Input<double>&, const Outputs&, const TileJob&);
// The features the AVX-512 entry points are compiled for (tile_kernel.cpp's target attribute).
bool cpuHasKernelAvx512();
// Pixels covered by one set-up, for coveredPixels(); the kernels' own coverage code, SSE2.
// raster: its unsnapped vertices (read only without snapping, bits 0).
void coveredPixelsOf(const CoverageSetup<float>& s, int bits, const glm::dvec2 raster[3], std::vector<std::uint32_t>& pixels,
                     int width);
void coveredPixelsOf(const CoverageSetup<double>& s, int bits, const glm::dvec2 raster[3], std::vector<std::uint32_t>& pixels,
                     int width);

// The unsnapped raster positions of set-up c's vertices: the frame's (the mesh's triangles
// index vertexRaster), or its clipped sub-triangle's among its block's `clipped`.
template <typename Real>
inline __attribute__((always_inline)) void rasterOfSetup(const CoverageSetup<Real>& c, const glm::uvec3* triangles,
                                                         const glm::dvec2* vertexRaster,
                                                         const ClippedTriangle* clipped, glm::dvec2 v[3]) {
  if (c.source.clipped < 0) {
    const glm::uvec3 tri = triangles[c.source.triangle];
    v[0] = vertexRaster[tri.x], v[1] = vertexRaster[tri.y], v[2] = vertexRaster[tri.z];
  } else {
    const ClippedTriangle& t = clipped[c.source.clipped];
    v[0] = t.raster[0], v[1] = t.raster[1], v[2] = t.raster[2];
  }
}

// A tile row's copy-out (tile_kernel.cpp's streamStagedRow), out of line, for writeOutPass
// (rasterizer.h).
void streamStagedRowSse2(std::uint32_t* const* planes, int count, const std::uint32_t* stage, std::size_t stride,
                         std::size_t rowStart, int n);
void streamStagedRowAvx2(std::uint32_t* const* planes, int count, const std::uint32_t* stage, std::size_t stride,
                         std::size_t rowStart, int n);

}  // namespace rc::kernel
