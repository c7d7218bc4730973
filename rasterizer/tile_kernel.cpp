// The tile kernels compiled three times from one source: for the x86-64 baseline (SSE2), with
// the AVX2 target attribute, and with AVX-512 added to it (per-function targets, no -march
// flag, so the rest of the program runs on any x86-64). The build's -ffp-contract=off keeps
// every multiply and add separate (none is fused into an FMA), so all three give the same bits.
#include "rasterizer/tile_kernel.h"

#include <immintrin.h>

// See tile_kernel.h: vectors never cross a call boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc::kernel {

void renderTileSse2(const Input<float>& in, const Outputs& out, const TileJob& job) {
  renderTile<float, 16>(in, out, job);
}
void renderTileSse2(const Input<double>& in, const Outputs& out, const TileJob& job) {
  renderTile<double, 16>(in, out, job);
}

__attribute__((target("avx2"))) void renderTileAvx2(const Input<float>& in, const Outputs& out,
                                                    const TileJob& job) {
  renderTile<float, 32>(in, out, job);
}
__attribute__((target("avx2"))) void renderTileAvx2(const Input<double>& in, const Outputs& out,
                                                    const TileJob& job) {
  renderTile<double, 32>(in, out, job);
}

// The same kernel with AVX-512 enabled: GCC then keeps 8 lanes of int64 or double in one zmm
// register instead of two ymm ones. Same operations, same bits.
#define RC_TARGET_AVX512 __attribute__((target("avx2,avx512f,avx512vl,avx512dq,avx512bw")))
RC_TARGET_AVX512 void renderTileAvx512(const Input<float>& in, const Outputs& out, const TileJob& job) {
  renderTile<float, 64>(in, out, job);
}
RC_TARGET_AVX512 void renderTileAvx512(const Input<double>& in, const Outputs& out, const TileJob& job) {
  renderTile<double, 64>(in, out, job);
}
bool cpuHasKernelAvx512() {
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
         __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
}

void streamStagedRowSse2(std::uint32_t* const* planes, int count, const std::uint32_t* stage, std::size_t stride,
                         std::size_t rowStart, int n) {
  streamStagedRow<false>(planes, count, stage, stride, rowStart, n);
}
__attribute__((target("avx2"))) void streamStagedRowAvx2(std::uint32_t* const* planes, int count,
                                                         const std::uint32_t* stage, std::size_t stride,
                                                         std::size_t rowStart, int n) {
  streamStagedRow<true>(planes, count, stage, stride, rowStart, n);
}

namespace {

template <typename Real>
void collect(const CoverageSetup<Real>& s, int bits, const glm::dvec2 raster[3], std::vector<std::uint32_t>& pixels,
             int width) {
  const auto add = [&](int x, int y, int, const i32x8& mask) {
    for (int k = 0; k < kLanes; ++k) {
      if (mask[k]) pixels.push_back(std::uint32_t(y) * std::uint32_t(width) + std::uint32_t(x + k));
    }
  };
  if (bits != 0) {
    forEachCoveredChunk<true, 16>(s, bits, s.minX, s.minY, s.maxX, s.maxY, add);
  } else {
    coverRowsUnsnapped<16>(s, raster, s.minX, s.minY, s.maxX, s.maxY, add);
  }
}

}  // namespace

void coveredPixelsOf(const CoverageSetup<float>& s, int bits, const glm::dvec2 raster[3], std::vector<std::uint32_t>& pixels,
                     int width) {
  collect(s, bits, raster, pixels, width);
}
void coveredPixelsOf(const CoverageSetup<double>& s, int bits, const glm::dvec2 raster[3], std::vector<std::uint32_t>& pixels,
                     int width) {
  collect(s, bits, raster, pixels, width);
}

}  // namespace rc::kernel
