// The reference's band tracer (trace_band.h). Every value is computed by the formulas of
// ray_triangle.h and Camera::directionThroughRaster on four lanes of doubles, the operations
// and their order those of one double, so each lane has the bits of the one-pixel code
// (-ffp-contract=off; "avx2" does not enable FMA).
#include "raytracer_ref/trace_band.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/channels.h"
#include "core/lanes.h"
#include "core/line_allocator.h"
#include "core/stream_row.h"
#include "raytracer_ref/ray_triangle.h"

// Vectors pass only between always-inlined functions (core/lanes.h).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace rc::reference {
namespace {

using lanes::f32x4;
using lanes::f64x4;
using lanes::i32x4;
using lanes::i64x4;
using lanes::u32x4;
using lanes::Vec3;

// What a hit needs of its triangle: the frame, and for the screen distance to the nearest edge
// of what the eye sees of it, planes through the eye: one through each edge, and where the
// triangle crosses the near or the far plane (the rays start at near and end at far), one
// through that cut, which is an edge too.
template <typename V>
struct HitTriangle {
  TriangleFrame<V> frame;
  Vec3<V> normal[5];  // of the plane through the origin and the edge opposite vertex i; 3, 4: the cuts
  V inPlane[5];       // length of its part in the image plane; 0 for a cut the triangle does not make
  int planes;         // 3, or 5 where a lane's triangle crosses the near or the far plane
};

template <std::size_t kWidth, typename V>
RC_LANES_INLINE HitTriangle<V> hitTriangleOf(const Vec3<V> p[3], const Vec3<V>& origin, const Vec3<V>& forward,
                                             bool clipCuts, double zNear, double zFar) {
  HitTriangle<V> h;
  h.frame = triangleFrame<kWidth>(origin, p[0], p[1], p[2]);
  for (int i = 0; i < 3; ++i) {
    h.normal[i] = lanes::cross(p[(i + 1) % 3] - origin, p[(i + 2) % 3] - origin);
    h.inPlane[i] = lanes::length(h.normal[i] - lanes::dot(h.normal[i], forward) * forward);
  }
  h.planes = 3;
  if (!clipCuts) return h;  // no vertex of the mesh nearer than near or beyond far
  // The triangle's plane n . (x - p0) = 0 meets a ray o + t d (d . forward = 1, so t is the
  // depth) at t = c / (n . d), c = n . (p0 - o): at depth z where (n - (c / z) forward) . d = 0.
  const V depth[3] = {lanes::dot(p[0] - origin, forward), lanes::dot(p[1] - origin, forward),
                      lanes::dot(p[2] - origin, forward)};
  const V nearest = lanes::stdMin<kWidth>(depth[0], lanes::stdMin<kWidth>(depth[1], depth[2]));
  const V farthest = lanes::stdMax<kWidth>(depth[0], lanes::stdMax<kWidth>(depth[1], depth[2]));
  const Vec3<V> n = lanes::cross(h.frame.e1, h.frame.e2);
  const V c = -lanes::dot(n, h.frame.T);
  const auto cut = [&](int i, double z, const auto& crosses) __attribute__((always_inline)) {
    h.normal[i] = n - (c / z) * forward;
    const V length = lanes::length(h.normal[i] - lanes::dot(h.normal[i], forward) * forward);
    h.inPlane[i] = lanes::select<kWidth>(crosses, length, V{});
    return (crosses[0] | crosses[1] | crosses[2] | crosses[3]) != 0;
  };
  const bool nearCut = cut(3, zNear, split::less<kWidth>(nearest, zNear));
  const bool farCut = cut(4, zFar, split::greater<kWidth>(farthest, zFar));  // never with an infinite far
  h.planes = nearCut || farCut ? 5 : 3;
  return h;
}

// Vertex `corner` of each lane's triangle, in double.
RC_LANES_INLINE Vec3<f64x4> cornerOf(const Mesh& mesh, const std::uint32_t triangle[kBlock], int corner) {
  Vec3<f64x4> p;
  for (int k = 0; k < kBlock; ++k) {
    const glm::vec3& v = mesh.positions[mesh.triangles[triangle[k]][corner]];
    p.x[k] = double(v.x);
    p.y[k] = double(v.y);
    p.z[k] = double(v.z);
  }
  return p;
}

RC_LANES_INLINE f32x4 toFloat(const f64x4& v) { return __builtin_convertvector(v, f32x4); }

// A strip of kBlock rows by kStrip pixels is staged per plane (in L1), then streamed out row
// by row (core/stream_row.h): the planes' memory traffic is then only the stores.
constexpr int kStrip = 64;
constexpr int kStagePlane = kBlock * kStrip;  // values of one plane in the stage

template <typename Lanes>
RC_LANES_INLINE void store(std::uint32_t* at, const Lanes& v) {
  static_assert(sizeof v == kBlock * sizeof(std::uint32_t));
  std::memcpy(at, &v, sizeof v);
}

// A block row's shading: lanes whose `hit` is zero are misses and get zeros.
struct Row {
  std::uint32_t triangle[kBlock];
  i32x4 hit;
  std::uint32_t* stage;  // lane 0's value of plane 0; plane p is kStagePlane further
};

// kAvx2 only keeps the two builds' instantiations apart; everything is inlined into them.
template <bool kAvx2>
struct Tracer {
  // The widest register, for the comparisons and selects (core/lanes.h, core/split_vectors.h).
  static constexpr std::size_t kWidth = kAvx2 ? 32 : 16;
  const BandInput& in;
  const Camera& camera;
  const Mesh& mesh;
  const Vec3<f64x4> origin, forward;
  const double pixelsPerUnit;
  // The last triangle that filled a whole block row, in every lane: neighbouring rows on one
  // triangle share it.
  std::uint32_t lastTriangle = std::numeric_limits<std::uint32_t>::max();
  HitTriangle<f64x4> last{};
  const float tFar;  // of every ray, reset before each packet
  // |Embree's b - b|^2, largest per lane; its square root at the end is the largest of the
  // square roots (sqrt is correctly rounded, so monotonic), as glm::length gives them.
  // lanes::stdMax, like std::max, skips a NaN.
  f64x4 embreeDiffSquaredMax{};
  std::vector<std::uint32_t, LineAllocator<std::uint32_t>> stage;  // on a cache line, as the tiles' rows

  RC_LANES_INLINE explicit Tracer(const BandInput& input)
      : in(input), camera(*input.camera), mesh(*input.mesh),
        origin(lanes::splat(lanes::vec3Of(camera.spec().eye))),
        forward(lanes::splat(lanes::vec3Of(camera.forward()))),
        pixelsPerUnit(camera.height() / (2.0 * camera.tanHalfFovY())),
        tFar(std::isinf(camera.zFar()) ? std::numeric_limits<float>::infinity() : float(camera.zFar())),
        stage(input.planes.size() * kStagePlane) {}

  RC_LANES_INLINE void shade(const Row& row, const Vec3<f64x4>& d, const f64x4& u, const f64x4& v,
                             const f64x4& tfar) {
    // The lanes' triangle: one shared (misses take the first hit's) or one each.
    std::uint32_t triangle[kBlock];
    int first = 0;
    while (!row.hit[first]) ++first;
    bool shared = true;
    for (int k = 0; k < kBlock; ++k) {
      triangle[k] = row.hit[k] ? row.triangle[k] : row.triangle[first];
      shared = shared && triangle[k] == triangle[first];
    }
    HitTriangle<f64x4> each;
    const HitTriangle<f64x4>* h = &last;
    if (!shared || triangle[first] != lastTriangle) {
      const Vec3<f64x4> p[3] = {cornerOf(mesh, triangle, 0), cornerOf(mesh, triangle, 1),
                                cornerOf(mesh, triangle, 2)};
      if (shared) {
        last = hitTriangleOf<kWidth>(p, origin, forward, in.clipCuts, camera.zNear(), camera.zFar());
        lastTriangle = triangle[first];
      } else {
        each = hitTriangleOf<kWidth>(p, origin, forward, in.clipCuts, camera.zNear(), camera.zFar());
        h = &each;
      }
    }

    const auto hit = intersectRay<kWidth>(h->frame, d);
    // Parallel to the plane: no unique point; Embree's, unbounded.
    const Vec3<f64x4> embree = baryFromEmbreeUv(u, v);
    const i64x4 valid = hit.valid;
    const f64x4 infinity = lanes::splat(std::numeric_limits<double>::infinity());
    const Vec3<f64x4> b = {lanes::select<kWidth>(valid, hit.b.x, embree.x),
                           lanes::select<kWidth>(valid, hit.b.y, embree.y),
                           lanes::select<kWidth>(valid, hit.b.z, embree.z)};
    const f64x4 t = lanes::select<kWidth>(valid, hit.t, tfar);
    const f64x4 baryBound = lanes::select<kWidth>(valid, hit.baryBound, infinity);
    const f64x4 depthBound = lanes::select<kWidth>(valid, hit.depthBound, infinity);
    if (!in.source) {
      const Vec3<f64x4> diff = hit.b - embree;
      const i64x4 counted = valid & __builtin_convertvector(row.hit, i64x4);
      embreeDiffSquaredMax = lanes::select<kWidth>(
          counted, lanes::stdMax<kWidth>(embreeDiffSquaredMax, lanes::dot(diff, diff)), embreeDiffSquaredMax);
    }

    const auto write = [&](int plane, const f64x4& value) __attribute__((always_inline)) {
      store(row.stage + plane * kStagePlane, lanes::bitsAs<i32x4>(toFloat(value)) & row.hit);
    };
    const i32x4 id = lanes::bitsAs<i32x4>(u32x4{triangle[0], triangle[1], triangle[2], triangle[3]});
    store(row.stage + kIdPlane * kStagePlane, id | ~row.hit);  // kNoTriangle is all ones
    write(kBaryPlane, b.x);
    write(kBaryPlane + 1, b.y);
    write(kBaryPlane + 2, b.z);
    write(kDepthPlane, t * lanes::dot(d, forward));
    // Float output rounds each value once more: half an ulp of numbers below 2 (b leaves
    // [0, 1] only within Embree's band), 2^-23 relative for depth.
    write(kBaryBoundPlane, baryBound + 0x1p-23);
    write(kDepthBoundPlane, depthBound + 0x1p-23);
    // Screen distance to the edge opposite vertex i (and to the cuts): the pixel's direction d
    // against the plane through the eye and that edge, measured in the image plane d . forward = 1.
    f64x4 nearest = infinity;
    const auto toPlane = [&](int i) __attribute__((always_inline)) {
      const f64x4 length = h->inPlane[i];
      const i64x4 positive = split::greater<kWidth>(length, 0.0);
      const f64x4 distance = lanes::absOf(lanes::dot(d, h->normal[i])) /
                             lanes::select<kWidth>(positive, length, lanes::splat(1.0)) * pixelsPerUnit;
      // std::min(nearest, distance)
      nearest = lanes::select<kWidth>(positive & split::less<kWidth>(distance, nearest), distance, nearest);
    };
    for (int i = 0; i < 3; ++i) toPlane(i);  // a constant count, unrolled
    if (h->planes == 5) toPlane(3), toPlane(4);
    write(kEdgeDistancePlane, nearest);
    glm::uvec3 tris[kBlock];
    for (int k = 0; k < kBlock; ++k) tris[k] = mesh.triangles[triangle[k]];
    int plane = kAttributePlanes;
    for (const BandInput::Attribute& a : in.attributes) {
      const int n = a.components;
      f64x4 spread{};
      for (int c = 0; c < n; ++c) {
        f64x4 value[3]{};
        if (shared) {
          for (int i = 0; i < 3; ++i) value[i] = lanes::splat(double(a.values[std::size_t(tris[0][i]) * n + c]));
        } else {
          for (int k = 0; k < kBlock; ++k) {
            for (int i = 0; i < 3; ++i) value[i][k] = double(a.values[std::size_t(tris[k][i]) * n + c]);
          }
        }
        write(plane++, b.x * value[0] + b.y * value[1] + b.z * value[2]);
        const f64x4 high = lanes::stdMax<kWidth>(value[0], lanes::stdMax<kWidth>(value[1], value[2]));
        const f64x4 low = lanes::stdMin<kWidth>(value[0], lanes::stdMin<kWidth>(value[1], value[2]));
        spread = lanes::stdMax<kWidth>(spread, high - low);
      }
      // Rounded up to float: compare's bound must not shrink by the output's rounding.
      write(plane++, spread * (1.0 + 0x1p-23));
    }
  }

  RC_LANES_INLINE void missRow(const Row& row) {
    store(row.stage + kIdPlane * kStagePlane, u32x4{} + channels::kNoTriangle);
    for (std::size_t plane = kIdPlane + 1; plane < in.planes.size(); ++plane) {
      store(row.stage + plane * kStagePlane, u32x4{});  // 0.0f
    }
  }

  RC_LANES_INLINE double run(int y0, int y1) {
    const int width = camera.width();
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    // Embree changes only the hits and tfar: the other inputs are set once per band (zeroing
    // the 1.3 kB packet per block cost 6% of a frame).
    alignas(64) RTCRayHit16 rh{};
    const float tNear = float(camera.zNear());
    for (int lane = 0; lane < 16; ++lane) {
      rh.ray.org_x[lane] = rh.ray.org_y[lane] = rh.ray.org_z[lane] = 0.0f;  // camera-relative geometry
      rh.ray.tnear[lane] = tNear;
      rh.ray.mask[lane] = 0xFFFFFFFFu;
    }
    for (int yb = y0; yb < y1; yb += kBlock) {
      const int rows = std::min(kBlock, y1 - yb);
      double up[kBlock];
      for (int r = 0; r < kBlock; ++r) up[r] = camera.upOffset(Camera::pixelCenter(0, yb + r).y);
      for (int strip = 0; strip < width; strip += kStrip) {
        const int stripEnd = std::min(width, strip + kStrip);
        for (int x0 = strip; x0 < stripEnd; x0 += kBlock) traceBlock(rh, context, rows, x0, up, strip);
        for (std::size_t plane = 0; plane < in.planes.size(); ++plane) {
          for (int r = 0; r < rows; ++r) {
            streamRowOf<kAvx2>(in.planes[plane] + std::size_t(yb + r) * width + strip,
                      stage.data() + plane * kStagePlane + r * kStrip, stripEnd - strip);
          }
        }
      }
    }
    _mm_sfence();  // the non-temporal stores are visible before the band counts as done
    double largest = 0.0;
    for (int k = 0; k < kBlock; ++k) largest = std::max(largest, embreeDiffSquaredMax[k]);
    return std::sqrt(largest);
  }

  // One packet: the 4x4 block at column x0 of the current block row, of which the first
  // `rows` rows are in the band; up: the rows' Camera::upOffset. Its values go to the stage,
  // which holds the columns from `strip` on.
  RC_LANES_INLINE void traceBlock(RTCRayHit16& rh, RTCIntersectContext& context, int rows, int x0,
                                  const double up[kBlock], int strip) {
    const int width = camera.width();
    alignas(64) int valid[16];
    Vec3<f64x4> d[kBlock];
    int n[kBlock];
    for (int r = 0; r < kBlock; ++r) {
      n[r] = r < rows ? std::min(kBlock, width - x0) : 0;
      f64x4 right;
      std::memcpy(&right, in.rightOffsets + x0, sizeof right);
      d[r] = camera.directionFromOffsets(right, lanes::splat(up[r]));
      const f32x4 dx = toFloat(d[r].x), dy = toFloat(d[r].y), dz = toFloat(d[r].z);
      std::memcpy(rh.ray.dir_x + kBlock * r, &dx, sizeof dx);
      std::memcpy(rh.ray.dir_y + kBlock * r, &dy, sizeof dy);
      std::memcpy(rh.ray.dir_z + kBlock * r, &dz, sizeof dz);
      for (int k = 0; k < kBlock; ++k) {
        valid[kBlock * r + k] = k < n[r] ? -1 : 0;
        rh.ray.tfar[kBlock * r + k] = tFar;
        rh.hit.geomID[kBlock * r + k] = RTC_INVALID_GEOMETRY_ID;
      }
    }
    rtcIntersect16(valid, in.scene, &context, &rh);
    for (int r = 0; r < kBlock; ++r) {
      if (n[r] == 0) continue;
      Row row{};
      row.stage = stage.data() + r * kStrip + (x0 - strip);
      bool any = false;
      for (int k = 0; k < kBlock; ++k) {
        const int lane = kBlock * r + k;
        const bool hit = valid[lane] && rh.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID;
        row.hit[k] = hit ? -1 : 0;
        row.triangle[k] = hit ? (in.source ? in.source[rh.hit.primID[lane]] : rh.hit.primID[lane]) : 0u;
        any = any || hit;
      }
      if (!any) {
        missRow(row);
        continue;
      }
      f32x4 u, v, tfar;
      std::memcpy(&u, rh.hit.u + kBlock * r, sizeof u);
      std::memcpy(&v, rh.hit.v + kBlock * r, sizeof v);
      std::memcpy(&tfar, rh.ray.tfar + kBlock * r, sizeof tfar);
      shade(row, d[r], __builtin_convertvector(u, f64x4), __builtin_convertvector(v, f64x4),
            __builtin_convertvector(tfar, f64x4));
    }
  }
};

}  // namespace

std::vector<double> rightOffsetsOf(const Camera& camera) {
  std::vector<double> offsets((camera.width() + kBlock - 1) / kBlock * kBlock, 0.0);
  for (int x = 0; x < camera.width(); ++x) offsets[x] = camera.rightOffset(Camera::pixelCenter(x, 0).x);
  return offsets;
}

double traceBandSse2(const BandInput& in, int y0, int y1) { return Tracer<false>(in).run(y0, y1); }

__attribute__((target("avx2"))) double traceBandAvx2(const BandInput& in, int y0, int y1) {
  return Tracer<true>(in).run(y0, y1);
}

}  // namespace rc::reference
