// Stage 1 of the rasterizer (pipeline.cpp): world positions to clip space through the camera,
// in double, with each vertex's outcode and raster position, and what a block of vertices tells
// about the transform's rounding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>

#include "rasterizer/clip.h"
#include "scenes/camera.h"

namespace rc {

// Raster position of a clip-space point inside the view volume.
inline glm::dvec2 rasterOf(const Camera& camera, const glm::dvec4& c) {
  return {camera.rasterXFromNdc(c.x / c.w), camera.rasterYFromNdc(c.y / c.w)};
}

// What the transform finds out about a block of vertices: the largest |world coordinate| (at
// least 1) and the nearest clip w, which bound the transform's rounding (clipError, culling,
// the edge band), and the or of their outcodes.
struct VertexFacts {
  double largest = 1.0;
  double nearestW = std::numeric_limits<double>::infinity();
  unsigned outcodes = 0;
};

// The transform of positions [begin, end): each vertex's clip position, outcode and (when the
// outcode is 0) raster position, into the frame's arrays with non-temporal stores, and the
// block's VertexFacts, folded into facts. The lines
// were last read by the other core's tiles, and a store that bypasses the cache need not take
// them from it first (BM_Frame at 1M, 2 threads: transform about 3.9 down to 2.0 to 2.6 ms; on
// 1 thread, whose lines are its own, 2.8 up to 3.5 ms). Set-up reads them back no slower.
void transformScalar(const glm::vec3* positions, std::size_t begin, std::size_t end, const glm::dmat4& m,
                     const ClipVolume<double>& volume, const Camera& camera, glm::dvec4* clip, glm::dvec2* raster,
                     std::uint8_t* outcode, VertexFacts& factsOut);

// transformScalar with AVX2, one vertex per 4-lane register. Every value takes the same IEEE
// operations as there, so the same bits: glm's mat4 * vec4 is (m0 x + m1 y) + (m2 z + m3 w),
// with w = 1 so that m3 w is m3; a distance guard w - x is guard w + (-x); the raster y,
// (1 - y / w) 0.5 height, has 1 - t as -t + 1. A third of the scalar loop's instructions
// (callgrind).
// Only where the CPU has AVX2.
void transformAvx2(const glm::vec3* positions, std::size_t begin, std::size_t end, const glm::dmat4& m,
                   const ClipVolume<double>& volume, const Camera& camera, glm::dvec4* clip, glm::dvec2* raster,
                   std::uint8_t* outcode, VertexFacts& facts);

}  // namespace rc
