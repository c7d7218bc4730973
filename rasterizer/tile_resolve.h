// The tile kernels' resolve, winner by winner: a winner's set-up completed (setupShade, four
// whole triangles at a time) and its pixels' barycentrics, depth, diagnostics and attributes
// computed for the lanes of a row chunk.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <type_traits>

#include "core/split_vectors.h"
#include "rasterizer/interpolate.h"
#include "rasterizer/kernel_lanes.h"
#include "rasterizer/setup.h"
#include "rasterizer/setup_batch.h"
#include "rasterizer/tile_kernel.h"

namespace rc::kernel {

// Vector values only ever pass between always-inlined functions, so the ABI of passing them
// (which differs with and without AVX) never matters.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// Everything written for the pixels of one winner, for the eight lanes of a chunk.
struct Resolved {
  f32x8 bary[3], depth, edgeDistance, depthTie;
};

// The resolve half of a set-up (setupShade), from the inputs its coverage half had: the set-up
// at `name` in the frame's precision, or, given a copy of its coverage record in another (Out)
// and that precision's context, in that one (tile_promote.h). s.clipMap is the set-up's own.
template <typename Real, typename Out>
inline void shadeSetupOf(const Input<Real>& in, std::uint32_t name, const SetupContext& context,
                         const CoverageSetup<Out>& c, ShadeSetup<Out>& s) {
  const SetupSource& source = c.source;
  if (source.clipped < 0) {
    const glm::uvec3 tri = in.triangles[source.triangle];
    const glm::dvec4 clip[3] = {in.vertexClip[tri.x], in.vertexClip[tri.y], in.vertexClip[tri.z]};
    const glm::dvec2 raster[3] = {in.vertexRaster[tri.x], in.vertexRaster[tri.y], in.vertexRaster[tri.z]};
    setupShade(clip, raster, 0u, false, context, c, s);
  } else {
    const ClippedTriangle& t = in.clipped[name >> kBlockShift][source.clipped];
    setupShade(t.clip, t.raster, t.innerEdges, true, context, c, s);
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
    const CoverageSetup<Real>& c = in.coverage[name >> kBlockShift][name & kLocalMask];
    const SetupSource& own = c.source;
    if (own.clipped >= 0) {
      shadeSetupOf(in, name, *in.context, c, shades[i]);
      continue;
    }
    shades[i].triangle = own.triangle;
    shades[i].clipMap = -1;
    tris[pending] = in.triangles[own.triangle];
    coverage[pending] = &c;
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

// The two per-pixel diagnostics (setup.h): the edge distance, the minimum over the set-up's edges
// of |l_i| height_i, and the depth tie, in Real (tieScale carries the rounding of this evaluation). H is the
// winner's scalars (winner by winner) or each lane's own (the gathered resolve); the operations
// and their order are the same either way.
template <std::size_t kWidth, typename V, typename H, typename Real>
RC_KERNEL_INLINE void diagnosticsOf(const V l[3], const H height[3], const H& key0, const H& keyX, const H& keyY,
                                    const V& dx, const H& dy, const V& depth, Real tieScale, V& edgeDistance,
                                    V& depthTie) {
  // A height below 0 (-height_i) marks a diagonal inside a clipped polygon: no edge of what is
  // drawn, so a centre inside the sub-triangle is not near an edge there. A centre outside it
  // across the diagonal (l_i < 0, covered by snapping) is measured to the diagonal, l_i height_i:
  // it lies outside the polygon (beyond a cut that meets the diagonal at a vertex) or inside
  // its neighbour, and snapping moves the diagonal as any edge.
  V nearest = split::splat<kWidth, V>(std::numeric_limits<Real>::infinity());
  for (int i = 0; i < 3; ++i) {
    if constexpr (std::is_arithmetic_v<H>) {
      if (!(height[i] < Real(0))) {
        const V d = split::select<kWidth>(split::less<kWidth>(l[i], Real(0)), -l[i], l[i]) * height[i];
        nearest = split::select<kWidth>(split::less<kWidth>(d, nearest), d, nearest);
      } else {
        const V d = l[i] * height[i];
        nearest = split::select<kWidth>(split::greater<kWidth>(d, Real(0)) & split::less<kWidth>(d, nearest), d, nearest);
      }
    } else {
      const auto inner = split::less<kWidth>(height[i], Real(0));
      const V d = split::select<kWidth>(split::less<kWidth>(l[i], Real(0)) & ~inner, -l[i], l[i]) * height[i];
      nearest = split::select<kWidth>((~inner | split::greater<kWidth>(d, Real(0))) & split::less<kWidth>(d, nearest), d,
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
    const glm::mat<3, 3, Real> m(in.clipped[name >> kBlockShift][s.clipMap].map);
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

#pragma GCC diagnostic pop

}  // namespace rc::kernel
