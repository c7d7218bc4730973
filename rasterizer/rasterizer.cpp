// The rasterizer pipeline. Stages, each in its own loop so that per-triangle work never
// enters the pixel loops (1 to 3 in pipeline.cpp, 4 here):
//   1. transform: world -> clip, in double through the camera, in parallel;
//   2. per block of triangles, in parallel: clip + set-up in double (only the per-pixel
//      coefficients are rounded to Real, setup.h), then the block's count per 64x64 tile;
//   3. a prefix sum over (tile, block) places every block's list for every tile, and the
//      blocks fill them in parallel: each tile's list is in block order, so triangle order;
//   4. per tile, in parallel: the SIMD kernels of tile_kernel.h (coverage + depth test into a
//      tile-local visibility buffer, then resolve for each pixel's winner).
// Tiles own disjoint pixels and visit set-ups in triangle order, and blocks are cut by
// triangle count alone, so the output does not depend on the thread count; depth ties go to
// the lower triangle index. All working memory lives in the Rasterizer and is reused.
#include "rasterizer/rasterizer.h"

#include <immintrin.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

#include "core/channels.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/preview.h"
#include "rasterizer/frame_setups.h"
#include "rasterizer/pipeline.h"
#include "rasterizer/tile_kernel.h"

namespace rc {

const char* interpolationName(Interpolation mode) {
  return mode == Interpolation::kPerspective ? "perspective" : "affine";
}
const char* precisionName(Precision precision) {
  return precision == Precision::kFloat ? "float" : "double";
}
const char* depthMappingName(DepthMapping mapping) {
  return mapping == DepthMapping::kInverseW ? "inverse-w" : "standard";
}
const char* fillRuleName(FillRule rule) {
  switch (rule) {
    case FillRule::kInclusive: return "inclusive";
    case FillRule::kExclusive: return "exclusive";
    default: return "top-left";
  }
}
std::string subpixelBitsName(int bits) { return bits == 0 ? "none" : std::to_string(bits); }
const char* kernelIsaName(KernelIsa isa) {
  switch (isa) {
    case KernelIsa::kSse2: return "sse2";
    case KernelIsa::kAvx2: return "avx2";
    case KernelIsa::kAvx512: return "avx512";
    default: return "auto";
  }
}

KernelIsa resolveKernelIsa(KernelIsa isa) {
  const bool avx2 = __builtin_cpu_supports("avx2");
  const bool avx512 = avx2 && kernel::cpuHasKernelAvx512();
  if (isa == KernelIsa::kAuto) return avx512 ? KernelIsa::kAvx512 : avx2 ? KernelIsa::kAvx2 : KernelIsa::kSse2;
  if (isa == KernelIsa::kAvx2 && !avx2) throw usageError("this CPU lacks AVX2; choose --raster-isa sse2 or auto");
  if (isa == KernelIsa::kAvx512 && !avx512) {
    throw usageError("this CPU lacks AVX-512 (F, VL, DQ and BW); choose --raster-isa avx2, sse2 or auto");
  }
  return isa;
}

namespace {

using kernel::kTileSize;

kernel::Outputs outputPlanes(Framebuffer& fb, const Mesh& mesh, bool diagnostics) {
  std::vector<std::string> names = {channels::kTriangleId, channels::kBary[0], channels::kBary[1],
                                    channels::kBary[2], channels::kDepth};
  if (diagnostics) {
    names.insert(names.end(), {channels::kBaryBound, channels::kDepthBound, channels::kEdgeDistance,
                               channels::kDepthTie});
  }
  for (const Attribute& a : mesh.attributes) {
    for (int c = 0; c < a.components; ++c) names.push_back(channels::attributeChannel(a.name, c));
  }
  fb.recycle(fb.width(), fb.height(), names);
  kernel::Outputs out{};
  out.width = fb.width();
  out.id = fb.reuseUint(channels::kTriangleId);
  for (int i = 0; i < 3; ++i) out.bary[i] = fb.reuseFloat(channels::kBary[i]);
  out.depth = fb.reuseFloat(channels::kDepth);
  if (diagnostics) {
    out.baryBound = fb.reuseFloat(channels::kBaryBound);
    out.depthBound = fb.reuseFloat(channels::kDepthBound);
    out.edgeDistance = fb.reuseFloat(channels::kEdgeDistance);
    out.depthTie = fb.reuseFloat(channels::kDepthTie);
  }
  for (const Attribute& a : mesh.attributes) {
    kernel::Outputs::Attribute attribute{a.values.data(), a.components, {}};
    for (int c = 0; c < a.components; ++c) attribute.out[c] = fb.reuseFloat(channels::attributeChannel(a.name, c));
    out.attributes.push_back(attribute);
    out.attributeComponents += a.components;
  }
  return out;
}

struct FrameFacts {
  bool culled;      // the frame culled back faces
  double edgeBand;  // pixels (channels::header::kEdgeBand)
  std::uint64_t promotedPixels;  // a float frame's pixels resolved in double (tile_promote.h)
};

template <typename Real>
FrameFacts renderFrame(const Scene& scene, const RasterOptions& options, Frame<Real>& frame, Framebuffer& fb,
                 StageTimes& times) {
  long long t0 = nowNanoseconds();
  Pipeline<Real> p(scene, options, frame);
  p.transform();
  times.transformMs = millisecondsSince(t0);
  p.setupAndBin(times);
  t0 = nowNanoseconds();

  if (fb.width() != p.width || fb.height() != p.height) fb.recycle(p.width, p.height, {});
  kernel::Outputs out = outputPlanes(fb, scene.mesh, options.diagnostics);
  std::atomic<std::uint64_t> promotedPixels{0};
  if constexpr (sizeof(Real) == 4) out.promotedPixels = &promotedPixels;
  kernel::Input<Real> in{};
  in.coverage = frame.blockCoverage.data();
  in.clipped = frame.blockClipped.data();
  in.vertexClip = frame.clip.data();
  in.vertexRaster = frame.raster.data();
  in.context = &p.context;
  in.triangles = scene.mesh.triangles.data();
  in.subpixelBits = options.subpixelBits;
  in.perspective = options.interpolation == Interpolation::kPerspective;
  in.gatheredResolve = options.gatheredResolve;
  // depthTieAt's 5 u (|key0| + |keyX dx| + |keyY dy|) w / keyB, evaluated in Real: its own
  // handful of roundings (under 8 u relative) is covered by the factor 1 + 2^-16.
  in.tieScale = Real(5.0 * p.context.unitRoundoff / p.context.keyB * (1.0 + 0x1p-16));
  const KernelIsa isa = p.isa;
  parallelForQueues(frame.tileQueues, [&](int tile, int) {
    const int tx = tile % p.tilesX, ty = tile / p.tilesX;
    kernel::TileJob job{frame.binned.data() + frame.binStart[tile], frame.binStart[tile + 1] - frame.binStart[tile],
                        tx * kTileSize, ty * kTileSize, std::min(p.width, (tx + 1) * kTileSize) - 1,
                        std::min(p.height, (ty + 1) * kTileSize) - 1};
    if (isa == KernelIsa::kAvx512) {
      kernel::renderTileAvx512(in, out, job);
    } else if (isa == KernelIsa::kAvx2) {
      kernel::renderTileAvx2(in, out, job);
    } else {
      kernel::renderTileSse2(in, out, job);
    }
  });
  times.tilesMs = millisecondsSince(t0);
  return {p.context.cullBackFaces, p.edgeBand(), promotedPixels.load()};
}

void checkSubpixelBits(const RasterOptions& options) {
  if (options.subpixelBits < 0 || options.subpixelBits > 16) {
    throw usageError("--subpixel-bits must be 1..16 or none (0), got " + std::to_string(options.subpixelBits));
  }
}

}  // namespace

template <typename Real>
void forEachSetup(const Scene& scene, const RasterOptions& options, const SetupVisitor<Real>& visit) {
  checkSubpixelBits(options);
  Frame<Real> frame;
  Pipeline<Real> p(scene, options, frame);
  p.transform();
  StageTimes times;
  p.setupAndBin(times);
  for (const SetupBlock<Real>& block : frame.blocks) {
    for (std::size_t i = 0; i < block.coverage.size(); ++i) {
      const CoverageSetup<Real>& c = block.coverage[i];
      VisitedSetup<Real> v{c, {}, {}, 0u, p.context};
      if (c.source.clipped < 0) {
        const glm::uvec3 tri = scene.mesh.triangles[c.source.triangle];
        for (int k = 0; k < 3; ++k) v.raster[k] = frame.raster[tri[k]], v.clip[k] = frame.clip[tri[k]];
      } else {
        const ClippedTriangle& t = block.clipped[std::size_t(c.source.clipped)];
        for (int k = 0; k < 3; ++k) v.raster[k] = t.raster[k], v.clip[k] = t.clip[k];
        v.innerEdges = t.innerEdges;
      }
      visit(v);
    }
  }
}
template void forEachSetup<float>(const Scene&, const RasterOptions&, const SetupVisitor<float>&);
template void forEachSetup<double>(const Scene&, const RasterOptions&, const SetupVisitor<double>&);

namespace {

template <typename Real>
std::vector<std::pair<std::uint32_t, std::uint32_t>> coveredPixelsAs(const Scene& scene, const RasterOptions& options) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::vector<std::uint32_t> pixels;
  const int width = scene.camera.width();
  forEachSetup<Real>(scene, options, [&](const VisitedSetup<Real>& v) {
    pixels.clear();
    kernel::coveredPixelsOf(v.coverage, options.subpixelBits, v.raster, pixels, width);
    for (std::uint32_t pixel : pixels) pairs.emplace_back(v.coverage.source.triangle, pixel);
  });
  return pairs;
}

}  // namespace

struct Rasterizer::Workspace {
  Frame<float> single;
  Frame<double> twice;
};

Rasterizer::Rasterizer(const RasterOptions& options) : options_(options), workspace_(std::make_unique<Workspace>()) {
  checkSubpixelBits(options_);
  resolveKernelIsa(options_.isa);
}

Rasterizer::~Rasterizer() = default;

void Rasterizer::render(const Scene& scene, Framebuffer& target) {
  const FrameFacts facts = options_.precision == Precision::kFloat
                               ? renderFrame(scene, options_, workspace_->single, target, times_)
                               : renderFrame(scene, options_, workspace_->twice, target, times_);
  target.attributes[channels::header::kRenderer] = "raster";
  target.attributes[channels::header::kMode] = interpolationName(options_.interpolation);
  target.attributes[channels::header::kPrecision] = precisionName(options_.precision);
  target.attributes["rastercheck.subpixelBits"] = subpixelBitsName(options_.subpixelBits);
  target.attributes["rastercheck.depthMapping"] = depthMappingName(options_.depthMapping);
  target.attributes["rastercheck.kernelIsa"] = kernelIsaName(resolveKernelIsa(options_.isa));
  target.attributes["rastercheck.cull"] = facts.culled ? "back" : "none";
  target.attributes["rastercheck.fillRule"] = fillRuleName(options_.fillRule);
  char band[32];
  std::snprintf(band, sizeof band, "%.17g", facts.edgeBand);  // exact: compare reads it back
  target.attributes[channels::header::kEdgeBand] = band;
  if (options_.precision == Precision::kFloat) {
    target.attributes[channels::header::kPromotedPixels] = std::to_string(facts.promotedPixels);
  }
  target.attributes[channels::header::kScene] = scene.name;
  target.attributes[channels::header::kCamera] = scene.camera.describe();
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> coveredPixels(const Scene& scene, const RasterOptions& options) {
  checkSubpixelBits(options);
  return options.precision == Precision::kFloat ? coveredPixelsAs<float>(scene, options)
                                                : coveredPixelsAs<double>(scene, options);
}

double writeOutPass(Framebuffer& fb, std::uint32_t value, const RasterOptions& options) {
  const KernelIsa isa = resolveKernelIsa(options.isa);
  std::vector<std::uint32_t*> planes;
  for (const Channel& c : fb.channels()) {
    Channel& own = *fb.find(c.name);
    planes.push_back(own.type == ChannelType::kFloat ? reinterpret_cast<std::uint32_t*>(own.floats.data())
                                                     : own.uints.data());
  }
  const int count = int(planes.size()), width = fb.width(), height = fb.height();
  const int tilesX = (width + kTileSize - 1) / kTileSize, tilesY = (height + kTileSize - 1) / kTileSize;
  const long long start = nowNanoseconds();
  parallelFor(tilesX * tilesY, options.threads, [&](int tile) {
    const int x0 = tile % tilesX * kTileSize, y0 = tile / tilesX * kTileSize;
    const int n = std::min(width, x0 + kTileSize) - x0;
    alignas(64) std::uint32_t stage[kTileSize];
    std::fill(stage, stage + kTileSize, value);
    for (int y = y0; y < std::min(height, y0 + kTileSize); ++y) {
      const std::size_t rowStart = std::size_t(y) * std::size_t(width) + std::size_t(x0);
      if (isa == KernelIsa::kSse2) {
        kernel::streamStagedRowSse2(planes.data(), count, stage, 0, rowStart, n);
      } else {
        kernel::streamStagedRowAvx2(planes.data(), count, stage, 0, rowStart, n);
      }
    }
    _mm_sfence();
  });
  return millisecondsSince(start);
}

Framebuffer rasterize(const Scene& scene, const RasterOptions& options) {
  Framebuffer fb;
  Rasterizer(options).render(scene, fb);
  addPreview(fb);
  return fb;
}

}  // namespace rc
