// Google Benchmark microbenchmarks of the rasterizer's kernels: triangle set-up, exact coverage,
// and the tile kernel dominated by coverage + depth test or by interpolation (resolve), in
// both precisions and on both instruction sets, plus whole frames of the scalable scene.
// Figures only: nothing here passes or fails. Run: build/bench/kernels_bench
// (docs/rasterizer.md lists what each measures).
#include <benchmark/benchmark.h>

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "rasterizer/rasterizer.h"
#include "rasterizer/setup.h"
#include "rasterizer/tile_coverage.h"
#include "rasterizer/tile_kernel.h"
#include "scenes/registry.h"

#pragma GCC diagnostic ignored "-Wpsabi"  // the kernels' vector types in inline helpers

namespace rc {
namespace {

constexpr int kWidth = 1920, kHeight = 1080, kBits = 8;

SetupContext context(double unitRoundoff) {
  SetupContext c{};
  c.width = kWidth, c.height = kHeight, c.subpixelBits = kBits;
  c.unitRoundoff = unitRoundoff;
  c.clipError = 1e-15;
  c.keyA = 0.0, c.keyB = 1.0;
  return c;
}

// Triangles of about `size` pixels across at random places and depths, as clip-space vertices
// with their raster positions (w = depth, NDC spanning the image).
struct Triangles {
  std::vector<glm::dvec4> clip;
  std::vector<glm::dvec2> raster;
};

Triangles randomTriangles(int count, double size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> px(size, kWidth - size), py(size, kHeight - size), offset(-size, size),
      depth(1.0, 20.0);
  Triangles t;
  for (int i = 0; i < count; ++i) {
    const double cx = px(rng), cy = py(rng);
    for (int k = 0; k < 3; ++k) {
      const glm::dvec2 r(cx + offset(rng), cy + offset(rng));
      const double w = depth(rng);
      t.raster.push_back(r);
      t.clip.push_back({(2.0 * r.x / kWidth - 1.0) * w, (1.0 - 2.0 * r.y / kHeight) * w, 0.0, w});
    }
  }
  return t;
}

template <typename Real>
void BM_Setup(benchmark::State& state) {
  const Triangles t = randomTriangles(4096, double(state.range(0)), 1);
  const SetupContext ctx = context(sizeof(Real) == 4 ? 0x1p-24 : 0x1p-53);
  CoverageSetup<Real> c;
  ShadeSetup<Real> s;
  for (auto _ : state) {
    for (int i = 0; i < 4096; ++i) {
      benchmark::DoNotOptimize(setupTriangle(&t.clip[3 * i], &t.raster[3 * i], 0u, false, ctx, c, s));
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 4096);
  state.SetLabel("triangles of ~" + std::to_string(state.range(0)) + " px");
}
BENCHMARK(BM_Setup<float>)->Arg(2)->Arg(20)->Arg(200);
BENCHMARK(BM_Setup<double>)->Arg(2)->Arg(20)->Arg(200);

// Exact coverage alone (the kernels' int32 or int64 lanes, stepping in vectors as the AVX2 and
// AVX-512 kernels do, here compiled for the baseline) of one triangle's box.
template <typename Lane>
void BM_Coverage(benchmark::State& state) {
  const int size = int(state.range(0));
  const std::int64_t one = 1 << kBits;
  const std::int64_t x[3] = {0, size * one, size * one / 3}, y[3] = {0, size * one / 4, size * one};
  EdgeFunctions e{};
  makeEdgeFunctions(x, y, e);
  long long covered = 0;
  for (auto _ : state) {
    kernel::coverRows<Lane, true, 16>(e, kBits, 0, 0, size - 1, size - 1, [&](int, int, int, const kernel::i32x8& mask) {
      covered += kernel::any(mask);
    });
    benchmark::DoNotOptimize(covered);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(size) * size);  // box pixels
}
BENCHMARK(BM_Coverage<std::int32_t>)->Arg(64)->Arg(200);
BENCHMARK(BM_Coverage<std::int64_t>)->Arg(64)->Arg(200);

// One 64x64 tile through the dispatched kernel: many small triangles (coverage and depth
// test dominate) or one triangle covering it (interpolation dominates), with an attribute.
template <typename Real>
struct TileFixture {
  SetupContext ctx;
  std::vector<CoverageSetup<Real>> coverage;
  std::vector<std::uint32_t> bins;
  std::vector<glm::uvec3> triangles;
  std::vector<glm::dvec4> vertexClip;
  std::vector<glm::dvec2> vertexRaster;
  std::vector<float> uv;
  std::vector<float> planes;
  kernel::Outputs out{};
  const CoverageSetup<Real>* coverageBlock[1];
  const ClippedTriangle* clippedBlock[1] = {nullptr};
  kernel::Input<Real> in{};

  TileFixture(int count, double size, bool perspective, bool diagnostics)
      : ctx(context(sizeof(Real) == 4 ? 0x1p-24 : 0x1p-53)) {
    const Triangles t = count == 1 ? oneBigTriangle() : randomTriangles(count, size, 2);
    for (int i = 0; i < count; ++i) {
      // Squeeze every triangle into the first tile.
      glm::dvec2 r[3];
      glm::dvec4 c[3];
      for (int k = 0; k < 3; ++k) {
        r[k] = count == 1 ? t.raster[3 * i + k] : glm::dvec2(std::fmod(t.raster[3 * i + k].x, 64.0), std::fmod(t.raster[3 * i + k].y, 64.0));
        const double w = t.clip[3 * i + k].w;
        c[k] = {(2.0 * r[k].x / kWidth - 1.0) * w, (1.0 - 2.0 * r[k].y / kHeight) * w, 0.0, w};
      }
      CoverageSetup<Real> cs;
      if (!setupCoverage(c, r, ctx, cs)) continue;
      bins.push_back(std::uint32_t(coverage.size()));
      cs.source = {std::uint32_t(triangles.size()), -1};
      coverage.push_back(cs);
      const auto first = std::uint32_t(vertexClip.size());
      triangles.push_back({first, first + 1, first + 2});
      vertexClip.insert(vertexClip.end(), c, c + 3);
      vertexRaster.insert(vertexRaster.end(), r, r + 3);
    }
    for (std::size_t v = 0; v < vertexClip.size(); v += 3) uv.insert(uv.end(), {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f});
    planes.assign(std::size_t(14) * kWidth * 64, 0.0f);
    out.width = kWidth;
    float* p = planes.data();
    const auto next = [&] { float* q = p; p += std::size_t(kWidth) * 64; return q; };
    out.id = reinterpret_cast<std::uint32_t*>(next());
    for (float*& b : out.bary) b = next();
    out.depth = next();
    if (diagnostics) out.baryBound = next(), out.depthBound = next(), out.edgeDistance = next(), out.depthTie = next();
    out.attributes.push_back({uv.data(), 2, {next(), next()}});
    out.attributeComponents = 2;
    coverageBlock[0] = coverage.data();
    in.coverage = coverageBlock;
    in.clipped = clippedBlock;
    in.triangles = triangles.data();
    in.vertexClip = vertexClip.data();
    in.vertexRaster = vertexRaster.data();
    in.context = &ctx;
    in.subpixelBits = kBits;
    in.perspective = perspective;
    in.gatheredResolve = true;
    in.tieScale = Real(5.0 * ctx.unitRoundoff);
  }

  static Triangles oneBigTriangle() {
    Triangles t;
    const glm::dvec2 r[3] = {{-10.0, -10.0}, {200.0, -5.0}, {-5.0, 200.0}};
    const double w[3] = {2.0, 5.0, 9.0};
    for (int k = 0; k < 3; ++k) {
      t.raster.push_back(r[k]);
      t.clip.push_back({(2.0 * r[k].x / kWidth - 1.0) * w[k], (1.0 - 2.0 * r[k].y / kHeight) * w[k], 0.0, w[k]});
    }
    return t;
  }
};

template <typename Real, KernelIsa kIsa>
void BM_Tile(benchmark::State& state) {
  try {
    resolveKernelIsa(kIsa);
  } catch (const std::exception&) {
    state.SkipWithError((std::string("no ") + kernelIsaName(kIsa) + " on this CPU").c_str());
    return;
  }
  const int count = int(state.range(0));
  const bool perspective = state.range(1) != 0;
  TileFixture<Real> f(count, 3.0, perspective, true);
  const kernel::TileJob job{f.bins.data(), f.bins.size(), 0, 0, 63, 63};
  for (auto _ : state) {
    if (kIsa == KernelIsa::kAvx512) {
      kernel::renderTileAvx512(f.in, f.out, job);
    } else if (kIsa == KernelIsa::kAvx2) {
      kernel::renderTileAvx2(f.in, f.out, job);
    } else {
      kernel::renderTileSse2(f.in, f.out, job);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 64 * 64);  // pixels
  state.SetLabel(std::string(count == 1 ? "one triangle (interpolation)" : "small triangles (coverage)") +
                 (perspective ? ", perspective" : ", affine"));
}
// Args: triangles in the tile (1: one covering it), perspective (1) or affine (0).
#define RC_TILE_ARGS ->Args({1, 1})->Args({1, 0})->Args({2000, 1})
BENCHMARK(BM_Tile<float, KernelIsa::kSse2>) RC_TILE_ARGS;
BENCHMARK(BM_Tile<float, KernelIsa::kAvx2>) RC_TILE_ARGS;
BENCHMARK(BM_Tile<float, KernelIsa::kAvx512>) RC_TILE_ARGS;
BENCHMARK(BM_Tile<double, KernelIsa::kSse2>) RC_TILE_ARGS;
BENCHMARK(BM_Tile<double, KernelIsa::kAvx2>) RC_TILE_ARGS;
BENCHMARK(BM_Tile<double, KernelIsa::kAvx512>) RC_TILE_ARGS;

// Whole frames of the scalable scene at 1920x1080 with the default settings, on 1 or 2 threads
// (the second argument), with the last frame's per-stage times.
void BM_Frame(benchmark::State& state) {
  const Scene scene = makeBuiltinScene("blob:tris=" + std::to_string(state.range(0)));
  RasterOptions options;
  options.threads = int(state.range(1));
  Rasterizer rasterizer{options};
  Framebuffer fb;
  rasterizer.render(scene, fb);
  for (auto _ : state) rasterizer.render(scene, fb);
  state.SetItemsProcessed(state.iterations() * std::int64_t(scene.mesh.triangleCount()));
  const StageTimes& t = rasterizer.stageTimes();
  state.counters["transform_ms"] = t.transformMs;
  state.counters["setup_ms"] = t.setupMs;
  state.counters["bin_ms"] = t.binMs;
  state.counters["tiles_ms"] = t.tilesMs;
}
BENCHMARK(BM_Frame)
    ->ArgsProduct({{1000, 100000, 1000000}, {2, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rc

BENCHMARK_MAIN();
