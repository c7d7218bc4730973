// Promotion: in a float frame, the pixels of a set-up whose own error bound says float learns
// next to nothing there (setup.h's kPromoteAbove) are resolved again in double. Everything else
// about them stays as the float frame made it: coverage (integer), the depth test (its float
// key plane), so the winners and ids are the same; their barycentrics, depth, edge distance,
// attributes and bounds become the double set-up's. The depth tie stays that of the float key
// that decided the test.
//
// Such set-ups are needles whose planes run to 1e7 and beyond (docs/rasterizer.md, "Known
// limits"): a tile holds none in the scalable scene, so a tile pays one comparison per winner.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/split_vectors.h"
#include "rasterizer/kernel_lanes.h"
#include "rasterizer/setup.h"
#include "rasterizer/tile_kernel.h"
#include "rasterizer/tile_resolve.h"

namespace rc::kernel {

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

inline bool promotes(const ShadeSetup<float>& s) {
  return !(s.baryBound <= kPromoteAbove && s.depthBound <= kPromoteAbove);
}

// A float tile's promoted winners, set up again in double, as an Input<double> that
// resolveLanes reads as it reads a double frame's: promoted winner k is set-up 0 of block k
// there, its coverage record a double copy of the float one and its block's sub-triangles the
// float frame's own (ClippedTriangle is the same record in either precision), so its clipMap
// stays the index it has. k stays below 4096, a tile's pixels: its name k << kBlockShift fits.
struct PromotedWinners {
  std::vector<std::uint32_t> positions;  // the winners' positions in the tile's bins
  std::vector<CoverageSetup<double>> coverage;
  std::vector<ShadeSetup<double>> shades;
  std::vector<const CoverageSetup<double>*> coverageBlocks;  // &coverage[k]
  std::vector<const ClippedTriangle*> clippedBlocks;         // the float frame's, block by block
  SetupContext context{};
  Input<double> in{};
};

// A float coverage record in double: the same box, snapped vertices, flags and source; its key
// plane's float values, exactly.
inline CoverageSetup<double> inDouble(const CoverageSetup<float>& c) {
  CoverageSetup<double> d{};
  d.minX = c.minX, d.minY = c.minY, d.maxX = c.maxX, d.maxY = c.maxY;
  for (int i = 0; i < 3; ++i) d.x[i] = c.x[i], d.y[i] = c.y[i];
  d.flags = c.flags;
  d.key0 = c.key0, d.keyX = c.keyX, d.keyY = c.keyY;
  d.source = c.source;
  return d;
}

// The promoted winners among a float tile's; false when there are none.
inline bool promoteWinners(const Input<float>& in, const TileJob& job, const std::uint32_t* winners,
                           const ShadeSetup<float>* shades, std::size_t count, PromotedWinners& p) {
  p.positions.clear(), p.coverage.clear(), p.shades.clear(), p.coverageBlocks.clear(), p.clippedBlocks.clear();
  for (std::size_t i = 0; i < count; ++i) {
    if (!promotes(shades[i])) continue;
    if (p.positions.empty()) {
      p.context = *in.context;
      p.context.unitRoundoff = 0x1p-53;
    }
    const std::uint32_t name = job.bins[winners[i]];
    p.positions.push_back(winners[i]);
    p.coverage.push_back(inDouble(in.coverage[name >> kBlockShift][name & kLocalMask]));
    p.clippedBlocks.push_back(in.clipped[name >> kBlockShift]);
    shadeSetupOf(in, name, p.context, p.coverage.back(), p.shades.emplace_back());
  }
  if (p.positions.empty()) return false;
  for (const CoverageSetup<double>& c : p.coverage) p.coverageBlocks.push_back(&c);
  // The float key decided the depth test, so the depth tie is still its: the float tieScale.
  p.in = {p.coverageBlocks.data(), p.clippedBlocks.data(), in.triangles,  in.vertexClip, in.vertexRaster,
          &p.context,              in.subpixelBits,        in.perspective, false,         double(in.tieScale)};
  return true;
}

// The lanes of a row chunk whose winner is promoted, resolved in double over what the float
// resolve staged for them: id, b0..b2, depth, then with diagnostics the two bounds, the edge
// distance and the depth tie, each a staged row `stride` apart from `at`, then the attributes'
// rows from `attributes`. Returns how many lanes it resolved.
template <std::size_t kWidth>
RC_KERNEL_INLINE int promoteChunk(const PromotedWinners& p, const Outputs& out, const u32x8& w, const i32x8& valid,
                                   int x, int y, bool diagnostics, std::uint32_t* at, std::size_t stride,
                                   float* attributes) {
  constexpr bool kAvx2 = kWidth >= 32;
  int resolved = 0;
  for (std::size_t k = 0; k < p.positions.size(); ++k) {
    const i32x8 mine = valid & split::equal<kWidth>(w, split::splat<kWidth, u32x8>(p.positions[k]));
    if (!anyOf<kAvx2>(mine)) continue;
    resolved += __builtin_popcount(laneBits<kAvx2>(mine));
    Resolved r{};
    const ShadeSetup<double>& s = p.shades[k];
    resolveLanes<true, kWidth>(p.in, out, std::uint32_t(k) << kBlockShift, s, x, y, r, attributes, stride, mine);
    const auto blend = [&](int plane, const f32x8& value) __attribute__((always_inline)) {
      float* row = reinterpret_cast<float*>(at + std::size_t(plane) * stride);
      store(row, split::select<kWidth>(mine, value, load<f32x8>(row)));
    };
    for (int i = 0; i < 3; ++i) blend(1 + i, r.bary[i]);
    blend(4, r.depth);
    if (diagnostics) {
      blend(5, split::splat<kWidth, f32x8>(s.baryBound));
      blend(6, split::splat<kWidth, f32x8>(s.depthBound));
      blend(7, r.edgeDistance);
      blend(8, r.depthTie);
    }
  }
  return resolved;
}

#pragma GCC diagnostic pop

}  // namespace rc::kernel
