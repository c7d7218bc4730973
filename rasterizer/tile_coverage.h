// The tile kernels' coverage: exact edge functions over a set-up's box, a row chunk of eight
// pixels at a time (snapped: coverage.h's integers; unsnapped: orientation.h's predicate),
// calling back for each chunk with the mask of covered pixel centres.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <type_traits>
#include <utility>

#include "core/split_vectors.h"
#include "rasterizer/coverage.h"
#include "rasterizer/kernel_lanes.h"
#include "rasterizer/orientation.h"
#include "rasterizer/setup.h"
#include "rasterizer/tile_kernel.h"

namespace rc::kernel {

// Vector values only ever pass between always-inlined functions, so the ABI of passing them
// (which differs with and without AVX) never matters.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

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
// (docs/rasterizer-speed.md, "Fixed row counts").
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

#pragma GCC diagnostic pop

}  // namespace rc::kernel
