// The CPU rasterizer: transform -> clip -> setup -> bin -> coverage + depth -> resolve.
// Same entry shape as the reference: (const Scene&, const Options&) -> Framebuffer.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
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

// Back faces: a triangle that is clockwise on screen faces away from the eye.
enum class Culling {
  kAuto,  // cull back faces when they cannot be seen: the mesh is a closed solid
          // (Mesh::closedSolid) and lies wholly beyond the near plane, so every view ray starts
          // outside it and meets a front face first (docs/rasterizer.md, "Back faces")
  kNone,  // draw every triangle
};

// Which pixel centres exactly on an edge a triangle covers. Only the top-left rule is right, and
// it is the default: two triangles that share an edge never both cover a centre on it, and never
// both miss one. The other two are wrong on purpose, so that anyone can see the gate fail them
// (its coverage audit, rasterizer/coverage_audit.h): inclusive covers a centre on any edge
// (both triangles of a shared edge), exclusive none (holes along every shared edge).
enum class FillRule { kTopLeft, kInclusive, kExclusive };
const char* fillRuleName(FillRule rule);

// The instruction set of the pixel kernels. Every level runs the same sequence of IEEE
// operations lane by lane (no FMA, no approximate reciprocals), so the output bits are the same
// on every level; auto picks the widest the CPU has.
// avx512 (AVX-512 F, VL, DQ and BW) is the AVX2 kernel compiled with AVX-512 enabled: the tiles'
// int64 coverage lanes and 8-wide doubles become one register each; set-up and transform
// stay AVX2 there.
enum class KernelIsa { kAuto, kSse2, kAvx2, kAvx512 };

const char* interpolationName(Interpolation mode);
const char* kernelIsaName(KernelIsa isa);
// The level `isa` resolves to on this CPU; throws usageError when the CPU lacks it.
KernelIsa resolveKernelIsa(KernelIsa isa);
const char* precisionName(Precision precision);
const char* depthMappingName(DepthMapping mapping);
// "8", or "none" for 0: as --subpixel-bits takes it and rastercheck.subpixelBits records it.
std::string subpixelBitsName(int bits);

struct RasterOptions {
  Interpolation interpolation = Interpolation::kPerspective;  // how barycentrics are recovered
  Precision precision = Precision::kFloat;  // arithmetic of clipping, setup and per-pixel work
  // Fixed-point fraction bits of snapped vertices for coverage (1..16), or 0: no snapping,
  // coverage of the unsnapped triangle decided exactly (orientation.h).
  int subpixelBits = 8;
  DepthMapping depthMapping = DepthMapping::kInverseW;
  int threads = 0;       // worker threads; 0 = all cores
  bool diagnostics = true;  // write bound.bary, bound.depth, edge.dist, depth.tie (compare's gate uses them)
  KernelIsa isa = KernelIsa::kAuto;
  Culling culling = Culling::kAuto;  // changes no pixel a front face wins (docs/rasterizer.md)
  FillRule fillRule = FillRule::kTopLeft;
  // Resolve a row chunk of several winners in one pass over its lanes (float; tile_gather.h)
  // rather than winner by winner. The same bits either way: off only to test that.
  bool gatheredResolve = true;
  // When every vertex lies inside the view volume, set up the triangles four at a time in
  // order without testing each one's outcodes (pipeline.cpp). The same bits either way: off
  // only to test that.
  bool wholeMeshBatches = true;
  // Records each block of triangles has in the frame's array of coverage set-ups before it
  // spills into a vector of its own (pipeline.h's SetupList); 0 = as many as the block has
  // triangles, so that only clipped triangles that split into several set-ups can make a block
  // spill. The same bits either way: set only to test the spill.
  std::size_t setupSlice = 0;
};

// Wall-clock time of each stage of the last frame (rasterizer.cpp's stages 1, 2, 3 and 4).
struct StageTimes {
  double transformMs = 0.0, setupMs = 0.0, binMs = 0.0, tilesMs = 0.0;
};

// A rasterizer that keeps its working memory (set-ups, bins) from frame to frame, as a real
// renderer does. render() writes tri.id, bary.b0..b2, depth.z, every mesh attribute
// (attr.<name>.<c>) and, with options.diagnostics, bound.bary, bound.depth, edge.dist and
// depth.tie (docs/numerics.md), plus the header attributes recording the settings (and
// rastercheck.cull: "back" when the frame culled back faces, else "none"); every
// pixel of every channel is written, so `target`'s planes are reused when its size is
// unchanged. No RGB preview. Throws usageError when subpixelBits does not fit the image size.
class Rasterizer {
 public:
  explicit Rasterizer(const RasterOptions& options);
  ~Rasterizer();
  Rasterizer(const Rasterizer&) = delete;
  Rasterizer& operator=(const Rasterizer&) = delete;

  void render(const Scene& scene, Framebuffer& target);
  const RasterOptions& options() const { return options_; }
  const StageTimes& stageTimes() const { return times_; }

 private:
  struct Workspace;
  RasterOptions options_;
  std::unique_ptr<Workspace> workspace_;
  StageTimes times_;
};

// The write-out floor: what writing a frame's planes costs with nothing else to do. Sets every
// value of every channel of `fb` to `value` the way the tile kernels write their output: 64x64
// tiles in parallel on options.threads, each tile row copied plane by plane from a staging row
// in L1 with the non-temporal stores of options.isa's kernels. No transform, set-up, coverage
// or resolve, so a frame that writes these planes cannot take less time (bench's
// store_floor_ms). Returns the pass's wall-clock time in milliseconds.
double writeOutPass(Framebuffer& fb, std::uint32_t value, const RasterOptions& options);

// One frame with a fresh Rasterizer, plus the RGB preview.
Framebuffer rasterize(const Scene& scene, const RasterOptions& options);

// Every (source triangle, pixel index) pair the coverage stage produces, before the depth
// test, in set-up order: the same transform, clipping, snapping and fill rule as rasterize.
// For tests against an exact oracle (tests/oracle/).
std::vector<std::pair<std::uint32_t, std::uint32_t>> coveredPixels(const Scene& scene,
                                                                   const RasterOptions& options);

}  // namespace rc
