// Stages 1 to 3 of the rasterizer (pipeline.h): transform, clipping and coverage set-up per
// block of triangles, and the bins per tile.
#include "rasterizer/pipeline.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include "core/clock.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/parallel.h"
#include "rasterizer/setup_batch.h"
#include "rasterizer/tile_kernel.h"
#include "rasterizer/vertex_order.h"

namespace rc {

namespace {

using kernel::kTileShift;
using kernel::kTileSize;

constexpr std::size_t kTrianglesPerBlock = 8192;

// The edge band takes the vertices one by one when bounding them at once would add more than
// this fraction of snapping's steps (Pipeline::edgeBand).
constexpr double kNegligibleShift = 1e-3;

// Asks for the cache line kWriteAhead bytes past `end` in a writable state ahead of the
// stores. The set-up arrays are rewritten every frame, and many of their lines were last read
// by the other core's tiles, so a store must first take the line from that core (about 110 ns
// between this machine's two cores). Measured: set-up on one thread took twice as long when
// the tiles before it had run on two threads as when they had run on one; this hint took a
// tenth off at 100k triangles. prefetchw is a no-op hint on x86-64 CPUs that lack it, and a
// prefetch never faults, so the address may lie past the end of the array; it is formed as an
// integer, since a pointer there (or off a null one) would be undefined. (Written as asm: GCC
// drops __builtin_prefetch's write hint, instruction and all, outside a prfchw target.)
constexpr std::uintptr_t kWriteAhead = 1024;  // bytes: about a dozen set-ups
inline void prefetchForWriteAhead(const void* end) {
  asm volatile("prefetchw (%0)" : : "r"(reinterpret_cast<std::uintptr_t>(end) + kWriteAhead));
}
// Names are (block << 20) | index (tile_kernel.h): a block's up to 7 sub-triangles per
// triangle must stay below 2^20, and block numbers below 4095 so no name equals kEmpty.
constexpr std::size_t kMaxBlocks = 4094;
// Set-up's vertex prefetches (vertex_order.h): from 16384 vertices (768 KB of clip and raster
// positions) on, 16 triangles ahead (32 and 64 measured the same on the Stanford bunny).
constexpr std::size_t kVertexPrefetchMinVertices = 16384;
constexpr std::size_t kVertexPrefetchAhead = 16;
constexpr std::size_t kMaxTrianglesPerBlock = (std::size_t(1) << kernel::kBlockShift) / (kMaxClipVertices - 2) - 1;

// `workers` empty queues, keeping what they had allocated in earlier frames.
void clearQueues(std::vector<std::vector<int>>& queues, int workers) {
  queues.resize(std::size_t(workers));
  for (std::vector<int>& queue : queues) queue.clear();
}

}  // namespace

template <typename Real>
Pipeline<Real>::Pipeline(const Scene& s, const RasterOptions& o, Frame<Real>& workspace)
    : scene(s), options(o), frame(workspace), isa(resolveKernelIsa(o.isa)), width(s.camera.width()),
      height(s.camera.height()) {
  // Guard band: 2^(28 - bits) pixels from the viewport centre, so that snapped positions
  // stay below 2^29 grid steps (coverage.h); the viewport must fit inside it. Without
  // snapping, 2^20 pixels, as with 8 bits: raster positions stay below 2^21.
  const double guardPixels = guardBandPixels(o.subpixelBits);
  if (std::max(width, height) > guardPixels) {
    throw usageError("--subpixel-bits " + std::to_string(o.subpixelBits) +
                     " is too fine for a " + std::to_string(width) + "x" +
                     std::to_string(height) + " image (exact int64 edges need at most " +
                     std::to_string(28 - int(std::ceil(std::log2(std::max(width, height))))) +
                     " bits)");
  }
  // The camera takes at most kMaxImageSide pixels a side.
  static_assert(kMaxImageSide / kTileSize <= 256, "tileBoxOf packs tile coordinates in 8 bits");
  tilesX = (width + kTileSize - 1) / kTileSize;
  tilesY = (height + kTileSize - 1) / kTileSize;
  const std::size_t count = s.mesh.triangles.size();
  blockSize = std::max(kTrianglesPerBlock, (count + kMaxBlocks - 1) / kMaxBlocks);
  if (blockSize > kMaxTrianglesPerBlock) {
    throw usageError("the rasterizer takes at most " + std::to_string(kMaxBlocks * kMaxTrianglesPerBlock) +
                     " triangles, got " + std::to_string(count));
  }
  volume.zNear = s.camera.zNear();
  volume.zFar = s.camera.zFar();
  volume.guard = 2.0 * guardPixels / std::max(width, height);
  context.width = width;
  context.height = height;
  context.subpixelBits = o.subpixelBits;
  if (o.subpixelBits == 0 && isa != KernelIsa::kSse2) {  // its own batch, without int64 lanes
    batchSetup = batch::setupUnsnappedAvx2;
  } else if (o.subpixelBits == 0) {
    batchSetup = batch::setupUnsnappedSse2;
  } else if (isa == KernelIsa::kAvx512) {  // AVX-512 VL and DQ have int64 multiplies, min and max
    batchSetup = batch::setupCoverageAvx512;
  } else if (isa != KernelIsa::kSse2) {
    batchSetup = batch::setupCoverageAvx2;
  } else {
    batchSetup = batch::setupCoverageSse2;
  }
  context.unitRoundoff = std::is_same_v<Real, float> ? 0x1p-24 : 0x1p-53;
  const double n = s.camera.zNear(), f = s.camera.zFar();
  if (o.depthMapping == DepthMapping::kInverseW) {
    context.keyA = 0.0, context.keyB = 1.0;
  } else if (std::isinf(f)) {
    context.keyA = -1.0, context.keyB = n;
  } else {
    context.keyA = -f / (f - n), context.keyB = f * n / (f - n);
  }
}

template <typename Real>
void Pipeline<Real>::transform() {
  const glm::dmat4 clipFromWorld = scene.camera.clipFromWorld();
  const auto& positions = scene.mesh.positions;
  frame.clip.resize(positions.size());
  frame.raster.resize(positions.size());
  frame.outcode.resize(positions.size());
  const int blocks = int((positions.size() + kTrianglesPerBlock - 1) / kTrianglesPerBlock);
  frame.vertexFacts.assign(blocks, VertexFacts{});
  const auto transformRange = isa != KernelIsa::kSse2 ? transformAvx2 : transformScalar;
  parallelFor(blocks, options.threads, [&](int b) {
    const std::size_t end = std::min(positions.size(), std::size_t(b + 1) * kTrianglesPerBlock);
    transformRange(positions.data(), std::size_t(b) * kTrianglesPerBlock, end, clipFromWorld, volume, scene.camera,
                   frame.clip.data(), frame.raster.data(), frame.outcode.data(), frame.vertexFacts[b]);
    _mm_sfence();
  });
  VertexFacts& all = frame.vertices;
  all = VertexFacts{};
  for (const VertexFacts& f : frame.vertexFacts) {
    all.largest = std::max(all.largest, f.largest);
    all.nearestW = std::min(all.nearestW, f.nearestW);
    all.outcodes |= f.outcodes;
  }
  context.clipError = clipErrorBound(clipFromWorld, all.largest);
  // Back faces (docs/rasterizer.md): when every vertex lies beyond the near plane, so does
  // the whole solid, and every view ray starts outside it. clipError covers the rounding of
  // the computed w.
  context.cullBackFaces = options.culling == Culling::kAuto && scene.mesh.closedSolid && !positions.empty() &&
                          all.nearestW - context.clipError > scene.camera.zNear();
  frame.allInside = all.outcodes == 0;
}

// How far a vertex's double raster position r may lie from the exact projection of the mesh,
// in pixels: setup_formulas.h's boundsOf delta, from its clip position c.
template <typename Real>
double Pipeline<Real>::rasterShift(const glm::dvec4& c, const glm::dvec2& r) const {
  const double ndc = std::max(std::fabs(c.x), std::fabs(c.y)) / c.w;
  return 0.5 * std::max(width, height) * context.clipError * (1.0 + ndc) / c.w +
         0x1p-50 * (std::max(std::fabs(r.x), std::fabs(r.y)) + 1.0);
}

// The header's edge band (docs/numerics.md): the distance within which coverage may decide a
// centre otherwise than the exact projection of the mesh would, in pixels; after set-up. The
// double raster positions may have moved by rasterShift, at the most over the vertices set up,
// doubled for the second-order terms and the clipped vertices' interpolation. Without
// snapping coverage is exact for those positions, and that is the band; snapping adds
// sqrt(2)/2 grid steps. A clipped sub-triangle's vertices are taken one by one, in set-up.
// The vertices inside the view volume are bounded at once first, from the transform's facts:
// |ndc| at the guard band (|r| <= (|ndc| + 1) / 2 the image's side), w at the nearest vertex
// or the near plane. That costs nothing, and next to snapping's steps it is mostly
// negligible (3.9e-9 pixel on the blob at 1920x1080); where it is not (a thousandth of them,
// or no snapping), a pass takes the vertices one by one (0.0107 pixel at 8 bits on
// faroffset:offset=1e7 at once, 1.1e-6 one by one).
template <typename Real>
double Pipeline<Real>::edgeBand() const {
  const double side = std::max(width, height);
  const double snapping = options.subpixelBits == 0 ? 0.0 : 0.7072 * std::ldexp(1.0, -options.subpixelBits);
  const double w = std::max(frame.vertices.nearestW, volume.zNear), ndc = volume.guard;
  double shift = 0.5 * side * context.clipError * (1.0 + ndc) / w + 0x1p-50 * (0.5 * (ndc + 1.0) * side + 1.0);
  if (2.0 * shift > kNegligibleShift * snapping) shift = insideShift();
  for (const SetupBlock<Real>& block : frame.blocks) shift = std::max(shift, block.clippedShift);
  return snapping + 2.0 * shift;
}

// The largest rasterShift over the vertices inside the view volume, in parallel blocks.
template <typename Real>
double Pipeline<Real>::insideShift() const {
  const std::size_t count = frame.clip.size();
  const int blocks = int((count + kTrianglesPerBlock - 1) / kTrianglesPerBlock);
  std::vector<double> largest(std::size_t(blocks), 0.0);
  parallelFor(blocks, options.threads, [&](int b) {
    const std::size_t end = std::min(count, std::size_t(b + 1) * kTrianglesPerBlock);
    double most = 0.0;
    for (std::size_t v = std::size_t(b) * kTrianglesPerBlock; v < end; ++v) {
      if (frame.outcode[v] == 0) most = std::max(most, rasterShift(frame.clip[v], frame.raster[v]));
    }
    largest[std::size_t(b)] = most;
  });
  return largest.empty() ? 0.0 : *std::max_element(largest.begin(), largest.end());
}

// Only the coverage half of the set-up runs here; the tiles run setupShade for the set-ups
// that win a pixel, from the same inputs (the frame's vertex arrays, or `clipped`).
template <typename Real>
void Pipeline<Real>::emit(SetupBlock<Real>& block, std::uint32_t triangle, const glm::dvec4 sub[3],
                          const glm::dvec2 raster[3], int clipped) const {
  CoverageSetup<Real> c;
  if (setupCoverage(sub, raster, context, c)) append(block, c, triangle, clipped);
}

template <typename Real>
void Pipeline<Real>::append(SetupBlock<Real>& block, const CoverageSetup<Real>& c, std::uint32_t triangle,
                            int clipped) {
  prefetchForWriteAhead(block.coverage.data() + block.coverage.size());
  block.coverage.push_back(c);
  block.coverage.back().source = {triangle, clipped};
}

// The batch set-up of whole triangles tris[0..kLanes) into c, appending the set-ups it
// accepts among the first n under their triangle ids, idOf(k); the lanes past n are ignored.
template <typename Real>
template <typename IdOf>
void Pipeline<Real>::setupWhole(const glm::uvec3 tris[], std::size_t n, IdOf&& idOf, CoverageSetup<Real> c[],
                                SetupBlock<Real>& block) const {
  const unsigned accepted = batchSetup(tris, frame.clip.data(), frame.raster.data(), context, c);
  for (std::size_t k = 0; k < n; ++k) {
    if ((accepted >> k) & 1u) append(block, c[k], idOf(k), -1);
  }
}

// Whole triangles (every vertex inside the view volume) go through the batch set-up four at
// a time; a clipped triangle first flushes the batch, so set-ups stay in triangle order.
template <typename Real>
void Pipeline<Real>::setupTriangleRange(std::size_t begin, std::size_t end, SetupBlock<Real>& block) const {
  if (frame.allInside && options.wholeMeshBatches) {
    setupAllInside(begin, end, block);
    return;
  }
  const auto& triangles = scene.mesh.triangles;
  glm::uvec3 pendingTris[batch::kLanes];
  std::uint32_t pendingIds[batch::kLanes];
  CoverageSetup<Real> c[batch::kLanes];
  int pending = 0;
  const auto flush = [&] {
    if (pending == 0) return;
    for (int k = pending; k < batch::kLanes; ++k) pendingTris[k] = pendingTris[0];  // lanes ignored
    setupWhole(pendingTris, std::size_t(pending), [&](std::size_t k) { return pendingIds[k]; }, c, block);
    pending = 0;
  };
  for (std::size_t t = begin; t < end; ++t) {
    const glm::uvec3 tri = triangles[t];
    const unsigned c0 = frame.outcode[tri.x], c1 = frame.outcode[tri.y], c2 = frame.outcode[tri.z];
    if (c0 & c1 & c2) continue;  // all outside one plane: nothing visible
    const auto id = static_cast<std::uint32_t>(t);
    if ((c0 | c1 | c2) == 0) {
      pendingTris[pending] = tri;
      pendingIds[pending] = id;
      if (++pending == batch::kLanes) flush();
      continue;
    }
    flush();
    setupClipped(id, tri, c0 | c1 | c2, block);
  }
  flush();
}

// Every vertex is inside the view volume, so every triangle is whole: four at a time, in
// order, without reading outcodes (set-up at 1M triangles about 15% faster). Vertex arrays
// larger than about a core's L2 cache, in an order that jumps through them, take prefetches of
// the vertices kVertexPrefetchAhead triangles on (vertex_order.h).
template <typename Real>
void Pipeline<Real>::setupAllInside(std::size_t begin, std::size_t end, SetupBlock<Real>& block) const {
  const auto& triangles = scene.mesh.triangles;
  glm::uvec3 tris[batch::kLanes];
  CoverageSetup<Real> c[batch::kLanes];
  const bool prefetch = frame.raster.size() >= kVertexPrefetchMinVertices &&
                        jumpsThroughVertices(triangles.data() + begin, end - begin);
  for (std::size_t t = begin; t < end; t += batch::kLanes) {
    const std::size_t n = std::min<std::size_t>(batch::kLanes, end - t);
    for (std::size_t k = 0; k < batch::kLanes; ++k) tris[k] = triangles[t + (k < n ? k : 0)];
    if (prefetch && t + kVertexPrefetchAhead + batch::kLanes <= end) {
      for (std::size_t k = 0; k < batch::kLanes; ++k) {
        const glm::uvec3 ahead = triangles[t + kVertexPrefetchAhead + k];
        for (int i = 0; i < 3; ++i) {
          __builtin_prefetch(&frame.raster[ahead[i]]);
          __builtin_prefetch(&frame.clip[ahead[i]].w);
        }
      }
    }
    setupWhole(tris, n, [t](std::size_t k) { return std::uint32_t(t + k); }, c, block);
  }
}

// A triangle that crosses a plane of the view volume (its vertices' outcodes or'ed): clipped
// to a polygon, set up as a fan of sub-triangles, each recorded in block.clipped.
template <typename Real>
void Pipeline<Real>::setupClipped(std::uint32_t id, const glm::uvec3& tri, unsigned outcodes,
                                  SetupBlock<Real>& block) const {
  const auto& clip = frame.clip;
  const glm::dvec4 v[3] = {clip[tri.x], clip[tri.y], clip[tri.z]};
  const ClipVertex<double> in[3] = {{v[0], {1, 0, 0}}, {v[1], {0, 1, 0}}, {v[2], {0, 0, 1}}};
  ClipVertex<double> poly[kMaxClipVertices];
  const int n = clipPolygon(in, volume, outcodes, poly);
  for (int k = 1; k + 1 < n; ++k) {  // fan around poly[0]
    const glm::dvec4 sub[3] = {poly[0].clip, poly[k].clip, poly[k + 1].clip};
    const glm::dvec2 raster[3] = {rasterOf(sub[0]), rasterOf(sub[1]), rasterOf(sub[2])};
    // The fan's diagonals poly[0]-poly[k] (opposite vertex 2) and poly[k+1]-poly[0]
    // (opposite vertex 1) run inside the polygon, except its first and last edges.
    const unsigned inner = (k > 1 ? 4u : 0u) | (k + 2 < n ? 2u : 0u);
    block.clipped.push_back({glm::dmat3(poly[0].bary, poly[k].bary, poly[k + 1].bary),
                             {sub[0], sub[1], sub[2]},
                             {raster[0], raster[1], raster[2]},
                             inner});
    emit(block, id, sub, raster, int(block.clipped.size()) - 1);
  }
}

// The tiles a set-up's box touches, packed in a word: first and last tile column, then row,
// 8 bits each (at most kMaxImageSide / kTileSize = 256 tiles a side). The box lies in the
// viewport, so its coordinates are non-negative. Set-up packs it while the record is in
// cache; binning then reads 4 bytes a set-up instead of the record's 64.
template <typename Real>
std::uint32_t Pipeline<Real>::tileBoxOf(const CoverageSetup<Real>& s) {
  return (unsigned(s.minX) >> kTileShift) | (unsigned(s.maxX) >> kTileShift) << 8 |
         (unsigned(s.minY) >> kTileShift) << 16 | (unsigned(s.maxY) >> kTileShift) << 24;
}

// Most set-ups of a large mesh lie in one tile (on the blob at 1920x1080, 93% at 1M
// triangles, 74% at 100k), which skips the loops.
template <typename Real>
template <typename Fn>
void Pipeline<Real>::forEachTile(std::uint32_t box, Fn&& fn) const {
  const unsigned x0 = box & 0xFFu, x1 = (box >> 8) & 0xFFu, y0 = (box >> 16) & 0xFFu, y1 = box >> 24;
  if (((box ^ (box >> 8)) & 0x00FF00FFu) == 0) {  // x0 == x1 and y0 == y1
    fn(std::size_t(y0) * tilesX + x0);
    return;
  }
  for (unsigned ty = y0; ty <= y1; ++ty) {
    for (unsigned tx = x0; tx <= x1; ++tx) fn(std::size_t(ty) * tilesX + tx);
  }
}

// A wrong fill rule (RasterOptions::fillRule), made by rewriting the set-ups' top-left flags:
// every edge owns the centres on it (inclusive) or none does (exclusive).
template <typename Real>
void Pipeline<Real>::breakFillRule(SetupBlock<Real>& block) const {
  constexpr std::uint32_t kEvery = 7u * CoverageSetup<Real>::kNotTopLeft;
  for (std::size_t i = 0; i < block.coverage.size(); ++i) {
    CoverageSetup<Real>& c = block.coverage[i];
    c.flags = options.fillRule == FillRule::kInclusive ? c.flags & ~kEvery : c.flags | kEvery;
  }
}

// Stages 2 and 3: set-ups per block and their bins.
template <typename Real>
void Pipeline<Real>::setupAndBin(StageTimes& times) {
  const long long t0 = nowNanoseconds();
  const int workers = resolveThreadCount(options.threads);
  setupBlocks(workers);
  times.setupMs = millisecondsSince(t0);
  const long long t1 = nowNanoseconds();
  binBlocks(workers);
  assignTiles(workers);
  times.binMs = millisecondsSince(t1);
}

// Stage 2: each block's set-ups, their clipped vertices' largest shift, and the number of them
// each tile's box touches. Each worker sets up a contiguous run of blocks, so that the tiles can
// go to the worker whose caches hold most of their set-ups (assignTiles).
template <typename Real>
void Pipeline<Real>::setupBlocks(int workers) {
  const std::size_t count = scene.mesh.triangles.size();
  const int blocks = int((count + blockSize - 1) / blockSize);
  const std::size_t tiles = std::size_t(tileCount());
  frame.blocks.resize(std::size_t(blocks));
  const std::size_t slice = options.setupSlice > 0 ? std::min(options.setupSlice, blockSize) : blockSize;
  frame.coverageSlices.resize(std::size_t(blocks) * slice);
  frame.blockWorker.assign(std::size_t(blocks), 0);
  parallelForQueues(contiguousQueues(blocks, workers), [&](int b, int worker) {
    frame.blockWorker[std::size_t(b)] = worker;
    SetupBlock<Real>& block = frame.blocks[b];
    block.coverage.reset(frame.coverageSlices.data() + std::size_t(b) * slice, slice);
    block.clipped.clear();
    const std::size_t begin = std::size_t(b) * blockSize;
    setupTriangleRange(begin, std::min(count, begin + blockSize), block);
    if (options.fillRule != FillRule::kTopLeft) breakFillRule(block);
    block.clippedShift = 0.0;
    for (const ClippedTriangle& t : block.clipped) {
      for (int i = 0; i < 3; ++i) block.clippedShift = std::max(block.clippedShift, rasterShift(t.clip[i], t.raster[i]));
    }
    block.tileCursor.assign(tiles, 0);
    block.tileBox.resize(block.coverage.size());
    for (std::size_t i = 0; i < block.coverage.size(); ++i) {
      block.tileBox[i] = tileBoxOf(block.coverage[i]);
      forEachTile(block.tileBox[i], [&](std::size_t t) { ++block.tileCursor[t]; });
    }
  });
}

// Stage 3: every tile's list of set-up names, in (block, index) order, so triangle order.
template <typename Real>
void Pipeline<Real>::binBlocks(int workers) {
  const std::size_t tiles = std::size_t(tileCount()), blocks = frame.blocks.size();
  frame.blockCoverage.resize(blocks);
  frame.blockClipped.resize(blocks);
  // A block's place in a tile's list is the tile's start plus the earlier blocks' counts there.
  // The counts are summed block by block, each block's array in order (tile by tile, the walk
  // strode through every block's array, a cache miss a step: about 1 ms at 1M triangles,
  // serial), and each block adds the tiles' starts to its own cursors below, in parallel.
  frame.tileTotal.assign(tiles, 0);
  frame.tileShare.assign(std::size_t(workers) * tiles, 0);
  clearQueues(frame.blockQueues, workers);
  for (std::size_t b = 0; b < blocks; ++b) {
    SetupBlock<Real>& block = frame.blocks[b];
    std::size_t* share = frame.tileShare.data() + std::size_t(frame.blockWorker[b]) * tiles;
    for (std::size_t t = 0; t < tiles; ++t) {
      const std::size_t n = block.tileCursor[t];
      block.tileCursor[t] = frame.tileTotal[t];
      frame.tileTotal[t] += n;
      share[t] += n;
    }
    frame.blockQueues[std::size_t(frame.blockWorker[b])].push_back(int(b));
  }
  frame.binStart.resize(tiles + 1);
  std::size_t total = 0;
  for (std::size_t t = 0; t < tiles; ++t) {
    frame.binStart[t] = total;
    total += frame.tileTotal[t];
  }
  frame.binStart[tiles] = total;
  frame.binned.resize(total);
  // A tile's list holds a few set-ups of each block, so neighbouring blocks write into the
  // same cache lines: each worker bins the contiguous run of blocks it set up (binning at
  // 1M triangles, 2 threads: 1.2 to 1.0 ms when each thread first took a contiguous run).
  parallelForQueues(frame.blockQueues, [&](int b, int) {
    SetupBlock<Real>& block = frame.blocks[b];
    for (std::size_t t = 0; t < tiles; ++t) block.tileCursor[t] += frame.binStart[t];
    frame.blockCoverage[b] = block.coverage.data();
    frame.blockClipped[b] = block.clipped.data();
    for (std::size_t i = 0; i < block.coverage.size(); ++i) {
      const auto name = std::uint32_t((std::size_t(b) << kernel::kBlockShift) | i);
      forEachTile(block.tileBox[i], [&](std::size_t t) { frame.binned[block.tileCursor[t]++] = name; });
    }
  });
}

// Each tile goes to the worker that made most of its set-ups; empty tiles take turns.
template <typename Real>
void Pipeline<Real>::assignTiles(int workers) {
  const std::size_t tiles = std::size_t(tileCount());
  clearQueues(frame.tileQueues, workers);
  for (std::size_t t = 0; t < tiles; ++t) {
    std::size_t best = t % std::size_t(workers);
    for (std::size_t w = 0; w < std::size_t(workers); ++w) {
      if (frame.tileShare[w * tiles + t] > frame.tileShare[best * tiles + t]) best = w;
    }
    frame.tileQueues[best].push_back(int(t));
  }
}

template struct Pipeline<float>;
template struct Pipeline<double>;

}  // namespace rc
