// The tile kernels' gathered resolve: each winner's resolve inputs packed into a record of
// floats, and a row chunk of several winners resolved in one pass over its lanes' records.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/channels.h"
#include "core/split_vectors.h"
#include "rasterizer/interpolate.h"
#include "rasterizer/kernel_lanes.h"
#include "rasterizer/tile_kernel.h"
#include "rasterizer/tile_resolve.h"

namespace rc::kernel {

// Vector values only ever pass between always-inlined functions, so the ABI of passing them
// (which differs with and without AVX) never matters.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// Gathered resolve, for float set-ups. At 1M triangles a row chunk of eight pixels has about
// five winners, and resolving it winner by winner computes all eight lanes for each to keep one
// or two of them. Instead, each winner's resolve inputs are packed into one record of floats
// (packShades); a chunk loads its lanes' records, transposes them so that each field is one
// vector across the lanes, and resolves all eight lanes in one pass. Each lane runs the very
// operations of resolveLanes in the same order, so the bits are the same whichever path a
// chunk takes (Rasterizer.GatheredResolveGivesTheSameBitsAsWinnerByWinner).
namespace pack {
constexpr int kL0 = 0, kLx = 3, kLy = 6;  // screen-space planes
constexpr int kQ = 9;                     // invW (perspective) or w (affine)
constexpr int kAnchorX = 12, kAnchorY = 13;
constexpr int kTriangle = 14;  // the triangle index's bits
// Group 2 (only read with diagnostics): bounds, depth key plane, edge heights.
constexpr int kBaryBound = 16, kDepthBound = 17, kKey0 = 18, kKeyX = 19, kKeyY = 20, kEdgeHeight = 21;
constexpr int kAttributes = 24;  // then v0, v1, v2 of each attribute component
constexpr int kGroup = kLanes;   // fields are transposed eight at a time
// Meshes with more attribute components take the winner-by-winner path.
constexpr int kMaxComponents = 8;
constexpr std::size_t kStride = kAttributes + kMaxComponents * 3;  // 48 floats
}  // namespace pack

// Four rows of four floats -> four columns (unpcklps / unpckhps / movlhps / movhlps).
typedef float f32x4 __attribute__((vector_size(16)));
RC_KERNEL_INLINE void transpose4(const f32x4 in[4], f32x4 out[4]) {
  const f32x4 t0 = __builtin_shufflevector(in[0], in[1], 0, 4, 1, 5);
  const f32x4 t1 = __builtin_shufflevector(in[0], in[1], 2, 6, 3, 7);
  const f32x4 t2 = __builtin_shufflevector(in[2], in[3], 0, 4, 1, 5);
  const f32x4 t3 = __builtin_shufflevector(in[2], in[3], 2, 6, 3, 7);
  out[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5), out[1] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  out[2] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5), out[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// Eight rows of eight floats -> eight columns, in place: the classic AVX unpack / shuffle /
// 128-bit permute sequence, as generic shuffles. Where the registers hold four floats (kWidth
// 16, the SSE2 build), four 4x4 transposes of the rows' halves instead: GCC lowers an 8-lane
// shuffle there lane by lane through memory wherever it mixes halves.
template <std::size_t kWidth>
RC_KERNEL_INLINE void transpose8(f32x8 r[8]) {
  if constexpr (kWidth < 32) {
    f32x4 low[8], high[8], out[4];
    for (int i = 0; i < 8; ++i) low[i] = split::lowOf(r[i]), high[i] = split::highOf(r[i]);
    f32x4 column[8][2];  // column j's halves: rows 0-3 and rows 4-7
    for (int half = 0; half < 2; ++half) {
      const f32x4* rows = half == 0 ? low : high;  // columns 0-3 or 4-7
      for (int block = 0; block < 2; ++block) {    // rows 0-3 or 4-7
        transpose4(rows + 4 * block, out);
        for (int j = 0; j < 4; ++j) column[4 * half + j][block] = out[j];
      }
    }
    for (int j = 0; j < 8; ++j) r[j] = split::joined(column[j][0], column[j][1]);
    return;
  }
  f32x8 t[8], u[8];
  for (int i = 0; i < 8; i += 2) {
    t[i] = __builtin_shufflevector(r[i], r[i + 1], 0, 8, 1, 9, 4, 12, 5, 13);
    t[i + 1] = __builtin_shufflevector(r[i], r[i + 1], 2, 10, 3, 11, 6, 14, 7, 15);
  }
  for (int i = 0; i < 8; i += 4) {
    u[i] = __builtin_shufflevector(t[i], t[i + 2], 0, 1, 8, 9, 4, 5, 12, 13);
    u[i + 1] = __builtin_shufflevector(t[i], t[i + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    u[i + 2] = __builtin_shufflevector(t[i + 1], t[i + 3], 0, 1, 8, 9, 4, 5, 12, 13);
    u[i + 3] = __builtin_shufflevector(t[i + 1], t[i + 3], 2, 3, 10, 11, 6, 7, 14, 15);
  }
  for (int i = 0; i < 4; ++i) {
    r[i] = __builtin_shufflevector(u[i], u[i + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    r[i + 4] = __builtin_shufflevector(u[i], u[i + 4], 4, 5, 6, 7, 12, 13, 14, 15);
  }
}

// One record of pack::kStride floats per winner, from its set-ups, at the winner's position in
// the tile's bins (winners[i]) rather than at i: a chunk then finds its lanes' records from the
// visibility buffer alone, without a lookup per lane. The records of set-ups that win nothing are
// never written or read, and the fields no lane reads (15, and those past the mesh's
// attributes) are left as they are. The attribute values at the winners' vertices lie
// scattered through the mesh's arrays: each winner's are prefetched kAttributesAhead winners
// ahead. In one process, rounds alternating, three sittings measured 1M triangles on 2 threads
// 25.7 down to 23.7, 28.9 down to 26.8 and 29.2 down to 27.1 ms a frame (1 thread 46.7 down to
// 43.6; 100k 8.13 down to 7.87), as fast as copying no attributes at all; two later sittings
// measured no difference (24.4 against 24.1, 33.0 against 32.7). The triangles were read by the
// set-up pass just before, so they are in cache.
inline void packShades(const Input<float>& in, const Outputs& out, const std::uint32_t* bins,
                       const std::uint32_t* winners, const ShadeSetup<float>* shades, std::size_t count,
                       float* packs) {
  constexpr std::size_t stride = pack::kStride, kAttributesAhead = 8;
  for (std::size_t i = 0; i < count; ++i) {
    if (i + kAttributesAhead < count) {
      const glm::uvec3 ahead = in.triangles[shades[i + kAttributesAhead].triangle];
      for (const Outputs::Attribute& a : out.attributes) {
        const float* v[3];
        vertexValuesOf(a, ahead, v);
        for (const float* values : v) __builtin_prefetch(values);
      }
    }
    const ShadeSetup<float>& s = shades[i];
    const std::uint32_t name = bins[winners[i]];
    const CoverageSetup<float>& c = in.coverage[name >> kBlockShift][name & kLocalMask];
    float* p = packs + std::size_t(winners[i]) * stride;
    for (int k = 0; k < 3; ++k) {
      p[pack::kL0 + k] = s.l0[k];
      p[pack::kLx + k] = s.lx[k];
      p[pack::kLy + k] = s.ly[k];
      p[pack::kQ + k] = in.perspective ? s.invW[k] : s.w[k];
      p[pack::kEdgeHeight + k] = s.edgeHeight[k];
    }
    p[pack::kAnchorX] = float(c.anchorX());  // pixel coordinates: exact
    p[pack::kAnchorY] = float(c.anchorY());
    std::memcpy(&p[pack::kTriangle], &s.triangle, sizeof s.triangle);
    p[pack::kBaryBound] = s.baryBound;
    p[pack::kDepthBound] = s.depthBound;
    p[pack::kKey0] = c.key0;
    p[pack::kKeyX] = c.keyX;
    p[pack::kKeyY] = c.keyY;
    const glm::uvec3 tri = in.triangles[s.triangle];
    float* v = p + pack::kAttributes;
    for (const Outputs::Attribute& a : out.attributes) {
      const float* from[3];
      vertexValuesOf(a, tri, from);
      withComponents(a.components, [&](auto n) __attribute__((always_inline)) {
        for (int j = 0; j < decltype(n)::value; ++j) v[3 * j] = from[0][j], v[3 * j + 1] = from[1][j], v[3 * j + 2] = from[2][j];
      });
      v += 3 * a.components;
    }
  }
}

// Field group g (fields 8g .. 8g + 7) of the eight lanes' records, one vector per field.
template <std::size_t kWidth>
RC_KERNEL_INLINE void gatherGroup(const float* const record[kLanes], int g, f32x8 field[kLanes]) {
  for (int k = 0; k < kLanes; ++k) field[k] = load<f32x8>(record[k] + g * pack::kGroup);
  transpose8<kWidth>(field);
}

// Chunks of up to this many runs of one winner are resolved winner by winner
// (docs/rasterizer.md, "Gathered resolve"). A chunk of two runs already resolves faster
// gathered: with AVX2 and AVX-512 (in one process, rounds alternating: 100k triangles, 2
// threads, 9.26 against 9.94 ms a frame; 1 thread 17.4 against 18.9; 1k and 1M the same or a
// little faster), and with SSE2 once its transposes took 4x4 halves (100k 14.0 against 16.9 ms,
// 14.2 against 16.4; 1k 7.7 against 8.1).
constexpr int kGatherAbove = 1;
// Whether the chunk's winner changes from lane to lane at least n times, that is, whether it
// has more than n runs of lanes with one winner (or none). A triangle's pixels in a row chunk
// are one run, so this counts its winners, empty lanes as one more, in four instructions.
// Counting the distinct winners exactly took a chain of lane extractions, 5% of the tiles'
// time at 100k triangles. Only the path taken depends on it: both give the same bits.
template <std::size_t kWidth>
RC_KERNEL_INLINE bool moreRunsThan(const u32x8& w, int n) {
  const u32x8 previous = __builtin_shufflevector(w, w, 0, 0, 1, 2, 3, 4, 5, 6);
  return __builtin_popcount(laneBits<(kWidth >= 32)>(split::notEqual<kWidth>(w, previous))) >= n;
}

// resolveLanes for lanes with different winners: lane k's record is record[k]. Lanes outside
// `valid` get what the winner-by-winner path leaves there: zeros and no triangle.
template <std::size_t kWidth>
RC_KERNEL_INLINE void resolveGathered(const Input<float>& in, const Outputs& out, const float* const record[kLanes],
                                      int x, int y, const i32x8& valid, Resolved& r, u32x8& id, f32x8& baryBound,
                                      f32x8& depthBound, float* attributes, std::size_t stride) {
  baryBound = depthBound = f32x8{};  // written only with diagnostics
  f32x8 f[kLanes];
  gatherGroup<kWidth>(record, 0, f);
  f32x8 g[kLanes];
  gatherGroup<kWidth>(record, 1, g);
  // Fields 0..7 in f, 8..15 in g.
  const f32x8 dx = (float(x) + iota<float>()) - g[pack::kAnchorX - 8];  // small integers: exact
  const f32x8 dy = float(y) - g[pack::kAnchorY - 8];
  const f32x8 ly2 = g[0];
  f32x8 l[3];
  l[0] = f[pack::kL0 + 0] + f[pack::kLx + 0] * dx + f[pack::kLy + 0] * dy;
  l[1] = f[pack::kL0 + 1] + f[pack::kLx + 1] * dx + f[pack::kLy + 1] * dy;
  l[2] = f[pack::kL0 + 2] + f[pack::kLx + 2] * dx + ly2 * dy;
  const f32x8 q[3] = {g[pack::kQ - 8], g[pack::kQ + 1 - 8], g[pack::kQ + 2 - 8]};  // 1/w or w, per lane
  const Recovered<f32x8> recovered = in.perspective ? perspectiveCorrect(l, q) : affineWeights(l, q);
  const f32x8* const b = recovered.b;
  const f32x8 depth = recovered.depth;
  const f32x8 none{};
  for (int i = 0; i < 3; ++i) r.bary[i] = split::select<kWidth>(valid, b[i], none);
  r.depth = split::select<kWidth>(valid, depth, none);
  u32x8 triangle;
  std::memcpy(&triangle, &g[pack::kTriangle - 8], sizeof triangle);
  id = split::select<kWidth>(valid, triangle, split::splat<kWidth, u32x8>(channels::kNoTriangle));
  if (out.edgeDistance) {
    f32x8 h[kLanes];
    gatherGroup<kWidth>(record, 2, h);
    f32x8 edgeDistance, depthTie;
    diagnosticsOf<kWidth>(l, h + (pack::kEdgeHeight - 16), h[pack::kKey0 - 16], h[pack::kKeyX - 16],
                          h[pack::kKeyY - 16], dx, dy, depth, in.tieScale, edgeDistance, depthTie);
    r.edgeDistance = split::select<kWidth>(valid, edgeDistance, none);
    r.depthTie = split::select<kWidth>(valid, depthTie, none);
    baryBound = split::select<kWidth>(valid, h[pack::kBaryBound - 16], none);
    depthBound = split::select<kWidth>(valid, h[pack::kDepthBound - 16], none);
  }
  // The attributes' vertex values, three fields per component (at most pack::kMaxComponents).
  f32x8 v[pack::kMaxComponents * 3 / pack::kGroup * kLanes];
  const int components = out.attributeComponents;
  for (int group = 0; group * pack::kGroup < 3 * components; ++group) {
    gatherGroup<kWidth>(record, pack::kAttributes / pack::kGroup + group, v + group * kLanes);
  }
  float* into = attributes;
  for (int j = 0; j < components; ++j, into += stride) {
    const f32x8 value = b[0] * v[3 * j] + b[1] * v[3 * j + 1] + b[2] * v[3 * j + 2];
    store(into, split::select<kWidth>(valid, value, none));
  }
}

#pragma GCC diagnostic pop

}  // namespace rc::kernel
