// The Embree reference renderer.
//
// Precision per stage: Embree gets camera-relative float geometry (vertex - eye, computed in
// double, rounded once), with triangles too long for their distance split (subdivide.h), and
// rays from the origin, so its hit decision does not degrade with the world offset. Embree only
// chooses the triangle; everything written is recomputed in double from the mesh's own float
// vertices and the camera's double ray, with its error bound (docs/numerics.md).
#include "raytracer_ref/reference.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/channels.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/preview.h"
#include "raytracer_ref/embree_device.h"
#include "raytracer_ref/ray_triangle.h"
#include "raytracer_ref/subdivide.h"

namespace rc {
namespace {

constexpr int kRowsPerTask = 8;

bool cpuSupports(const std::string& isa) {
  if (isa == "sse2") return __builtin_cpu_supports("sse2");
  if (isa == "sse4.2") return __builtin_cpu_supports("sse4.2");
  if (isa == "avx") return __builtin_cpu_supports("avx");
  if (isa == "avx2") return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (isa == "avx512") return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
  throw usageError("--embree-isa must be one of sse2, sse4.2, avx, avx2, avx512; got '" + isa + "'");
}

// Returns the mesh triangle of each Embree triangle (empty: the same index).
std::vector<std::uint32_t> buildGeometry(EmbreeDevice& device, EmbreeScene& scene, const Mesh& mesh,
                                         const Camera& camera) {
  EmbreeTriangles triangles = embreeTriangles(mesh, camera);
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  device.check("rtcNewGeometry");
  const std::size_t vertexCount = triangles.vertices.size() / 3, triangleCount = triangles.indices.size() / 3;
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangleCount));
  device.check("rtcSetNewGeometryBuffer");
  std::copy(triangles.vertices.begin(), triangles.vertices.end(), vertices);
  std::copy(triangles.indices.begin(), triangles.indices.end(), indices);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene.get(), geometry);
  rtcReleaseGeometry(geometry);
  device.check("building the geometry");
  rtcCommitScene(scene.get());
  device.check("rtcCommitScene");
  return std::move(triangles.source);
}

struct Planes {
  std::uint32_t* id;
  float* bary[3];
  float* depth;
  float* baryBound;
  float* depthBound;
  float* edgeDistance;
  std::vector<std::pair<const Attribute*, std::array<float*, 4>>> attributes;
};

// Embree's float hit test, on triangles no longer than kMaxLengthOverDistance times their
// distance, errs in angle by at most about 8 (1 + kMaxLengthOverDistance) u_float (the factor
// 8 covers the few roundings of its edge tests); in pixels, that angle is scaled by the image
// plane's pixels per unit, and by up to 1 + tan^2 at the image's corners.
double referenceEdgeBand(const Camera& camera) {
  const double tanY = camera.tanHalfFovY(), tanX = tanY * camera.aspect();
  const double pixelsPerUnit = camera.height() / (2.0 * tanY);
  return 8.0 * (1.0 + kMaxLengthOverDistance) * 0x1p-24 * pixelsPerUnit * (1.0 + tanX * tanX + tanY * tanY);
}

}  // namespace

struct ReferenceTracer::Impl {
  const Scene& scene;
  ReferenceOptions options;
  int threads;
  EmbreeDevice device;
  EmbreeScene embreeScene;
  std::vector<std::uint32_t> source;  // Embree primID -> mesh triangle; empty = identity

  Impl(const Scene& s, const ReferenceOptions& o)
      : scene(s), options(o), threads(resolveThreadCount(o.threads)),
        device("isa=" + o.isa + ",threads=" + std::to_string(threads) + ",verbose=0"),
        embreeScene(device, RTC_SCENE_FLAG_ROBUST) {
    source = buildGeometry(device, embreeScene, scene.mesh, scene.camera);
  }
};

namespace {

const ReferenceOptions& checkIsa(const ReferenceOptions& options) {
  if (!cpuSupports(options.isa)) {
    throw usageError("this CPU lacks the Embree ISA '" + options.isa +
                     "'; choose another with --embree-isa (results differ between ISAs)");
  }
  return options;
}

}  // namespace

ReferenceTracer::ReferenceTracer(const Scene& scene, const ReferenceOptions& options)
    : impl_(std::make_unique<Impl>(scene, checkIsa(options))) {}

ReferenceTracer::~ReferenceTracer() = default;

Framebuffer renderReference(const Scene& scene, const ReferenceOptions& options) {
  return ReferenceTracer(scene, options).trace();
}

Framebuffer ReferenceTracer::trace() const {
  Framebuffer fb;
  trace(fb);
  addPreview(fb);
  return fb;
}

void ReferenceTracer::trace(Framebuffer& fb) const {
  const Scene& scene = impl_->scene;
  const ReferenceOptions& options = impl_->options;
  const int threads = impl_->threads;
  EmbreeDevice& device = impl_->device;
  const EmbreeScene& embreeScene = impl_->embreeScene;
  const Camera& camera = scene.camera;

  std::vector<std::string> names = {channels::kTriangleId, channels::kBary[0], channels::kBary[1], channels::kBary[2],
                                    channels::kDepth, channels::kBaryBound, channels::kDepthBound,
                                    channels::kEdgeDistance};
  for (const Attribute& a : scene.mesh.attributes) {
    for (int c = 0; c < a.components; ++c) names.push_back(channels::attributeChannel(a.name, c));
  }
  fb.recycle(camera.width(), camera.height(), names);
  Planes planes{fb.reuseUint(channels::kTriangleId), {}, nullptr, nullptr, nullptr, nullptr, {}};
  for (int i = 0; i < 3; ++i) planes.bary[i] = fb.reuseFloat(channels::kBary[i]);
  planes.depth = fb.reuseFloat(channels::kDepth);
  planes.baryBound = fb.reuseFloat(channels::kBaryBound);
  planes.depthBound = fb.reuseFloat(channels::kDepthBound);
  planes.edgeDistance = fb.reuseFloat(channels::kEdgeDistance);
  for (const Attribute& a : scene.mesh.attributes) {
    std::array<float*, 4> out{};
    for (int c = 0; c < a.components; ++c) out[c] = fb.reuseFloat(channels::attributeChannel(a.name, c));
    planes.attributes.push_back({&a, out});
  }

  const Mesh& mesh = scene.mesh;
  const int width = camera.width(), height = camera.height();
  const int tasks = (height + kRowsPerTask - 1) / kRowsPerTask;
  std::vector<double> embreeDiff(tasks, 0.0);  // max |Embree bary - double bary| per task
  // Everything written for one hit is recomputed in double from the mesh and the camera's ray.
  const std::vector<std::uint32_t>& source = impl_->source;
  const double pixelsPerUnit = height / (2.0 * camera.tanHalfFovY());
  const auto miss = [&](int x, int y) {
    const std::size_t pixel = std::size_t(y) * width + x;
    planes.id[pixel] = channels::kNoTriangle;
    for (int i = 0; i < 3; ++i) planes.bary[i][pixel] = 0.0f;
    planes.depth[pixel] = planes.baryBound[pixel] = planes.depthBound[pixel] = planes.edgeDistance[pixel] = 0.0f;
    for (const auto& [attribute, out] : planes.attributes) {
      for (int c = 0; c < attribute->components; ++c) out[c][pixel] = 0.0f;
    }
  };
  // What a hit needs of its triangle that does not depend on the ray's direction: the rays
  // all start at the camera's eye, so neighbouring pixels on one triangle share it (each task
  // keeps its last triangle; the arithmetic is the same whether it is reused or not).
  struct HitTriangle {
    std::uint32_t triangle = std::numeric_limits<std::uint32_t>::max();
    glm::dvec3 origin{0.0};
    glm::uvec3 tri{0u};
    TriangleFrame frame{};
    glm::dvec3 normal[3]{};  // of the plane through the origin and the edge opposite vertex i
    double inPlane[3]{};     // length of its part in the image plane
  };
  const auto hitTriangle = [&](std::uint32_t triangle, const glm::dvec3& origin, HitTriangle& h) {
    if (h.triangle == triangle && h.origin == origin) return;
    h.triangle = triangle;
    h.origin = origin;
    h.tri = mesh.triangles[triangle];
    const glm::dvec3 p[3] = {glm::dvec3(mesh.positions[h.tri.x]), glm::dvec3(mesh.positions[h.tri.y]),
                             glm::dvec3(mesh.positions[h.tri.z])};
    h.frame = triangleFrame(origin, p[0], p[1], p[2]);
    for (int i = 0; i < 3; ++i) {
      h.normal[i] = glm::cross(p[(i + 1) % 3] - origin, p[(i + 2) % 3] - origin);
      h.inPlane[i] = glm::length(h.normal[i] - glm::dot(h.normal[i], camera.forward()) * camera.forward());
    }
  };
  const auto shade = [&](int x, int y, const CameraRay& ray, unsigned primID, float u, float v, float tfar,
                         double& embreeDiffMax, HitTriangle& h) {
    const std::uint32_t triangle = source.empty() ? primID : source[primID];
    hitTriangle(triangle, ray.origin, h);
    const glm::uvec3 tri = h.tri;
    DoubleHit hit = intersectRay(h.frame, ray.direction);
    if (!hit.valid) {  // parallel to the plane: no unique point; keep Embree's, unbounded
      hit = {true, baryFromEmbreeUv(u, v), double(tfar), std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::infinity()};
    } else if (source.empty()) {
      embreeDiffMax = std::max(embreeDiffMax, glm::length(hit.b - baryFromEmbreeUv(u, v)));
    }
    const std::size_t pixel = std::size_t(y) * width + x;
    planes.id[pixel] = triangle;
    for (int i = 0; i < 3; ++i) planes.bary[i][pixel] = float(hit.b[i]);
    planes.depth[pixel] = float(hit.t * glm::dot(ray.direction, camera.forward()));
    // Float output rounds each value once more: half an ulp of numbers below 2 (b leaves
    // [0, 1] only within Embree's band), 2^-23 relative for depth.
    planes.baryBound[pixel] = float(hit.baryBound + 0x1p-23);
    planes.depthBound[pixel] = float(hit.depthBound + 0x1p-23);
    // Screen distance to the edge opposite vertex i: the pixel's direction d against the plane
    // through the eye and that edge, measured in the image plane d . forward = 1.
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
      const double length = h.inPlane[i];
      if (length > 0.0) {
        nearest = std::min(nearest, std::fabs(glm::dot(ray.direction, h.normal[i])) / length * pixelsPerUnit);
      }
    }
    planes.edgeDistance[pixel] = float(nearest);
    for (const auto& [attribute, out] : planes.attributes) {
      const int n = attribute->components;
      const float* values = attribute->values.data();
      for (int c = 0; c < n; ++c) {
        out[c][pixel] = float(hit.b[0] * values[std::size_t(tri.x) * n + c] +
                              hit.b[1] * values[std::size_t(tri.y) * n + c] +
                              hit.b[2] * values[std::size_t(tri.z) * n + c]);
      }
    }
  };
  // Coherent packets of 16 rays over 4x4 pixel blocks: the performance notes measured this
  // Embree's best mode, several times faster than single rays.
  parallelFor(tasks, threads, [&](int task) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    HitTriangle last;
    double diffMax = 0.0;  // kept here, not in embreeDiff, which the tasks' threads share lines of
    // Cleared once per task: each packet sets every input field it uses, and Embree changes
    // only the hits and tfar (zeroing 1.3 kB per packet cost 6% of a frame).
    alignas(64) RTCRayHit16 rh{};
    const int yEnd = std::min(height, (task + 1) * kRowsPerTask);
    for (int y0 = task * kRowsPerTask; y0 < yEnd; y0 += 4) {
      for (int x0 = 0; x0 < width; x0 += 4) {
        alignas(64) int valid[16];
        CameraRay rays[16];
        for (int lane = 0; lane < 16; ++lane) {
          const int x = x0 + lane % 4, y = y0 + lane / 4;
          valid[lane] = (x < width && y < yEnd) ? -1 : 0;
          rh.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
          if (!valid[lane]) continue;
          rays[lane] = camera.rayThroughPixel(x, y);
          rh.ray.org_x[lane] = rh.ray.org_y[lane] = rh.ray.org_z[lane] = 0.0f;  // camera-relative geometry
          rh.ray.dir_x[lane] = float(rays[lane].direction.x);
          rh.ray.dir_y[lane] = float(rays[lane].direction.y);
          rh.ray.dir_z[lane] = float(rays[lane].direction.z);
          rh.ray.tnear[lane] = float(rays[lane].tNear);
          rh.ray.tfar[lane] = std::isinf(rays[lane].tFar) ? std::numeric_limits<float>::infinity()
                                                          : float(rays[lane].tFar);
          rh.ray.mask[lane] = 0xFFFFFFFFu;
        }
        rtcIntersect16(valid, embreeScene.get(), &context, &rh);
        for (int lane = 0; lane < 16; ++lane) {
          if (!valid[lane]) continue;
          if (rh.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID) {
            miss(x0 + lane % 4, y0 + lane / 4);
            continue;
          }
          shade(x0 + lane % 4, y0 + lane / 4, rays[lane], rh.hit.primID[lane], rh.hit.u[lane], rh.hit.v[lane],
                rh.ray.tfar[lane], diffMax, last);
        }
      }
    }
    embreeDiff[task] = diffMax;
  });
  device.check("rtcIntersect16");

  fb.attributes[channels::header::kRenderer] = "reference";
  fb.attributes[channels::header::kMode] = "exact";
  fb.attributes[channels::header::kPrecision] = "double";
  fb.attributes["rastercheck.embreeIsa"] = options.isa;
  char band[32];
  std::snprintf(band, sizeof band, "%.6g", referenceEdgeBand(camera));
  fb.attributes[channels::header::kEdgeBand] = band;
  // Embree orders hits by its float t, within the same angular error (8 (1 + k) u, relative).
  std::snprintf(band, sizeof band, "%.6g", 8.0 * (1.0 + kMaxLengthOverDistance) * 0x1p-24);
  fb.attributes[channels::header::kDepthResolution] = band;
  fb.attributes["rastercheck.embreeTriangles"] = std::to_string(source.empty() ? mesh.triangleCount() : source.size());
  char diff[32];
  std::snprintf(diff, sizeof diff, "%.3g", *std::max_element(embreeDiff.begin(), embreeDiff.end()));
  fb.attributes["rastercheck.embreeBaryMaxDiff"] = diff;
  fb.attributes[channels::header::kScene] = scene.name;
  fb.attributes[channels::header::kCamera] = camera.describe();
}

}  // namespace rc
