// setupCoverage and setupShade for four triangles at once (setup_batch.h), in GCC vector
// extensions; the floating-point formulas are setup_formulas.h's, shared with setup.cpp. The
// snapped coordinates are carried twice: as int64 lanes for the exact area and the narrow
// test, and as doubles (integers below 2^30, so exact) for everything else, where SSE2 and
// AVX2 have the operations that int64 lanes lack (shifts, compares, conversions).
#include "rasterizer/setup_batch.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "rasterizer/orientation.h"
#include "rasterizer/setup_formulas.h"

// Vectors never cross a call boundary (kernel_lanes.h).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc::batch {
namespace {

using formulas::f64x4;
using formulas::i64x4;
using lanes::bitsAs;
using lanes::f32x4;
using lanes::i32x4;

#define RC_BATCH_INLINE inline __attribute__((always_inline))

// 1.5 * 2^52: x + kMagic, for |x| < 2^51, holds round(x) in its low mantissa bits (setup.cpp's
// roundToInteger).
constexpr double kMagic = 0x1.8p52;

// Comparisons and selects go through core/split_vectors.h with kWidth, the target's widest
// register in bytes: in the SSE2 build (16) a four-lane double or int64 vector is two
// registers wide, and GCC would lower them lane by lane, with a branch per lane in a select.
RC_BATCH_INLINE f64x4 roundToInteger(const f64x4& x) { return (x + kMagic) - kMagic; }
// floor and ceil of a multiple of a power of two below 2^51 (a shifted integer): exact.
template <std::size_t kWidth>
RC_BATCH_INLINE f64x4 floorOf(const f64x4& x) {
  const f64x4 r = roundToInteger(x);
  return split::select<kWidth>(split::greater<kWidth>(r, x), r - 1.0, r);
}
template <std::size_t kWidth>
RC_BATCH_INLINE f64x4 ceilOf(const f64x4& x) {
  const f64x4 r = roundToInteger(x);
  return split::select<kWidth>(split::less<kWidth>(r, x), r + 1.0, r);
}
template <std::size_t kWidth, typename V>
RC_BATCH_INLINE V minOf(const V& a, const V& b) { return split::select<kWidth>(split::less<kWidth>(a, b), a, b); }
template <std::size_t kWidth, typename V>
RC_BATCH_INLINE V maxOf(const V& a, const V& b) { return split::select<kWidth>(split::greater<kWidth>(a, b), a, b); }
// Integral doubles within int32 (the caller zeroes lanes it will not use) to int32.
RC_BATCH_INLINE i32x4 toInt32(const f64x4& v) { return __builtin_convertvector(v, i32x4); }

// Raster x, y and clip w of the lanes' vertices.
RC_BATCH_INLINE void gatherVertices(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                                    f64x4 rx[3], f64x4 ry[3], f64x4 w[3]) {
  for (int i = 0; i < 3; ++i) {
    const glm::dvec2 &r0 = raster[tris[0][i]], &r1 = raster[tris[1][i]];
    const glm::dvec2 &r2 = raster[tris[2][i]], &r3 = raster[tris[3][i]];
    rx[i] = f64x4{r0.x, r1.x, r2.x, r3.x};
    ry[i] = f64x4{r0.y, r1.y, r2.y, r3.y};
    w[i] = f64x4{clip[tris[0][i]].w, clip[tris[1][i]].w, clip[tris[2][i]].w, clip[tris[3][i]].w};
  }
}

// The flags of four set-ups from their vertices and the lanes whose area is positive:
// kPositive, and kNotTopLeft << i for each edge i that is not top or left (coverage.h's rule on
// the signs of a = y_from - y_to and b = x_to - x_from, normalised by the area's sign; the
// sign of a difference of doubles is exact).
template <std::size_t kWidth, typename Real>
RC_BATCH_INLINE i64x4 edgeFlags4(const f64x4 x[3], const f64x4 y[3], const i64x4& positive) {
  i64x4 flags = positive & std::int64_t(CoverageSetup<Real>::kPositive);
  for (int i = 0; i < 3; ++i) {
    const int from = (i + 1) % 3, to = (i + 2) % 3;
    const f64x4 a = y[from] - y[to], b = x[to] - x[from];
    const f64x4 ea = split::select<kWidth>(positive, a, -a), eb = split::select<kWidth>(positive, b, -b);
    const i64x4 topLeft =
        split::greater<kWidth>(ea, 0.0) | (split::equal<kWidth>(ea, 0.0) & split::greater<kWidth>(eb, 0.0));
    flags |= ~topLeft & std::int64_t(CoverageSetup<Real>::kNotTopLeft << i);
  }
  return flags;
}

// The rest of setupCoverage for four lanes with their boxes made: the anchor
// (CoverageSetup::anchorX, anchorY), the depth key plane, and the records of the lanes still
// accepted. xr, yr: the snapped vertices as integral doubles (zeros without snapping).
template <std::size_t kWidth, typename Real>
RC_BATCH_INLINE unsigned finishCoverage4(const f64x4 rx[3], const f64x4 ry[3], const f64x4 w[3], const f64x4& minX,
                                         const f64x4& minY, const f64x4& maxX, const f64x4& maxY, const f64x4 xr[3],
                                         const f64x4 yr[3], const i64x4& flags, i64x4 accept, const SetupContext& ctx,
                                         CoverageSetup<Real> c[kLanes]) {
  const f64x4 anchorX = minX + floorOf<kWidth>((maxX - minX) * 0.5);
  const f64x4 anchorY = minY + floorOf<kWidth>((maxY - minY) * 0.5);
  const f64x4 ax = anchorX + 0.5, ay = anchorY + 0.5;
  const formulas::Anchored<f64x4> an = formulas::anchoredOf(rx, ry, w, ax, ay);
  accept &= split::greater<kWidth>(lanes::absOf(an.area), an.noise);  // setup.cpp's setupPlanes
  const formulas::KeyPlane<f64x4> key = formulas::keyPlaneOf(an, ctx);

  // Out to the records, lane by lane; lanes not accepted are zeroed before the conversions.
  const auto ints = [&](const f64x4& v) { return toInt32(split::select<kWidth>(accept, v, f64x4{})); };
  const i32x4 minXi = ints(minX), minYi = ints(minY), maxXi = ints(maxX), maxYi = ints(maxY);
  i32x4 xi[3], yi[3];
  for (int i = 0; i < 3; ++i) xi[i] = ints(xr[i]), yi[i] = ints(yr[i]);
  unsigned accepted = 0;
  for (int k = 0; k < kLanes; ++k) {
    if (!accept[k]) continue;
    accepted |= 1u << k;
    CoverageSetup<Real>& out = c[k];
    out.minX = minXi[k], out.minY = minYi[k], out.maxX = maxXi[k], out.maxY = maxYi[k];
    for (int i = 0; i < 3; ++i) out.x[i] = xi[i][k], out.y[i] = yi[i][k];
    out.flags = std::uint32_t(flags[k]);
    out.key0 = Real(key.key0[k]), out.keyX = Real(key.keyX[k]), out.keyY = Real(key.keyY[k]);
  }
  return accepted;
}

// setupCoverage without snapping (setup.cpp's setupUnsnapped) for four lanes: the exact
// orientation from orientation.h's filter in lanes, and its exact path for the lanes the filter
// leaves open; the box from the double raster positions (ceil and floor of min - 0.5 and
// max - 0.5, |raster| below the guard band's 2^21 pixels).
template <std::size_t kWidth, typename Real>
RC_BATCH_INLINE unsigned setupUnsnapped4(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                                         const SetupContext& ctx, CoverageSetup<Real> c[kLanes]) {
  f64x4 rx[3], ry[3], w[3];
  gatherVertices(tris, clip, raster, rx, ry, w);
  // orientation(v0, v1, v2): the filter, then the exact sign where it cannot decide.
  const f64x4 left = (rx[0] - rx[2]) * (ry[1] - ry[2]), right = (ry[0] - ry[2]) * (rx[1] - rx[2]);
  const f64x4 det = left - right;
  const f64x4 scaled = kOrientationBound * (lanes::absOf(left) + lanes::absOf(right));
  const f64x4 bound = maxOf<kWidth>(scaled, f64x4{} + kOrientationFloor);
  i64x4 positive = split::greater<kWidth>(det, bound), negative = split::less<kWidth>(det, -bound);
  for (int k = 0; k < kLanes; ++k) {
    if (positive[k] | negative[k]) continue;
    const int sign = exactOrientation(rx[0][k], ry[0][k], rx[1][k], ry[1][k], rx[2][k], ry[2][k]);
    positive[k] = sign > 0 ? -1 : 0, negative[k] = sign < 0 ? -1 : 0;
  }
  i64x4 accept = ctx.cullBackFaces ? negative : positive | negative;
  const f64x4 minXr = minOf<kWidth>(rx[0], minOf<kWidth>(rx[1], rx[2]));
  const f64x4 maxXr = maxOf<kWidth>(rx[0], maxOf<kWidth>(rx[1], rx[2]));
  const f64x4 minYr = minOf<kWidth>(ry[0], minOf<kWidth>(ry[1], ry[2]));
  const f64x4 maxYr = maxOf<kWidth>(ry[0], maxOf<kWidth>(ry[1], ry[2]));
  const f64x4 minX = maxOf<kWidth>(f64x4{}, ceilOf<kWidth>(minXr - 0.5));
  const f64x4 minY = maxOf<kWidth>(f64x4{}, ceilOf<kWidth>(minYr - 0.5));
  const f64x4 maxX = minOf<kWidth>(f64x4{} + double(ctx.width - 1), floorOf<kWidth>(maxXr - 0.5));
  const f64x4 maxY = minOf<kWidth>(f64x4{} + double(ctx.height - 1), floorOf<kWidth>(maxYr - 0.5));
  accept &= split::lessEqual<kWidth>(minX, maxX) & split::lessEqual<kWidth>(minY, maxY);
  if (!(accept[0] | accept[1] | accept[2] | accept[3])) return 0u;
  const i64x4 flags = edgeFlags4<kWidth, Real>(rx, ry, positive);
  const f64x4 zero[3] = {};
  return finishCoverage4<kWidth>(rx, ry, w, minX, minY, maxX, maxY, zero, zero, flags, accept, ctx, c);
}

template <std::size_t kWidth, typename Real>
RC_BATCH_INLINE unsigned setupCoverage4(const glm::uvec3 tris[kLanes], const glm::dvec4* clip,
                                        const glm::dvec2* raster, const SetupContext& ctx,
                                        CoverageSetup<Real> c[kLanes]) {
  const int bits = ctx.subpixelBits;
  const double scale = double(std::int64_t(1) << bits), invScale = 1.0 / scale;
  f64x4 rx[3], ry[3], w[3];
  gatherVertices(tris, clip, raster, rx, ry, w);
  // Snapping, as setupCoverage: round to nearest, ties to even. The int64 lanes take the
  // integer out of the sum's bits.
  const i64x4 magicBits = bitsAs<i64x4>(f64x4{} + kMagic);
  f64x4 xr[3], yr[3];
  i64x4 xf[3], yf[3];
  for (int i = 0; i < 3; ++i) {
    const f64x4 sx = rx[i] * scale + kMagic, sy = ry[i] * scale + kMagic;
    xf[i] = bitsAs<i64x4>(sx) - magicBits;
    yf[i] = bitsAs<i64x4>(sy) - magicBits;
    xr[i] = sx - kMagic;
    yr[i] = sy - kMagic;
  }
  const i64x4 area = (xf[1] - xf[0]) * (yf[2] - yf[0]) - (yf[1] - yf[0]) * (xf[2] - xf[0]);
  i64x4 accept = split::notEqual<kWidth>(area, std::int64_t(0));
  if (ctx.cullBackFaces) accept &= split::lessEqual<kWidth>(area, std::int64_t(0));
  // The bounding box of pixel centres: ceil / floor of (coordinate - half) / 2^bits.
  const double half = 0.5 * scale;
  const f64x4 minXr = minOf<kWidth>(xr[0], minOf<kWidth>(xr[1], xr[2]));
  const f64x4 maxXr = maxOf<kWidth>(xr[0], maxOf<kWidth>(xr[1], xr[2]));
  const f64x4 minYr = minOf<kWidth>(yr[0], minOf<kWidth>(yr[1], yr[2]));
  const f64x4 maxYr = maxOf<kWidth>(yr[0], maxOf<kWidth>(yr[1], yr[2]));
  const f64x4 minX = maxOf<kWidth>(f64x4{}, ceilOf<kWidth>((minXr - half) * invScale));
  const f64x4 minY = maxOf<kWidth>(f64x4{}, ceilOf<kWidth>((minYr - half) * invScale));
  const f64x4 maxX = minOf<kWidth>(f64x4{} + double(ctx.width - 1), floorOf<kWidth>((maxXr - half) * invScale));
  const f64x4 maxY = minOf<kWidth>(f64x4{} + double(ctx.height - 1), floorOf<kWidth>((maxYr - half) * invScale));
  accept &= split::lessEqual<kWidth>(minX, maxX) & split::lessEqual<kWidth>(minY, maxY);
  if (!(accept[0] | accept[1] | accept[2] | accept[3])) return 0u;

  i64x4 flags = edgeFlags4<kWidth, Real>(xr, yr, split::greater<kWidth>(area, std::int64_t(0)));
  // The narrow test, spans clamped to 2^30 so that no product overflows (a span that large
  // already fails it).
  const i64x4 limit = i64x4{} + (std::int64_t(1) << 30), one = i64x4{} + (std::int64_t(1) << bits);
  const i64x4 spanX =
      maxOf<kWidth>(xf[0], maxOf<kWidth>(xf[1], xf[2])) - minOf<kWidth>(xf[0], minOf<kWidth>(xf[1], xf[2]));
  const i64x4 spanY =
      maxOf<kWidth>(yf[0], maxOf<kWidth>(yf[1], yf[2])) - minOf<kWidth>(yf[0], minOf<kWidth>(yf[1], yf[2]));
  const i64x4 sx = minOf<kWidth>(spanX, limit), sy = minOf<kWidth>(spanY, limit);
  const i64x4 narrow = split::less<kWidth>(spanX, limit) & split::less<kWidth>(spanY, limit) &
                       split::less<kWidth>(sy * (sx + 9 * one) + sx * (sy + one) + 1, std::int64_t(1) << 31);
  flags |= narrow & std::int64_t(CoverageSetup<Real>::kNarrow);

  return finishCoverage4<kWidth>(rx, ry, w, minX, minY, maxX, maxY, xr, yr, flags, accept, ctx, c);
}

template <std::size_t kWidth, typename Real>
RC_BATCH_INLINE void setupShade4(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                                 const SetupContext& ctx, const CoverageSetup<Real>* const c[kLanes],
                                 ShadeSetup<Real>* const s[kLanes]) {
  f64x4 rx[3], ry[3], w[3], cx[3], cy[3];
  gatherVertices(tris, clip, raster, rx, ry, w);
  for (int i = 0; i < 3; ++i) {
    cx[i] = f64x4{clip[tris[0][i]].x, clip[tris[1][i]].x, clip[tris[2][i]].x, clip[tris[3][i]].x};
    cy[i] = f64x4{clip[tris[0][i]].y, clip[tris[1][i]].y, clip[tris[2][i]].y, clip[tris[3][i]].y};
  }
  // As setupShade.
  const f64x4 ax = f64x4{double(c[0]->anchorX()), double(c[1]->anchorX()), double(c[2]->anchorX()), double(c[3]->anchorX())} + 0.5;
  const f64x4 ay = f64x4{double(c[0]->anchorY()), double(c[1]->anchorY()), double(c[2]->anchorY()), double(c[3]->anchorY())} + 0.5;
  const formulas::Anchored<f64x4> an = formulas::anchoredOf(rx, ry, w, ax, ay);
  const formulas::Planes<f64x4> p = formulas::planesOf<kWidth>(an);
  f64x4 R;
  for (int k = 0; k < kLanes; ++k) {
    const CoverageSetup<Real>& b = *c[k];
    R[k] = std::max({b.anchorX() - b.minX, b.maxX - b.anchorX(), b.anchorY() - b.minY, b.maxY - b.anchorY(), 0}) + 0.0;
  }
  const formulas::Bounds<f64x4> bounds = formulas::boundsOf<kWidth>(p, R, rx, ry, cx, cy, w, ctx, false);

  for (int k = 0; k < kLanes; ++k) {
    ShadeSetup<Real>& out = *s[k];
    for (int i = 0; i < 3; ++i) {
      out.w[i] = Real(w[i][k]);
      out.invW[i] = Real(an.invW[i][k]);
      out.l0[i] = Real(p.l0[i][k]);
      out.lx[i] = Real(p.lx[i][k]);
      out.ly[i] = Real(p.ly[i][k]);
      out.edgeHeight[i] = Real(p.height[i][k]);
    }
    out.baryBound = float(bounds.bary[k]);
    out.depthBound = float(bounds.depth[k]);
  }
}

}  // namespace

// The entry points are overloads, one per target and precision: GCC 12 drops the target
// attribute of a function template's explicit instantiation (an AVX2 one came out with no ymm
// register). RC_COVERAGE_ENTRY defines a name's two, for float and double records.
#define RC_COVERAGE_ENTRY(kTarget, name, body, kWidth)                                                        \
  kTarget unsigned name(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,      \
                        const SetupContext& ctx, CoverageSetup<float> c[kLanes]) {                            \
    return body<kWidth>(tris, clip, raster, ctx, c);                                                          \
  }                                                                                                           \
  kTarget unsigned name(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,      \
                        const SetupContext& ctx, CoverageSetup<double> c[kLanes]) {                           \
    return body<kWidth>(tris, clip, raster, ctx, c);                                                          \
  }
#define RC_BATCH_BASELINE
#define RC_BATCH_AVX2 __attribute__((target("avx2")))
#define RC_BATCH_AVX512 __attribute__((target("avx2,avx512f,avx512vl,avx512dq,avx512bw")))
RC_COVERAGE_ENTRY(RC_BATCH_BASELINE, setupCoverageSse2, setupCoverage4, 16)
RC_COVERAGE_ENTRY(RC_BATCH_AVX2, setupCoverageAvx2, setupCoverage4, 32)
RC_COVERAGE_ENTRY(RC_BATCH_AVX512, setupCoverageAvx512, setupCoverage4, 64)
RC_COVERAGE_ENTRY(RC_BATCH_BASELINE, setupUnsnappedSse2, setupUnsnapped4, 16)
RC_COVERAGE_ENTRY(RC_BATCH_AVX2, setupUnsnappedAvx2, setupUnsnapped4, 32)
#undef RC_COVERAGE_ENTRY

void setupShadeSse2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                    const SetupContext& ctx, const CoverageSetup<float>* const c[kLanes],
                    ShadeSetup<float>* const s[kLanes]) {
  setupShade4<16>(tris, clip, raster, ctx, c, s);
}
void setupShadeSse2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                    const SetupContext& ctx, const CoverageSetup<double>* const c[kLanes],
                    ShadeSetup<double>* const s[kLanes]) {
  setupShade4<16>(tris, clip, raster, ctx, c, s);
}
__attribute__((target("avx2"))) void setupShadeAvx2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip,
                                                    const glm::dvec2* raster, const SetupContext& ctx,
                                                    const CoverageSetup<float>* const c[kLanes],
                                                    ShadeSetup<float>* const s[kLanes]) {
  setupShade4<32>(tris, clip, raster, ctx, c, s);
}
__attribute__((target("avx2"))) void setupShadeAvx2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip,
                                                    const glm::dvec2* raster, const SetupContext& ctx,
                                                    const CoverageSetup<double>* const c[kLanes],
                                                    ShadeSetup<double>* const s[kLanes]) {
  setupShade4<32>(tris, clip, raster, ctx, c, s);
}

}  // namespace rc::batch
