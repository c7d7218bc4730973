// Whether a run of a mesh's triangles jumps through its vertex arrays, so that set-up
// prefetches vertices only where the hardware prefetcher cannot follow its reads.
//
// A mesh in strip or grid order (the blob, most modelled meshes) reads its vertices nearly in
// sequence, which the hardware prefetcher follows, and prefetching there is pure cost. A
// scan's order (the Stanford bunny's) jumps across the mesh from one triangle to the next, and
// once the vertex arrays outgrow the core's L2 cache nearly every jump misses it
// (docs/rasterizer-speed.md, "Vertex order").
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>

namespace rc {

// A triangle jumps when its first vertex index lies more than kNearVertices from the previous
// triangle's: 32 vertices are 512 bytes of raster positions, 8 cache lines.
constexpr std::uint32_t kNearVertices = 32;

// True when at least a quarter of 16 pairs of consecutive triangles, spread evenly over
// tris[0, count), jump.
inline bool jumpsThroughVertices(const glm::uvec3* tris, std::size_t count) {
  constexpr std::size_t kSamples = 16;
  if (count < 2) return false;
  std::size_t jumps = 0;
  for (std::size_t s = 0; s < kSamples; ++s) {
    const std::size_t t = (count - 1) * s / kSamples;
    jumps += tris[t + 1].x - tris[t].x + kNearVertices > 2 * kNearVertices;  // unsigned: |difference| > kNear
  }
  return jumps >= kSamples / 4;
}

}  // namespace rc
