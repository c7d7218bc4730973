// The per-tile pixel kernels: coverage + depth test into a tile-local visibility buffer, then
// resolve (barycentrics, depth, attributes and diagnostics of each pixel's winner), eight pixels
// of a row at a time in GCC vector extensions. The same source is compiled for SSE2 (any
// x86-64), AVX2 and AVX-512 (the rasterizer picks one at run time); each lane runs the formulas
// of setup.h and interpolate.h in the same order, without FMA, so all give the same bits
// (Rasterizer.OutputBitsAreIdenticalOnEveryKernelIsa). Comparisons and selects go through
// core/split_vectors.h with the target's register width (kWidth), since GCC lowers those on a
// vector wider than the registers lane by lane.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <emmintrin.h>
#include <limits>
#include <type_traits>
#include <vector>
#include <glm/glm.hpp>

#include "core/channels.h"
#include "core/line_allocator.h"
#include "core/split_vectors.h"
#include "core/stream_row.h"
#include "rasterizer/coverage.h"
#include "rasterizer/interpolate.h"
#include "rasterizer/orientation.h"
#include "rasterizer/setup.h"
#include "rasterizer/setup_batch.h"

namespace rc::kernel {

constexpr int kTileShift = 6;
constexpr int kTileSize = 1 << kTileShift;  // 64
constexpr int kLanes = 8;
// The coverage pass prefetches the set-up this many bins ahead: a tile's bins skip through its
// blocks' arrays, which the hardware prefetcher does not follow (7% of the tiles' time at 1M).
constexpr std::size_t kPrefetchAhead = 8;
// coverRows runs a box one chunk wide and at most this many rows high as exactly 2 or this
// many rows, so the visibility buffers reach kFixedRows - 1 rows past the tile.
constexpr int kFixedRows = 4;
constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;
// A set-up is named by (block << kBlockShift) | index within its block: set-ups stay in their
// blocks (no concatenation), and the names still sort in triangle order.
constexpr int kBlockShift = 20;
constexpr std::uint32_t kLocalMask = (1u << kBlockShift) - 1u;

struct Outputs {
  int width;
  std::uint32_t* id;
  float* bary[3];
  float* depth;
  float* baryBound;     // the four diagnostics are null when they are not written
  float* depthBound;
  float* edgeDistance;
  float* depthTie;
  struct Attribute {
    const float* values;  // per vertex, `components` each
    int components;
    float* out[4];
  };
  std::vector<Attribute> attributes;
  int attributeComponents;  // sum of components
};

template <typename Real>
struct Input {
  const CoverageSetup<Real>* const* coverage;       // per block
  const ClippedTriangle<Real>* const* clipped;      // per block
  const glm::uvec3* triangles;                      // the mesh's
  const glm::dvec4* vertexClip;                     // per mesh vertex: setupShade's inputs
  const glm::dvec2* vertexRaster;
  const SetupContext* context;
  int subpixelBits;
  bool perspective;
  bool gatheredResolve;  // RasterOptions::gatheredResolve
  Real tieScale;  // depth.tie = tieScale (|key0| + |keyX dx| + |keyY dy|) depth (setup.h)
};

// One tile: pixels [x0, x1] x [y0, y1], set-ups bins[0..count) in triangle order.
struct TileJob {
  const std::uint32_t* bins;
  std::size_t count;
  int x0, y0, x1, y1;
};

// Entry points, one per (precision, instruction set); tile_kernel.cpp.
void renderTileSse2(const Input<float>&, const Outputs&, const TileJob&);
void renderTileSse2(const Input<double>&, const Outputs&, const TileJob&);
void renderTileAvx2(const Input<float>&, const Outputs&, const TileJob&);
void renderTileAvx2(const Input<double>&, const Outputs&, const TileJob&);
void renderTileAvx512(const Input<float>&, const Outputs&, const TileJob&);
void renderTileAvx512(const Input<double>&, const Outputs&, const TileJob&);
// The features the AVX-512 entry points are compiled for (tile_kernel.cpp's target attribute).
bool cpuHasKernelAvx512();
// Pixels covered by one set-up, for coveredPixels(); the kernels' own coverage code, SSE2.
// raster: its unsnapped vertices (read only without snapping, bits 0).
void coveredPixelsOf(const CoverageSetup<float>& s, int bits, const glm::dvec2 raster[3], std::vector<std::uint32_t>& pixels,
                     int width);
void coveredPixelsOf(const CoverageSetup<double>& s, int bits, const glm::dvec2 raster[3], std::vector<std::uint32_t>& pixels,
                     int width);

// Vector values only ever pass between always-inlined functions, so the ABI of passing them
// (which differs with and without AVX) never matters.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

#define RC_KERNEL_INLINE inline __attribute__((always_inline))

typedef float f32x8 __attribute__((vector_size(32)));
typedef double f64x8 __attribute__((vector_size(64)));
typedef std::int32_t i32x8 __attribute__((vector_size(32)));
typedef std::uint32_t u32x8 __attribute__((vector_size(32)));
typedef std::int64_t i64x8 __attribute__((vector_size(64)));

template <typename Real>
struct Lanes;
template <>
struct Lanes<float> {
  using V = f32x8;
  using M = i32x8;  // comparison result of two V
};
template <>
struct Lanes<double> {
  using V = f64x8;
  using M = i64x8;
};

template <typename T>
RC_KERNEL_INLINE T load(const void* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <typename T>
RC_KERNEL_INLINE void store(void* p, const T& v) { std::memcpy(p, &v, sizeof v); }

RC_KERNEL_INLINE bool any(const i32x8& m) {
  std::uint64_t q[4];
  std::memcpy(q, &m, sizeof q);
  return (q[0] | q[1] | q[2] | q[3]) != 0;
}
// any() in one instruction where the caller is AVX2 or AVX-512 code (renderTile<Real, 32>
// or <Real, 64>): vptest sets ZF when every bit is 0. The generic form goes through memory,
// four loads and three ORs, 3 to 6% of the tiles' time. Written as asm since an AVX2 builtin cannot sit in code shared
// with the SSE2 build; the operand is a ymm register only once GCC has inlined it into AVX2
// code. Clang checks the operand's size before inlining and refuses it, so a clang build (the
// fuzzers') takes the generic forms, which give the same answers.
template <bool kAvx2>
RC_KERNEL_INLINE bool anyOf(const i32x8& m) {
#if !defined(__clang__)
  if constexpr (kAvx2) {
    bool nonzero;
    asm("vptest %1, %1" : "=@ccnz"(nonzero) : "x"(m));
    return nonzero;
  }
#endif
  return any(m);
}
// Bit k set when lane k of the mask is set (vmovmskps; SSE's movmskps on each half).
template <bool kAvx2>
RC_KERNEL_INLINE unsigned laneBits(const i32x8& m) {
#if !defined(__clang__)
  if constexpr (kAvx2) {
    int bits;
    asm("vmovmskps %1, %0" : "=r"(bits) : "x"(m));
    return unsigned(bits);
  }
#endif
  __m128 half[2];
  std::memcpy(half, &m, sizeof half);
  return unsigned(_mm_movemask_ps(half[0]) | (_mm_movemask_ps(half[1]) << 4));
}

template <typename M>
RC_KERNEL_INLINE M maskAs(const i32x8& m) { return __builtin_convertvector(m, M); }
template <typename M>
RC_KERNEL_INLINE i32x8 mask32(const M& m) { return __builtin_convertvector(m, i32x8); }

template <typename Real>
RC_KERNEL_INLINE typename Lanes<Real>::V iota() {
  return typename Lanes<Real>::V{0, 1, 2, 3, 4, 5, 6, 7};
}
RC_KERNEL_INLINE i32x8 iota32() { return i32x8{0, 1, 2, 3, 4, 5, 6, 7}; }

template <typename Real>
RC_KERNEL_INLINE f32x8 toFloat(const typename Lanes<Real>::V& v) {
  if constexpr (sizeof(Real) == 4) {
    return v;
  } else {
    return __builtin_convertvector(v, f32x8);
  }
}

// The lanes of v (eight int32 or int64) that are not negative, as a mask of int32 lanes. An
// int64 lane is not negative when its high word, as an int32, is not: where the target has no
// 64-byte registers, that high word's test is what compiles well (whole, GCC tests the lanes
// one by one in scalar registers; in halves, the loop keeps its vectors in memory).
template <std::size_t kWidth, typename LaneVector>
RC_KERNEL_INLINE i32x8 nonNegative(const LaneVector& v) {
  using Lane = std::remove_cvref_t<decltype(v[0])>;
  if constexpr (sizeof(Lane) == 4) {
    return split::greaterEqual<kWidth>(v, Lane(0));
  } else if constexpr (kWidth >= sizeof(LaneVector)) {
    return __builtin_convertvector(v >= 0, i32x8);
  } else {
    typedef std::uint64_t U64x8 __attribute__((vector_size(64)));
    const u32x8 high = __builtin_convertvector(U64x8(v) >> 32, u32x8);
    return split::greaterEqual<kWidth>(i32x8(high), 0);
  }
}

// Exact coverage, a row chunk of eight pixels at a time. Narrow set-ups (every value below
// 2^31, CoverageSetup::kNarrow) take int32 lanes, the others int64 lanes (values below 2^62:
// products below 2^61, plus at most 8 steps of 2^46). With kVectorSteps (the AVX2 and AVX-512
// builds), each edge's values E_i + bias_i at the chunk's eight pixels (exact, coverage.h) sit
// in a vector that steps by a chunk along the row and by a row down the box; the steps wrap
// around (unsigned lanes) where they go past the box, whose values are never read. Without it
// (the SSE2 build, which has half the registers and splits each vector in two), each row's
// values at the chunk's first pixel step in int64 scalars and lane k adds k a_i 2^bits: the
// vector steps made its tiles 8% slower at 100k triangles.
//
// Calls fn(x, y, column, mask) for every row chunk of [xa, xb] x [ya, yb], x = xa + 8 column,
// with lanes x .. x + 7, mask set where the pixel centre is inside and x + k <= xb, also when
// no lane is set: a test of the mask here was a data-dependent branch per chunk, and with the
// depth test's own (below) it mispredicted often enough that the tiles ran 10% faster without
// both. The limit x + k <= xb is a fourth value that must not be negative, xb - x - k.
// With kVectorSteps, a box one chunk wide and at most kFixedRows rows high runs as exactly 2 or
// kFixedRows rows (fn is called for up to kFixedRows - 1 rows past yb, with empty masks; the
// caller's buffers must reach that far): the row loop's exit, at a trip count that varies from
// set-up to set-up, cost more than the rows this adds. At 1M triangles most set-ups have such
// boxes (2.4 row chunks on average), and the tiles took 13.4 down to 12.5 ms a frame
// (docs/rasterizer.md, "Fixed row counts").
template <typename Lane, bool kVectorSteps, std::size_t kWidth, typename Fn>
RC_KERNEL_INLINE void coverRows(const EdgeFunctions& e, int bits, int xa, int ya, int xb, int yb, Fn&& fn) {
  typedef Lane LaneVector __attribute__((vector_size(kLanes * sizeof(Lane))));
  if constexpr (!kVectorSteps) {
    const std::int64_t step = std::int64_t(1) << bits;
    LaneVector laneStep[3];
    std::int64_t chunkStep[3], rowStep[3], row[3];
    const std::int64_t px = pixelCenterFixed(xa, bits), py = pixelCenterFixed(ya, bits);
    for (int i = 0; i < 3; ++i) {
      const Lane a = Lane(e.a[i] * step);
      laneStep[i] = LaneVector{0, 1, 2, 3, 4, 5, 6, 7} * a;
      chunkStep[i] = std::int64_t(kLanes) * e.a[i] * step;
      rowStep[i] = e.b[i] * step;
      row[i] = e.a[i] * (px - e.ox[i]) + e.b[i] * (py - e.oy[i]) + e.bias[i];
    }
    for (int y = ya; y <= yb; ++y) {
      std::int64_t chunk[3] = {row[0], row[1], row[2]};
      for (int x = xa, column = 0; x <= xb; x += kLanes, ++column) {
        const LaneVector all = (Lane(chunk[0]) + laneStep[0]) | (Lane(chunk[1]) + laneStep[1]) |
                               (Lane(chunk[2]) + laneStep[2]);
        i32x8 mask = nonNegative<kWidth>(all);  // all three non-negative
        mask &= split::lessEqual<kWidth>(iota32() + x, xb);
        fn(x, y, column, mask);
        for (int i = 0; i < 3; ++i) chunk[i] += chunkStep[i];
      }
      for (int i = 0; i < 3; ++i) row[i] += rowStep[i];
    }
    return;
  }
  typedef std::make_unsigned_t<Lane> Unsigned;
  typedef Unsigned UnsignedVector __attribute__((vector_size(kLanes * sizeof(Lane))));
  const UnsignedVector iota{0, 1, 2, 3, 4, 5, 6, 7};
  const std::int64_t step = std::int64_t(1) << bits;
  const std::int64_t px = pixelCenterFixed(xa, bits), py = pixelCenterFixed(ya, bits);
  Unsigned first[3], chunkStep[3], rowStep[3], laneStep[3];
  for (int i = 0; i < 3; ++i) {
    first[i] = Unsigned(e.a[i] * (px - e.ox[i]) + e.b[i] * (py - e.oy[i]) + e.bias[i]);
    laneStep[i] = Unsigned(e.a[i] * step);
    chunkStep[i] = Unsigned(std::int64_t(kLanes) * e.a[i] * step);
    rowStep[i] = Unsigned(e.b[i] * step);
  }
  const UnsignedVector chunk0 = UnsignedVector{} + chunkStep[0], chunk1 = UnsignedVector{} + chunkStep[1],
                       chunk2 = UnsignedVector{} + chunkStep[2];
  const UnsignedVector row0 = UnsignedVector{} + rowStep[0], row1 = UnsignedVector{} + rowStep[1],
                       row2 = UnsignedVector{} + rowStep[2];
  const UnsignedVector rowLimit = Unsigned(xb - xa) - iota;
  UnsignedVector rowValue0 = first[0] + iota * laneStep[0], rowValue1 = first[1] + iota * laneStep[1],
                 rowValue2 = first[2] + iota * laneStep[2];
  // A box one chunk wide and at most kFixedRows high: exactly 2 or kFixedRows rows, those past
  // the box with an empty mask (all ones in the limit: negative). Past the box the triangle may
  // go on (the box is clamped to the tile), and int32 lanes may wrap around to values that look
  // inside (FillRule.SmallBoxesReportOnlyTheirOwnPixels).
  const auto fixedRows = [&](auto count) __attribute__((always_inline)) {
    const int rows = yb - ya;
#pragma GCC unroll 4
    for (int r = 0; r < decltype(count)::value; ++r) {
      const UnsignedVector beyond = UnsignedVector{} + (Unsigned(0) - Unsigned(r > rows));
      fn(xa, ya + r, 0, nonNegative<kWidth>(LaneVector(rowValue0 | rowValue1 | rowValue2 | rowLimit | beyond)));
      rowValue0 += row0, rowValue1 += row1, rowValue2 += row2;
    }
  };
  if (xb - xa < kLanes && yb - ya < kFixedRows) {
    if (yb - ya < 2) {
      fixedRows(std::integral_constant<int, 2>{});
    } else {
      fixedRows(std::integral_constant<int, kFixedRows>{});
    }
    return;
  }
  for (int y = ya; y <= yb; ++y) {
    UnsignedVector v0 = rowValue0, v1 = rowValue1, v2 = rowValue2, limit = rowLimit;
    for (int x = xa, column = 0; x <= xb; x += kLanes, ++column) {
      const LaneVector all = LaneVector(v0 | v1 | v2 | limit);
      const i32x8 mask = nonNegative<kWidth>(all);  // all four non-negative
      fn(x, y, column, mask);
      v0 += chunk0, v1 += chunk1, v2 += chunk2, limit -= Unsigned(kLanes);
    }
    rowValue0 += row0, rowValue1 += row1, rowValue2 += row2;
  }
}

template <bool kVectorSteps, std::size_t kWidth, typename Real, typename Fn>
RC_KERNEL_INLINE void forEachCoveredChunk(const CoverageSetup<Real>& c, int bits, int xa, int ya, int xb, int yb,
                                          Fn&& fn) {
  if (c.flags & CoverageSetup<Real>::kNarrow) {
    coverRows<std::int32_t, kVectorSteps, kWidth>(c.edges(), bits, xa, ya, xb, yb, fn);
  } else {
    coverRows<std::int64_t, kVectorSteps, kWidth>(c.edges(), bits, xa, ya, xb, yb, fn);
  }
}

// Coverage without snapping (subpixelBits 0, --subpixel-bits none): edge i's E_i at a pixel
// centre c is the set-up's orientation sign times orientation(from, to, c) (orientation.h),
// decided exactly: its filter in eight lanes of double, the same operations in the same order,
// for the three edges at once; a chunk with a lane that the filter leaves open for some edge
// (a centre on the edge's line, or within about 1e-16 of its length of it) takes orientation()
// lane by lane, filter and exact path. A centre exactly on an edge is inside when the edge is top or
// left (the flags), as coverage.h decides it for snapped vertices: so two triangles that share an
// edge, whose vertices have the same raster positions, never both cover a centre and never both
// miss one between them. v: the unsnapped raster positions. Calls fn as coverRows does, for the
// rows ya..yb only.
//
// kAvx2Code: called from AVX2 or AVX-512 code, so that anyOf may test a mask in one instruction
// (the tests call it from baseline code, with the generic test).
template <std::size_t kWidth, bool kAvx2Code = false, typename Real, typename Fn>
RC_KERNEL_INLINE void coverRowsUnsnapped(const CoverageSetup<Real>& c, const glm::dvec2 v[3], int xa, int ya, int xb, int yb,
                                         Fn&& fn) {
  // Each edge's ends, swapped where the orientation is negative: the determinant of (b, a, c)
  // is that of (a, b, c) negated, bit for bit (its products are the same, their difference
  // turned round), so inside is where it is positive for every edge.
  const bool positive = c.flags & CoverageSetup<Real>::kPositive;
  double ax[3], ay[3], bx[3], by[3];
  bool topLeft[3];
  for (int i = 0; i < 3; ++i) {
    glm::dvec2 a = v[(i + 1) % 3], b = v[(i + 2) % 3];
    if (!positive) std::swap(a, b);
    ax[i] = a.x, ay[i] = a.y, bx[i] = b.x, by[i] = b.y;
    topLeft[i] = !((c.flags >> i) & CoverageSetup<Real>::kNotTopLeft);
  }
  const f64x8 lane{0, 1, 2, 3, 4, 5, 6, 7};
  const auto magnitude = [](const f64x8& d) __attribute__((always_inline)) {
    return f64x8(i64x8(d) & std::numeric_limits<std::int64_t>::max());
  };
  for (int y = ya; y <= yb; ++y) {
    const double cy = double(y) + 0.5;
    const double ayc[3] = {ay[0] - cy, ay[1] - cy, ay[2] - cy}, byc[3] = {by[0] - cy, by[1] - cy, by[2] - cy};
    for (int x = xa, column = 0; x <= xb; x += kLanes, ++column) {
      const f64x8 cx = (double(x) + 0.5) + lane;
      const i32x8 limit = split::lessEqual<kWidth>(iota32() + x, xb);
      // The filter for the three edges: inside where every determinant clears its bound, and
      // decided where every one's magnitude does.
      // Each comparison narrowed at once: GCC 12 lowers an and of two 512-bit comparisons, or a
      // negated one, lane by lane.
      i32x8 inside = limit, decided = limit;
#pragma GCC unroll 3
      for (int i = 0; i < 3; ++i) {
        const f64x8 left = (ax[i] - cx) * byc[i], right = ayc[i] * (bx[i] - cx), det = left - right;
        const f64x8 scaled = kOrientationBound * (magnitude(left) + magnitude(right));
        const f64x8 bound = split::select<kWidth>(split::greater<kWidth>(scaled, kOrientationFloor), scaled,
                                                  f64x8{} + kOrientationFloor);
        inside &= mask32(split::greater<kWidth>(det, bound));
        decided &= mask32(split::greater<kWidth>(magnitude(det), bound));
      }
      i32x8 mask = inside;
      if (anyOf<kAvx2Code>(decided ^ limit)) {
        // Rare: a centre on an edge's line or within about 1e-16 of its length of it. The
        // lane is decided by orientation.h's predicate (the same filter, then the exact sign).
        for (int k = 0; k < kLanes; ++k) {
          if (!limit[k]) continue;
          bool in = true;
          for (int i = 0; i < 3 && in; ++i) {
            const int e = orientation(ax[i], ay[i], bx[i], by[i], cx[k], cy);
            in = e > 0 || (e == 0 && topLeft[i]);
          }
          mask[k] = in ? -1 : 0;
        }
      }
      fn(x, y, column, mask);
    }
  }
}

// The unsnapped raster positions of set-up c's vertices: the frame's (the mesh's triangles
// index vertexRaster), or its clipped sub-triangle's among its block's `clipped`.
template <typename Real>
RC_KERNEL_INLINE void rasterOfSetup(const CoverageSetup<Real>& c, const glm::uvec3* triangles, const glm::dvec2* vertexRaster,
                                    const ClippedTriangle<Real>* clipped, glm::dvec2 v[3]) {
  if (c.source.clipped < 0) {
    const glm::uvec3 tri = triangles[c.source.triangle];
    v[0] = vertexRaster[tri.x], v[1] = vertexRaster[tri.y], v[2] = vertexRaster[tri.z];
  } else {
    const ClippedTriangle<Real>& t = clipped[c.source.clipped];
    v[0] = t.raster[0], v[1] = t.raster[1], v[2] = t.raster[2];
  }
}

// Everything written for the pixels of one winner, for the eight lanes of a chunk.
struct Resolved {
  f32x8 bary[3], depth, edgeDistance, depthTie;
};

// The resolve half of a set-up (setupShade), from the inputs its coverage half had.
template <typename Real>
inline void shadeSetupOf(const Input<Real>& in, std::uint32_t name, ShadeSetup<Real>& s) {
  const CoverageSetup<Real>& c = in.coverage[name >> kBlockShift][name & kLocalMask];
  const SetupSource& source = c.source;
  if (source.clipped < 0) {
    const glm::uvec3 tri = in.triangles[source.triangle];
    const glm::dvec4 clip[3] = {in.vertexClip[tri.x], in.vertexClip[tri.y], in.vertexClip[tri.z]};
    const glm::dvec2 raster[3] = {in.vertexRaster[tri.x], in.vertexRaster[tri.y], in.vertexRaster[tri.z]};
    setupShade(clip, raster, 0u, false, *in.context, c, s);
  } else {
    const ClippedTriangle<Real>& t = in.clipped[name >> kBlockShift][source.clipped];
    setupShade(t.clip, t.raster, t.innerEdges, true, *in.context, c, s);
  }
  s.triangle = source.triangle;
  s.clipMap = source.clipped;
}

// An attribute's values at a triangle's three vertices.
RC_KERNEL_INLINE void vertexValuesOf(const Outputs::Attribute& a, const glm::uvec3& tri, const float* v[3]) {
  const std::size_t n = std::size_t(a.components);
  v[0] = a.values + tri.x * n, v[1] = a.values + tri.y * n, v[2] = a.values + tri.z * n;
}

// shadeSetupOf for the set-ups at bins[winners[0..count)]: whole triangles four at a time
// through the batch set-up (setup_batch.h, the same bits), clipped sub-triangles one by one.
// Nothing is prefetched here: the records are still in cache from the coverage pass, and
// prefetching each winner's triangle, vertices and attributes a few winners ahead, which once
// took a millisecond off the tiles at 1M triangles, measured slower since (in one process,
// rounds alternating, 1M: 1 thread 32.2 against 31.2 ms of tiles, 2 threads 17.9 against 17.7;
// 100k the same). The attributes are prefetched in packShades, which reads them.
template <bool kAvx2, typename Real>
inline void shadeSetupsOf(const Input<Real>& in, const std::uint32_t* bins, const std::uint32_t* winners,
                          std::size_t count, ShadeSetup<Real>* shades) {
  glm::uvec3 tris[batch::kLanes];
  const CoverageSetup<Real>* coverage[batch::kLanes];
  ShadeSetup<Real>* into[batch::kLanes];
  ShadeSetup<Real> spare;
  int pending = 0;
  const auto flush = [&] {
    for (int k = pending; k < batch::kLanes; ++k) tris[k] = tris[0], coverage[k] = coverage[0], into[k] = &spare;
    if constexpr (kAvx2) {
      batch::setupShadeAvx2(tris, in.vertexClip, in.vertexRaster, *in.context, coverage, into);
    } else {
      batch::setupShadeSse2(tris, in.vertexClip, in.vertexRaster, *in.context, coverage, into);
    }
    pending = 0;
  };
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t name = bins[winners[i]];
    const SetupSource& own = in.coverage[name >> kBlockShift][name & kLocalMask].source;
    if (own.clipped >= 0) {
      shadeSetupOf(in, name, shades[i]);
      continue;
    }
    shades[i].triangle = own.triangle;
    shades[i].clipMap = -1;
    tris[pending] = in.triangles[own.triangle];
    coverage[pending] = &in.coverage[name >> kBlockShift][name & kLocalMask];
    into[pending] = &shades[i];
    if (++pending == batch::kLanes) flush();
  }
  if (pending > 0) flush();
}

// fn(std::integral_constant<int, n>{}) for an attribute's n components (meshes have 1 to 4), so
// that loops over them unroll: a loop over a runtime count cost as much in control as in work.
template <typename Fn>
RC_KERNEL_INLINE void withComponents(int n, Fn&& fn) {
  switch (n) {
    case 1: fn(std::integral_constant<int, 1>{}); break;
    case 2: fn(std::integral_constant<int, 2>{}); break;
    case 3: fn(std::integral_constant<int, 3>{}); break;
    default: fn(std::integral_constant<int, 4>{}); break;
  }
}

// std::fabs of a scalar, or of each lane of a float vector (the sign bit cleared).
template <typename T>
RC_KERNEL_INLINE T absOf(const T& v) {
  if constexpr (std::is_arithmetic_v<T>) {
    return std::fabs(v);
  } else {
    u32x8 bits;
    std::memcpy(&bits, &v, sizeof bits);
    bits &= 0x7FFFFFFFu;
    T r;
    std::memcpy(&r, &bits, sizeof r);
    return r;
  }
}

// The two per-pixel diagnostics (setup.h): the edge distance, the minimum over the source's edges
// of |l_i| height_i (a height below 0 marks an edge inside a clipped polygon, no source edge),
// and the depth tie, in Real (tieScale carries the rounding of this evaluation). H is the
// winner's scalars (winner by winner) or each lane's own (the gathered resolve); the operations
// and their order are the same either way.
template <std::size_t kWidth, typename V, typename H, typename Real>
RC_KERNEL_INLINE void diagnosticsOf(const V l[3], const H height[3], const H& key0, const H& keyX, const H& keyY,
                                    const V& dx, const H& dy, const V& depth, Real tieScale, V& edgeDistance,
                                    V& depthTie) {
  V nearest = split::splat<kWidth, V>(std::numeric_limits<Real>::infinity());
  for (int i = 0; i < 3; ++i) {
    const V d = split::select<kWidth>(split::less<kWidth>(l[i], Real(0)), -l[i], l[i]) * height[i];
    if constexpr (std::is_arithmetic_v<H>) {
      if (!(height[i] < Real(0))) nearest = split::select<kWidth>(split::less<kWidth>(d, nearest), d, nearest);
    } else {
      nearest = split::select<kWidth>(~split::less<kWidth>(height[i], Real(0)) & split::less<kWidth>(d, nearest), d,
                                      nearest);
    }
  }
  edgeDistance = nearest;
  const V kx = keyX * dx;
  const H ky = absOf(keyY * dy);
  const V terms = absOf(key0) + split::select<kWidth>(split::less<kWidth>(kx, Real(0)), -kx, kx) + ky;
  depthTie = tieScale * terms * depth;
}

// One attribute's kComponents components at barycentrics b, from its values at the three
// vertices, into rows `stride` floats apart: all eight lanes, or with kBlend only `mine`.
template <bool kBlend, int kComponents, std::size_t kWidth, typename V>
RC_KERNEL_INLINE void interpolateInto(const V b[3], const float* const v[3], float* into, std::size_t stride,
                                      const i32x8& mine) {
  using Real = decltype(b[0][0] + 0);
  for (int j = 0; j < kComponents; ++j, into += stride) {
    const f32x8 value = toFloat<Real>(b[0] * Real(v[0][j]) + b[1] * Real(v[1][j]) + b[2] * Real(v[2][j]));
    if constexpr (kBlend) {
      store(into, split::select<kWidth>(mine, value, load<f32x8>(into)));
    } else {
      store(into, value);
    }
  }
}

// The attributes go straight into `attributes` (one row of `stride` floats per component): all
// eight lanes, or with kBlend only the lanes set in `mine`.
template <bool kBlend, std::size_t kWidth, typename Real>
RC_KERNEL_INLINE void resolveLanes(const Input<Real>& in, const Outputs& out, std::uint32_t name,
                                   const ShadeSetup<Real>& s, int x, int y, Resolved& r, float* attributes,
                                   std::size_t stride, const i32x8& mine) {
  using V = typename Lanes<Real>::V;
  const CoverageSetup<Real>& c = in.coverage[name >> kBlockShift][name & kLocalMask];
  const V dx = Real(x - c.anchorX()) + iota<Real>();  // small integers: exact
  const Real dy = Real(y - c.anchorY());
  V l[3];
  for (int i = 0; i < 3; ++i) l[i] = s.l0[i] + s.lx[i] * dx + s.ly[i] * dy;
  const Recovered<V> recovered = in.perspective ? perspectiveCorrect(l, s.invW) : affineWeights(l, s.w);
  V b[3] = {recovered.b[0], recovered.b[1], recovered.b[2]};
  const V depth = recovered.depth;
  if (s.clipMap >= 0) {  // sub-triangle -> source triangle, in glm's mat3 * vec3 order
    const glm::mat<3, 3, Real>& m = in.clipped[name >> kBlockShift][s.clipMap].map;
    const V c0 = m[0][0] * b[0] + m[1][0] * b[1] + m[2][0] * b[2];
    const V c1 = m[0][1] * b[0] + m[1][1] * b[1] + m[2][1] * b[2];
    const V c2 = m[0][2] * b[0] + m[1][2] * b[1] + m[2][2] * b[2];
    b[0] = c0, b[1] = c1, b[2] = c2;
  }
  for (int i = 0; i < 3; ++i) r.bary[i] = toFloat<Real>(b[i]);
  r.depth = toFloat<Real>(depth);
  if (out.edgeDistance) {
    V edgeDistance, depthTie;
    diagnosticsOf<kWidth>(l, s.edgeHeight, c.key0, c.keyX, c.keyY, dx, dy, depth, in.tieScale, edgeDistance, depthTie);
    r.edgeDistance = toFloat<Real>(edgeDistance);
    r.depthTie = toFloat<Real>(depthTie);
  }
  const glm::uvec3& tri = in.triangles[s.triangle];
  float* into = attributes;
  for (const Outputs::Attribute& a : out.attributes) {
    const float* v[3];
    vertexValuesOf(a, tri, v);
    withComponents(a.components, [&](auto n) __attribute__((always_inline)) {
      interpolateInto<kBlend, decltype(n)::value, kWidth>(b, v, into, stride, mine);
    });
    into += stride * std::size_t(a.components);
  }
}

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

// Resolve writes each tile row into a small staging row per plane (in L1), then copies each
// plane's row out in one go (core/stream_row.h); renderTile ends with a store fence.
// streamStagedRow is that copy-out: plane p's staged row, stage + p * stride, to planes[p] +
// rowStart (null planes are not written), n values each. Whole tile rows take the AVX2 build's
// inline 32-byte stores (streamRowOf): frames at 1k triangles 5 to 8% faster than with a call
// per row and plane (docs/rasterizer.md, "The memory floor").
template <bool kAvx2>
RC_KERNEL_INLINE void streamStagedRow(std::uint32_t* const* planes, int count, const std::uint32_t* stage,
                                      std::size_t stride, std::size_t rowStart, int n) {
  for (int p = 0; p < count; ++p) {
    if (!planes[p]) continue;
    streamRowOf<kAvx2>(planes[p] + rowStart, stage + std::size_t(p) * stride, n);
  }
}
// The same, out of line, for writeOutPass (rasterizer.h): tile_kernel.cpp.
void streamStagedRowSse2(std::uint32_t* const* planes, int count, const std::uint32_t* stage, std::size_t stride,
                         std::size_t rowStart, int n);
void streamStagedRowAvx2(std::uint32_t* const* planes, int count, const std::uint32_t* stage, std::size_t stride,
                         std::size_t rowStart, int n);

// kWidth: the widest vector register the caller's target has, in bytes (16 SSE2, 32 AVX2, 64
// AVX-512), for the comparisons and selects (core/split_vectors.h).
template <typename Real, std::size_t kWidth>
RC_KERNEL_INLINE void renderTile(const Input<Real>& in, const Outputs& out, const TileJob& job) {
  constexpr bool kAvx2 = kWidth >= 32;
  using V = typename Lanes<Real>::V;
  using M = typename Lanes<Real>::M;
  // + a chunk of slack past the end, and the rows coverRows may run past a box at the tile's
  // bottom.
  constexpr int kPixels = kTileSize * kTileSize + (kFixedRows - 1) * kTileSize + kLanes;
  // Position in job.bins of each pixel's winner: below kMaxBlocks 2^20 (rasterizer.cpp), so
  // never kEmpty.
  alignas(64) std::uint32_t winner[kPixels];
  alignas(64) Real nearest[kPixels];  // depth key of the winner: larger is nearer
  for (int i = 0; i < kPixels; ++i) winner[i] = kEmpty;
  for (int i = 0; i < kPixels; ++i) nearest[i] = -std::numeric_limits<Real>::infinity();

  // Coverage and depth test, set-ups in triangle order; a tie keeps the earlier triangle. The
  // loop is made twice, with and without snapping, so that the default's holds no test of it.
  const auto coverage = [&](auto unsnapped) __attribute__((always_inline)) {
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
        Real* nearestAt = nearest + (y - job.y0) * kTileSize + (x - job.x0);
        std::uint32_t* winnerAt = winner + (y - job.y0) * kTileSize + (x - job.x0);
        const V old = load<V>(nearestAt);
        const M nearer = maskAs<M>(mask) & split::greater<kWidth>(z, old);
        const i32x8 update = mask32(nearer);
        // Branch-free: a chunk that changes nothing stores what it loaded.
        store(nearestAt, split::select<kWidth>(nearer, z, old));
        const u32x8 w = load<u32x8>(winnerAt);
        store(winnerAt, split::select<kWidth>(update, position, w));
      };
      if constexpr (!decltype(unsnapped)::value) {
        forEachCoveredChunk<kAvx2, kWidth>(c, in.subpixelBits, xa, ya, xb, yb, depthTest);
      } else {
        glm::dvec2 v[3];
        rasterOfSetup(c, in.triangles, in.vertexRaster, in.clipped[name >> kBlockShift], v);
        coverRowsUnsnapped<kWidth, kAvx2>(c, v, xa, ya, xb, yb, depthTest);
      }
    }
  };
  if (in.subpixelBits != 0) {
    coverage(std::false_type{});
  } else {
    coverage(std::true_type{});
  }

  // The resolve half of the set-up (setupShade) for every set-up that wins a pixel of this
  // tile, in bin order; set-ups that win nothing in the frame never get one. slot[n] is the
  // index in `shades` of the set-up at job.bins[n]. The arrays live per thread, reused from
  // tile to tile of a frame.
  thread_local std::vector<std::int32_t> slot;
  thread_local std::vector<std::uint32_t> winners;  // positions in job.bins, ascending
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
  const auto shadeOf = [&](std::uint32_t n) -> const ShadeSetup<Real>& { return shades[std::size_t(slot[n])]; };
  // Gathered resolve (float only) needs every winner whole: a clipped one's barycentrics go
  // through its map, which only the winner-by-winner path applies.
  // Records and staging rows start on a cache line, so that no 32-byte access straddles two
  // (core/line_allocator.h).
  thread_local std::vector<float, LineAllocator<float>> packs;
  constexpr std::size_t packStride = pack::kStride;
  bool gathered = false;
  if constexpr (sizeof(Real) == 4) {
    gathered = in.gatheredResolve && out.attributeComponents <= pack::kMaxComponents &&
               std::none_of(shades.begin(), shades.end(), [](const ShadeSetup<Real>& s) { return s.clipMap >= 0; });
    if (gathered) {
      packs.resize((job.count + 1) * packStride);  // + the empty pixels' record of zeros
      packShades(in, out, job.bins, winners.data(), shades.data(), winners.size(), packs.data());
      std::fill(packs.end() - std::ptrdiff_t(packStride), packs.end(), 0.0f);
    }
  }

  // Resolve, a row chunk at a time: one pass per distinct winner among its lanes.
  const int components = out.attributeComponents;
  const bool diagnostics = out.edgeDistance != nullptr;
  // Staging rows: id, b0..b2, depth, the four diagnostics, then the attribute components.
  constexpr int kFixedPlanes = 9, kStride = kTileSize + kLanes;
  // Per thread, reused from tile to tile like the arrays above: allocating and freeing them
  // per tile was about 2% of the samples at 100k triangles (free, and zeroing the rows).
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
      Resolved r{};
      std::uint32_t* at = stage.data() + (x - job.x0);
      float* attributesAt = reinterpret_cast<float*>(at + kFixedPlanes * kStride);
      u32x8 id;
      f32x8 baryBound, depthBound;
      // One winner: no blending.
      if (lanes == kLanes && !anyOf<kAvx2>(split::notEqual<kWidth>(w, w[0])) && w[0] != kEmpty) {
        const ShadeSetup<Real>& s = shadeOf(w[0]);
        resolveLanes<false, kWidth>(in, out, job.bins[w[0]], s, x, y, r, attributesAt, kStride, valid);
        id = split::splat<kWidth, u32x8>(s.triangle);
        baryBound = split::splat<kWidth, f32x8>(s.baryBound);
        depthBound = split::splat<kWidth, f32x8>(s.depthBound);
      } else if (gathered && moreRunsThan<kWidth>(w, kGatherAbove)) {
        if constexpr (sizeof(Real) == 4) {
          // Lane k's record is at its winner's position in the bins, an empty lane's after
          // the last. A lookup per lane through slot[] was 5% of the instructions at 100k
          // triangles; making the eight addresses in vector lanes and storing them measured
          // slower than this loop.
          const u32x8 position = split::select<kWidth>(valid, w, split::splat<kWidth, u32x8>(std::uint32_t(job.count)));
          const float* record[kLanes];
          for (int k = 0; k < kLanes; ++k) record[k] = packs.data() + std::size_t(position[k]) * packStride;
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
          const ShadeSetup<Real>& s = shadeOf(n);
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
    const std::size_t rowStart = std::size_t(y) * out.width + job.x0;
    const int n = job.x1 - job.x0 + 1;
    streamStagedRow<kAvx2>(planes.data(), kFixedPlanes + components, stage.data(), kStride, rowStart, n);
  }
  _mm_sfence();  // the non-temporal stores are visible before the tile counts as done
}

#pragma GCC diagnostic pop

}  // namespace rc::kernel
