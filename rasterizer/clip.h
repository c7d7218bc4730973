// Clipping in homogeneous clip space, in barycentric space (as nvdiffrast does): every vertex
// of the clipped polygon carries its barycentrics relative to the ORIGINAL triangle, so the
// source triangle id and its barycentrics survive and no attribute is ever interpolated at an
// invented vertex. Planes: near (w >= zNear), far (w <= zFar, when finite) and a guard band
// (|x|, |y| <= k w) that keeps snapped coordinates inside the exact range of int64 edge math.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace rc {

inline constexpr int kMaxClipVertices = 9;  // 3 + one per plane (6 planes)
inline constexpr int kClipPlaneCount = 6;

// The guard band's half-width in pixels from the viewport centre: 2^(28 - bits), so that snapped
// positions stay below 2^29 grid steps (coverage.h); without snapping (bits 0), 2^20, as with 8
// bits: raster positions stay below 2^21.
inline double guardBandPixels(int subpixelBits) { return std::ldexp(1.0, 28 - (subpixelBits == 0 ? 8 : subpixelBits)); }

// A bound on the absolute error of each clip coordinate that the double transform
// clipFromWorld * (p, 1) computes, for world coordinates at most `largest` in magnitude: each is a
// 4-term dot product, error <= 4 u sum_j |M_rj| |p_j| <= 4 u (largest sum_{j<3} |M_rj| + |M_r3|).
inline double clipErrorBound(const glm::dmat4& clipFromWorld, double largest) {
  double bound = 0.0;
  for (int r = 0; r < 4; ++r) {
    double linear = 0.0;
    for (int c = 0; c < 3; ++c) linear += std::fabs(clipFromWorld[c][r]);
    bound = std::max(bound, linear * largest + std::fabs(clipFromWorld[3][r]));
  }
  return 4.0 * 0x1p-53 * bound;
}

template <typename Real>
struct ClipVertex {
  glm::vec<4, Real> clip;  // clip-space position
  glm::vec<3, Real> bary;  // barycentrics relative to the source triangle
};

template <typename Real>
struct ClipVolume {
  Real zNear;  // w >= zNear
  Real zFar;   // w <= zFar; +inf disables the plane
  Real guard;  // |x| <= guard * w and |y| <= guard * w

  // Signed distance of p to plane `plane`; >= 0 is inside.
  Real distance(const glm::vec<4, Real>& p, int plane) const {
    switch (plane) {
      case 0: return p.w - zNear;
      case 1: return std::isinf(zFar) ? Real(1) : zFar - p.w;
      case 2: return guard * p.w - p.x;
      case 3: return guard * p.w + p.x;
      case 4: return guard * p.w - p.y;
      default: return guard * p.w + p.y;
    }
  }

  // Bit i set when p is outside plane i.
  unsigned outcode(const glm::vec<4, Real>& p) const {
    unsigned code = 0;
    for (int i = 0; i < kClipPlaneCount; ++i) {
      if (!(distance(p, i) >= Real(0))) code |= 1u << i;
    }
    return code;
  }
};

// Sutherland-Hodgman over the planes set in `planes` (outcode bits). The intersection on an
// edge is always computed from its inside vertex towards its outside one, so two triangles
// sharing that edge produce bit-identical new vertices and stay watertight.
// Returns the vertex count of the convex polygon written to out (0 when nothing remains).
template <typename Real>
int clipPolygon(const ClipVertex<Real> in[3], const ClipVolume<Real>& volume, unsigned planes,
                ClipVertex<Real> out[kMaxClipVertices]) {
  ClipVertex<Real> buffers[2][kMaxClipVertices];
  ClipVertex<Real>* src = buffers[0];
  ClipVertex<Real>* dst = buffers[1];
  int count = 3;
  for (int i = 0; i < 3; ++i) src[i] = in[i];
  for (int plane = 0; plane < kClipPlaneCount && count > 0; ++plane) {
    if (!(planes & (1u << plane))) continue;
    int outCount = 0;
    for (int i = 0; i < count; ++i) {
      const ClipVertex<Real>& cur = src[i];
      const ClipVertex<Real>& next = src[(i + 1) % count];
      const Real dCur = volume.distance(cur.clip, plane);
      const Real dNext = volume.distance(next.clip, plane);
      const bool curIn = dCur >= Real(0), nextIn = dNext >= Real(0);
      if (curIn) dst[outCount++] = cur;
      if (curIn != nextIn) {
        const ClipVertex<Real>& inside = curIn ? cur : next;
        const ClipVertex<Real>& outside = curIn ? next : cur;
        const Real dIn = curIn ? dCur : dNext, dOut = curIn ? dNext : dCur;
        const Real t = dIn / (dIn - dOut);  // in [0, 1): dIn >= 0 > dOut
        dst[outCount++] = {inside.clip + t * (outside.clip - inside.clip),
                           inside.bary + t * (outside.bary - inside.bary)};
      }
    }
    count = outCount;
    std::swap(src, dst);
  }
  for (int i = 0; i < count; ++i) out[i] = src[i];
  return count;
}

}  // namespace rc
