// The tile kernels compiled twice from one source: once for the x86-64 baseline (SSE2) and
// once with the AVX2 target attribute (per-function target, no -march flag, so the rest of
// the program runs on any x86-64). "avx2" does not enable FMA, so no multiply-add is ever
// contracted and both produce the same bits.
#include "rasterizer/tile_kernel.h"

#include <immintrin.h>

// See tile_kernel.h: vectors never cross a call boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc::kernel {

void renderTileSse2(const Input<float>& in, const Outputs& out, const TileJob& job) {
  renderTile<float, false>(in, out, job);
}
void renderTileSse2(const Input<double>& in, const Outputs& out, const TileJob& job) {
  renderTile<double, false>(in, out, job);
}

__attribute__((target("avx2"))) void renderTileAvx2(const Input<float>& in, const Outputs& out,
                                                    const TileJob& job) {
  renderTile<float, true>(in, out, job);
}
__attribute__((target("avx2"))) void renderTileAvx2(const Input<double>& in, const Outputs& out,
                                                    const TileJob& job) {
  renderTile<double, true>(in, out, job);
}

__attribute__((target("avx2"))) void streamRowAvx2(std::uint32_t* to, const std::uint32_t* from, int n) {
  int k = 0;
  if ((reinterpret_cast<std::uintptr_t>(to) & 31u) == 0) {
    for (; k + 8 <= n; k += 8) {
      _mm256_stream_si256(reinterpret_cast<__m256i*>(to + k),
                          _mm256_loadu_si256(reinterpret_cast<const __m256i*>(from + k)));
    }
  }
  streamRow(to + k, from + k, n - k);
}

namespace {

template <typename Real>
void collect(const CoverageSetup<Real>& s, int bits, std::vector<std::uint32_t>& pixels, int width) {
  forEachCoveredChunk(s, bits, s.minX, s.minY, s.maxX, s.maxY, [&](int x, int y, const i32x8& mask) {
    for (int k = 0; k < kLanes; ++k) {
      if (mask[k]) pixels.push_back(std::uint32_t(y) * std::uint32_t(width) + std::uint32_t(x + k));
    }
  });
}

}  // namespace

void coveredPixelsOf(const CoverageSetup<float>& s, int bits, std::vector<std::uint32_t>& pixels, int width) {
  collect(s, bits, pixels, width);
}
void coveredPixelsOf(const CoverageSetup<double>& s, int bits, std::vector<std::uint32_t>& pixels, int width) {
  collect(s, bits, pixels, width);
}

}  // namespace rc::kernel
