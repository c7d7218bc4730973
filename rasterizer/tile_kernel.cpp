// renderTile, one tile from its bins to its rows of every output plane (coverage and depth
// test, the winners' set-ups, resolve, copy-out), compiled three times from one source: for
// the x86-64 baseline (SSE2), with the AVX2 target attribute, and with AVX-512 added to it
// (per-function targets, no -march flag, so the rest of the program runs on any x86-64). The build's -ffp-contract=off keeps
// every multiply and add separate (none is fused into an FMA), so all three give the same bits.
#include "rasterizer/tile_kernel.h"

#include <immintrin.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/channels.h"
#include "core/line_allocator.h"
#include "core/split_vectors.h"
#include "core/stream_row.h"
#include "rasterizer/kernel_lanes.h"
#include "rasterizer/tile_coverage.h"
#include "rasterizer/tile_gather.h"
#include "rasterizer/tile_promote.h"
#include "rasterizer/tile_resolve.h"

// See kernel_lanes.h: vectors never cross a call boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc::kernel {

// Resolve writes each tile row into a small staging row per plane (in L1), then copies each
// plane's row out in one go (core/stream_row.h); renderTile ends with a store fence.
// streamStagedRow is that copy-out: plane p's staged row, stage + p * stride, to planes[p] +
// rowStart (null planes are not written), n values each. Whole tile rows take the AVX2 build's
// inline 32-byte stores (streamRowOf): frames at 1k triangles 5 to 8% faster than with a call
// per row and plane (docs/rasterizer-speed.md, "The memory floor").
template <bool kAvx2>
RC_KERNEL_INLINE void streamStagedRow(std::uint32_t* const* planes, int count, const std::uint32_t* stage,
                                      std::size_t stride, std::size_t rowStart, int n) {
  for (int p = 0; p < count; ++p) {
    if (!planes[p]) continue;
    streamRowOf<kAvx2>(planes[p] + rowStart, stage + std::size_t(p) * stride, n);
  }
}
// kWidth, in every function below: the widest vector register the caller's target has, in
// bytes (16 SSE2, 32 AVX2, 64 AVX-512), for the comparisons and selects (core/split_vectors.h).
// Each is always inlined into renderTile, so the phases share its registers and stack.

// A tile's visibility buffer: each pixel's winner, as its position in job.bins (kEmpty where
// none; positions stay below kMaxBlocks 2^20, pipeline.cpp, so never kEmpty), and the
// winner's depth key (larger is nearer). kPixels leaves a chunk of slack past the end, and the
// rows coverRows may run past a box at the tile's bottom.
template <typename Real>
struct Visibility {
  static constexpr int kPixels = kTileSize * kTileSize + (kFixedRows - 1) * kTileSize + kLanes;
  alignas(64) std::uint32_t winner[kPixels];
  alignas(64) Real nearest[kPixels];
};

// Coverage and depth test of every set-up binned to the tile, in triangle order; a tie keeps
// the earlier triangle. Made twice, with and without snapping (Unsnapped: std::true_type), so
// that the default's loop holds no test of it.
template <typename Real, std::size_t kWidth, typename Unsnapped>
RC_KERNEL_INLINE void coverTile(const Input<Real>& in, const TileJob& job, Visibility<Real>& vis, Unsnapped) {
  constexpr bool kAvx2 = kWidth >= 32;
  using V = typename Lanes<Real>::V;
  using M = typename Lanes<Real>::M;
  for (std::size_t n = 0; n < job.count; ++n) {
    const std::uint32_t name = job.bins[n];
    if (n + kPrefetchAhead < job.count) {
      const std::uint32_t ahead = job.bins[n + kPrefetchAhead];
      __builtin_prefetch(&in.coverage[ahead >> kBlockShift][ahead & kLocalMask]);
    }
    const CoverageSetup<Real>& c = in.coverage[name >> kBlockShift][name & kLocalMask];
    const int xa = std::max(job.x0, c.minX), ya = std::max(job.y0, c.minY);
    const int xb = std::min(job.x1, c.maxX), yb = std::min(job.y1, c.maxY);
    // Once per set-up, in locals: the compiler cannot tell that the stores below miss c.
    const int anchorX = c.anchorX(), anchorY = c.anchorY();
    const Real key0 = c.key0, keyX = c.keyX, keyY = c.keyY;
    const V dx0 = Real(xa - anchorX) + iota<Real>();
    // The key key0 + keyX dx + keyY dy sums its first two terms first, and they are the same
    // for every row: the AVX2 and AVX-512 builds take them once per chunk column (dx: small
    // integers, exact). The SSE2 build measured 6% slower that way, and makes them per chunk.
    V keyOfColumn[kTileSize / kLanes];
    if constexpr (kAvx2) {
      V dx = dx0;
      for (int column = 0; column <= (xb - xa) / kLanes; ++column, dx += Real(kLanes)) {
        keyOfColumn[column] = key0 + keyX * dx;
      }
    }
    const u32x8 position = split::splat<kWidth, u32x8>(std::uint32_t(n));  // built once, not per chunk
    const auto depthTest = [&](int x, int y, int column, const i32x8& mask) {
      V z;
      if constexpr (kAvx2) {
        z = keyOfColumn[column] + keyY * Real(y - anchorY);
      } else {
        z = key0 + keyX * (dx0 + Real(x - xa)) + keyY * Real(y - anchorY);
      }
      Real* nearestAt = vis.nearest + (y - job.y0) * kTileSize + (x - job.x0);
      std::uint32_t* winnerAt = vis.winner + (y - job.y0) * kTileSize + (x - job.x0);
      const V old = load<V>(nearestAt);
      const M nearer = maskAs<M>(mask) & split::greater<kWidth>(z, old);
      const i32x8 update = mask32(nearer);
      // Branch-free: a chunk that changes nothing stores what it loaded.
      store(nearestAt, split::select<kWidth>(nearer, z, old));
      const u32x8 w = load<u32x8>(winnerAt);
      store(winnerAt, split::select<kWidth>(update, position, w));
    };
    if constexpr (!Unsnapped::value) {
      forEachCoveredChunk<kAvx2, kWidth>(c, in.subpixelBits, xa, ya, xb, yb, depthTest);
    } else {
      glm::dvec2 v[3];
      rasterOfSetup(c, in.triangles, in.vertexRaster, in.clipped[name >> kBlockShift], v);
      coverRowsUnsnapped<kWidth, kAvx2>(c, v, xa, ya, xb, yb, depthTest);
    }
  }
}

// The winners' set-ups of a tile: shades[slot[n]] is the resolve half (setupShade) of the
// set-up at job.bins[n], for each n that won a pixel of the tile.
template <typename Real>
struct TileShades {
  const std::int32_t* slot;
  const std::uint32_t* winners;  // positions in job.bins, ascending
  std::size_t count;
  const ShadeSetup<Real>* shades;
  const ShadeSetup<Real>& of(std::uint32_t n) const { return shades[std::size_t(slot[n])]; }
};

// The resolve half of the set-up (setupShade) for every set-up that wins a pixel of this tile,
// in bin order; set-ups that win nothing in the frame never get one. The arrays live per
// thread, reused from tile to tile of a frame.
template <typename Real, std::size_t kWidth>
RC_KERNEL_INLINE TileShades<Real> shadeWinners(const Input<Real>& in, const TileJob& job, const std::uint32_t* winner) {
  constexpr bool kAvx2 = kWidth >= 32;
  thread_local std::vector<std::int32_t> slot;
  thread_local std::vector<std::uint32_t> winners;
  thread_local std::vector<ShadeSetup<Real>> shades;
  // Marking: a chunk that is all the last chunk's final winner is skipped; the others mark
  // all eight lanes without a branch, an empty pixel (kEmpty) marking the sink slot[job.count].
  slot.assign(job.count + 1, -1);
  const u32x8 sink = split::splat<kWidth, u32x8>(std::uint32_t(job.count));
  std::uint32_t last = kEmpty;
  for (int i = 0; i < kTileSize * kTileSize; i += kLanes) {
    const u32x8 w = load<u32x8>(winner + i);
    if (!anyOf<kAvx2>(split::notEqual<kWidth>(w, last))) continue;
    const u32x8 marked = split::select<kWidth>(split::less<kWidth>(w, sink), w, sink);
    for (int k = 0; k < kLanes; ++k) slot[marked[k]] = 0;
    last = w[kLanes - 1];
  }
  winners.clear();
  for (std::size_t n = 0; n < job.count; ++n) {
    if (slot[n] == 0) {
      slot[n] = std::int32_t(winners.size());
      winners.push_back(std::uint32_t(n));
    }
  }
  shades.resize(winners.size());
  shadeSetupsOf<kAvx2>(in, job.bins, winners.data(), winners.size(), shades.data());
  return {slot.data(), winners.data(), winners.size(), shades.data()};
}

// The winners' packed records for the gathered resolve (tile_gather.h), each at its winner's
// position in the bins and one of zeros for the empty pixels after them; null where the
// gathered resolve does not apply: double precision, more attribute components than a record
// holds, or a clipped winner (its barycentrics go through its map, which only the
// winner-by-winner path applies). Records start on a cache line, so that no 32-byte access
// straddles two (core/line_allocator.h); they live per thread too.
template <typename Real>
RC_KERNEL_INLINE const float* packWinners(const Input<Real>& in, const Outputs& out, const TileJob& job,
                                          const TileShades<Real>& shades) {
  if constexpr (sizeof(Real) == 4) {
    thread_local std::vector<float, LineAllocator<float>> packs;
    constexpr std::size_t packStride = pack::kStride;
    const bool gathered =
        in.gatheredResolve && out.attributeComponents <= pack::kMaxComponents &&
        std::none_of(shades.shades, shades.shades + shades.count, [](const ShadeSetup<Real>& s) { return s.clipMap >= 0; });
    if (!gathered) return nullptr;
    packs.resize((job.count + 1) * packStride);  // + the empty pixels' record of zeros
    packShades(in, out, job.bins, shades.winners, shades.shades, shades.count, packs.data());
    std::fill(packs.end() - std::ptrdiff_t(packStride), packs.end(), 0.0f);
    return packs.data();
  } else {
    return nullptr;
  }
}

// Staging rows: id, b0..b2, depth, the four diagnostics, then the attribute components.
constexpr int kFixedPlanes = 9, kStride = kTileSize + kLanes;

// One row chunk, x to x + kLanes, resolved into the staging rows at `at` (the diagnostics'
// rows where `diagnostics`): one pass for a chunk of one winner, a gathered pass (packs not
// null) for one of several runs, else a pass per distinct winner, blended by mask.
template <typename Real, std::size_t kWidth>
RC_KERNEL_INLINE void resolveChunk(const Input<Real>& in, const Outputs& out, const TileJob& job,
                                   const TileShades<Real>& shades, const float* packs, u32x8 w,
                                   i32x8 valid, int lanes, int x, int y, int components, bool diagnostics,
                                   std::uint32_t* at) {
  constexpr bool kAvx2 = kWidth >= 32;
  Resolved r{};
  float* attributesAt = reinterpret_cast<float*>(at + kFixedPlanes * kStride);
  u32x8 id;
  f32x8 baryBound, depthBound;
  // One winner: no blending.
  if (lanes == kLanes && !anyOf<kAvx2>(split::notEqual<kWidth>(w, w[0])) && w[0] != kEmpty) {
    const ShadeSetup<Real>& s = shades.of(w[0]);
    resolveLanes<false, kWidth>(in, out, job.bins[w[0]], s, x, y, r, attributesAt, kStride, valid);
    id = split::splat<kWidth, u32x8>(s.triangle);
    baryBound = split::splat<kWidth, f32x8>(s.baryBound);
    depthBound = split::splat<kWidth, f32x8>(s.depthBound);
  } else if (packs && moreRunsThan<kWidth>(w, kGatherAbove)) {
    if constexpr (sizeof(Real) == 4) {
      // Lane k's record is at its winner's position in the bins, an empty lane's after the
      // last. A lookup per lane through slot[] was 5% of the instructions at 100k triangles;
      // making the eight addresses in vector lanes and storing them measured slower than this
      // loop.
      const u32x8 position = split::select<kWidth>(valid, w, split::splat<kWidth, u32x8>(std::uint32_t(job.count)));
      const float* record[kLanes];
      for (int k = 0; k < kLanes; ++k) record[k] = packs + std::size_t(position[k]) * pack::kStride;
      resolveGathered<kWidth>(in, out, record, x, y, valid, r, id, baryBound, depthBound, attributesAt, kStride);
    }
  } else {
    id = split::splat<kWidth, u32x8>(channels::kNoTriangle);
    baryBound = depthBound = f32x8{};
    for (int k = 0; k < components; ++k) store(attributesAt + kStride * k, f32x8{});
    unsigned remaining = laneBits<kAvx2>(valid);
    while (remaining != 0) {
      const std::uint32_t n = w[__builtin_ctz(remaining)];
      const i32x8 mine = valid & split::equal<kWidth>(w, n);
      remaining &= ~laneBits<kAvx2>(mine);
      Resolved own{};
      const ShadeSetup<Real>& s = shades.of(n);
      resolveLanes<true, kWidth>(in, out, job.bins[n], s, x, y, own, attributesAt, kStride, mine);
      id = split::select<kWidth>(mine, split::splat<kWidth, u32x8>(s.triangle), id);
      for (int i = 0; i < 3; ++i) r.bary[i] = split::select<kWidth>(mine, own.bary[i], r.bary[i]);
      r.depth = split::select<kWidth>(mine, own.depth, r.depth);
      r.edgeDistance = split::select<kWidth>(mine, own.edgeDistance, r.edgeDistance);
      r.depthTie = split::select<kWidth>(mine, own.depthTie, r.depthTie);
      baryBound = split::select<kWidth>(mine, split::splat<kWidth, f32x8>(s.baryBound), baryBound);
      depthBound = split::select<kWidth>(mine, split::splat<kWidth, f32x8>(s.depthBound), depthBound);
    }
  }
  store(at, id);
  for (int i = 0; i < 3; ++i) store(at + (1 + i) * kStride, r.bary[i]);
  store(at + 4 * kStride, r.depth);
  if (diagnostics) {
    store(at + 5 * kStride, baryBound);
    store(at + 6 * kStride, depthBound);
    store(at + 7 * kStride, r.edgeDistance);
    store(at + 8 * kStride, r.depthTie);
  }
}

// Resolve, a row chunk at a time, each tile row into its staging rows (per thread, reused from
// tile to tile: allocating and freeing them per tile was about 2% of the samples at 100k
// triangles), then copied out plane by plane. `promoted` (a float tile's, null where none):
// winners whose lanes are resolved again in double (tile_promote.h).
template <typename Real, std::size_t kWidth>
RC_KERNEL_INLINE void resolveTile(const Input<Real>& in, const Outputs& out, const TileJob& job,
                                  const std::uint32_t* winner, const TileShades<Real>& shades, const float* packs,
                                  const PromotedWinners* promoted) {
  constexpr bool kAvx2 = kWidth >= 32;
  const int components = out.attributeComponents;
  const bool diagnostics = out.edgeDistance != nullptr;
  thread_local std::vector<std::uint32_t, LineAllocator<std::uint32_t>> stage;
  thread_local std::vector<std::uint32_t*> planes;
  stage.resize(std::size_t(kFixedPlanes + components) * kStride);
  planes.assign({out.id, reinterpret_cast<std::uint32_t*>(out.bary[0]), reinterpret_cast<std::uint32_t*>(out.bary[1]),
                 reinterpret_cast<std::uint32_t*>(out.bary[2]), reinterpret_cast<std::uint32_t*>(out.depth),
                 reinterpret_cast<std::uint32_t*>(out.baryBound), reinterpret_cast<std::uint32_t*>(out.depthBound),
                 reinterpret_cast<std::uint32_t*>(out.edgeDistance), reinterpret_cast<std::uint32_t*>(out.depthTie)});
  for (const Outputs::Attribute& a : out.attributes) {
    for (int j = 0; j < a.components; ++j) planes.push_back(reinterpret_cast<std::uint32_t*>(a.out[j]));
  }
  // Bit c set: chunk column c of the staging rows holds what a chunk without a winner writes
  // (no triangle, zeros), so a chunk without a winner below it writes nothing again.
  unsigned stagedEmpty = 0;
  std::uint64_t promotedPixels = 0;
  for (int y = job.y0; y <= job.y1; ++y) {
    for (int x = job.x0; x <= job.x1; x += kLanes) {
      const int lanes = std::min(kLanes, job.x1 - x + 1);
      const u32x8 w = load<u32x8>(winner + (y - job.y0) * kTileSize + (x - job.x0));
      const i32x8 valid = split::less<kWidth>(iota32(), lanes) & split::notEqual<kWidth>(w, kEmpty);
      const unsigned column = 1u << ((x - job.x0) / kLanes);
      if (anyOf<kAvx2>(valid)) {
        stagedEmpty &= ~column;
      } else if (stagedEmpty & column) {
        continue;
      } else {
        stagedEmpty |= column;
      }
      std::uint32_t* at = stage.data() + (x - job.x0);
      resolveChunk<Real, kWidth>(in, out, job, shades, packs, w, valid, lanes, x, y, components, diagnostics, at);
      if (promoted) {
        promotedPixels += promoteChunk<kWidth>(*promoted, out, w, valid, x, y, diagnostics, at, kStride,
                                               reinterpret_cast<float*>(at + kFixedPlanes * kStride));
      }
    }
    const std::size_t rowStart = std::size_t(y) * out.width + job.x0;
    const int n = job.x1 - job.x0 + 1;
    streamStagedRow<kAvx2>(planes.data(), kFixedPlanes + components, stage.data(), kStride, rowStart, n);
  }
  if (promotedPixels != 0 && out.promotedPixels) out.promotedPixels->fetch_add(promotedPixels, std::memory_order_relaxed);
}

// One tile: coverage and depth test into the visibility buffer, the winners' set-ups (and
// their packed records), then resolve and copy-out.
template <typename Real, std::size_t kWidth>
RC_KERNEL_INLINE void renderTile(const Input<Real>& in, const Outputs& out, const TileJob& job) {
  Visibility<Real> vis;
  for (int i = 0; i < Visibility<Real>::kPixels; ++i) vis.winner[i] = kEmpty;
  for (int i = 0; i < Visibility<Real>::kPixels; ++i) vis.nearest[i] = -std::numeric_limits<Real>::infinity();
  if (in.subpixelBits != 0) {
    coverTile<Real, kWidth>(in, job, vis, std::false_type{});
  } else {
    coverTile<Real, kWidth>(in, job, vis, std::true_type{});
  }
  const TileShades<Real> shades = shadeWinners<Real, kWidth>(in, job, vis.winner);
  const float* packs = packWinners(in, out, job, shades);
  const PromotedWinners* promoted = nullptr;
  if constexpr (sizeof(Real) == 4) {
    thread_local PromotedWinners winners;
    if (promoteWinners(in, job, shades.winners, shades.shades, shades.count, winners)) promoted = &winners;
  }
  resolveTile<Real, kWidth>(in, out, job, vis.winner, shades, packs, promoted);
  _mm_sfence();  // the non-temporal stores are visible before the tile counts as done
}

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
