// The Embree reference renderer.
//
// Precision per stage: Embree gets camera-relative float geometry (vertex - eye, computed in
// double, rounded once), with triangles too long for their distance split (subdivide.h), and
// rays from the origin, so its hit decision does not degrade with the world offset. Embree only
// chooses the triangle; everything written is recomputed in double from the mesh's own float
// vertices and the camera's double ray, with its error bound (docs/numerics.md).
#include "raytracer_ref/reference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/channels.h"
#include "core/error.h"
#include "core/number_text.h"
#include "core/parallel.h"
#include "core/preview.h"
#include "raytracer_ref/embree_device.h"
#include "raytracer_ref/subdivide.h"
#include "raytracer_ref/trace_band.h"

namespace rc {
namespace {

constexpr int kRowsPerTask = 2 * reference::kBlock;  // whole 4-row blocks of trace_band.h

bool cpuSupports(const std::string& isa) {
  if (isa == "sse2") return __builtin_cpu_supports("sse2");
  if (isa == "sse4.2") return __builtin_cpu_supports("sse4.2");
  if (isa == "avx") return __builtin_cpu_supports("avx");
  if (isa == "avx2") return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (isa == "avx512") return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
  throw usageError("--embree-isa must be one of sse2, sse4.2, avx, avx2, avx512; got '" + isa + "'");
}

}  // namespace

const char* embreeBuildName(EmbreeBuild build) {
  switch (build) {
    case EmbreeBuild::kLow: return "low";
    case EmbreeBuild::kMedium: return "medium";
    case EmbreeBuild::kHigh: return "high";
  }
  return "?";
}

std::string fastestEmbreeIsa() {
  for (const char* isa : {"avx512", "avx2", "avx", "sse4.2"}) {
    if (cpuSupports(isa)) return isa;
  }
  return "sse2";
}

std::string embreeVersion() {
  EmbreeDevice device("verbose=0");
  const auto v = rtcGetDeviceProperty(device.get(), RTC_DEVICE_PROPERTY_VERSION);  // 31305 for 3.13.5
  return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
}

namespace {

// Builds the scene from `triangles` (embreeTriangles), whose arrays, and the mesh's triangles
// where none was split, Embree reads in place: they must outlive the scene. Copied into
// buffers of Embree's own, they were 18 MB to fault in at 1M triangles (about 70 ms of a first
// build on this machine class, 10 of a later one).
void buildGeometry(EmbreeDevice& device, EmbreeScene& scene, const Mesh& mesh, EmbreeTriangles& triangles,
                   EmbreeBuild build) {
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  device.check("rtcNewGeometry");
  static_assert(sizeof(glm::uvec3) == 3 * sizeof(unsigned));
  const bool ownTriangles = triangles.indices.empty();
  const unsigned* indices =
      ownTriangles ? reinterpret_cast<const unsigned*>(mesh.triangles.data()) : triangles.indices.data();
  const std::size_t vertexCount = triangles.vertices.size() / 3;
  const std::size_t triangleCount = ownTriangles ? mesh.triangleCount() : triangles.indices.size() / 3;
  // Embree reads the last vertex with a 16-byte load: one float of padding after it.
  triangles.vertices.push_back(0.0f);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, triangles.vertices.data(), 0,
                             3 * sizeof(float), vertexCount);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0, 3 * sizeof(unsigned),
                             triangleCount);
  device.check("rtcSetSharedGeometryBuffer");
  const RTCBuildQuality quality = build == EmbreeBuild::kLow      ? RTC_BUILD_QUALITY_LOW
                                 : build == EmbreeBuild::kMedium ? RTC_BUILD_QUALITY_MEDIUM
                                                                 : RTC_BUILD_QUALITY_HIGH;
  rtcSetGeometryBuildQuality(geometry, quality);
  rtcSetSceneBuildQuality(scene.get(), quality);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene.get(), geometry);
  rtcReleaseGeometry(geometry);
  device.check("building the geometry");
  rtcCommitScene(scene.get());
  device.check("rtcCommitScene");
}

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
  // Embree's vertices, and its triangles where any was split; declared before the scene that
  // reads them, so they outlive it. Its `source`: Embree primID -> mesh triangle (empty = identity).
  EmbreeTriangles triangles;
  EmbreeDevice device;
  EmbreeScene embreeScene;
  // Some vertex lies nearer than the near plane or beyond the far plane, so a triangle may be
  // cut by one, and the band tracer measures the distance to the cuts (trace_band.h).
  bool clipCuts = false;

  Impl(const Scene& s, const ReferenceOptions& o)
      : scene(s), options(o), threads(resolveThreadCount(o.threads)),
        device("isa=" + o.isa + ",threads=" + std::to_string(threads) + ",verbose=0"),
        embreeScene(device, RTC_SCENE_FLAG_ROBUST) {
    triangles = embreeTriangles(scene.mesh, scene.camera, threads);
    buildGeometry(device, embreeScene, scene.mesh, triangles, o.build);
    const glm::dvec3 eye = scene.camera.spec().eye, forward = scene.camera.forward();
    for (const glm::vec3& p : scene.mesh.positions) {
      const double depth = glm::dot(glm::dvec3(p) - eye, forward);
      if (!(depth >= scene.camera.zNear() && depth <= scene.camera.zFar())) {
        clipCuts = true;
        break;
      }
    }
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

  // The channels in trace_band.h's plane order.
  std::vector<std::string> names = {channels::kTriangleId, channels::kBary[0], channels::kBary[1], channels::kBary[2],
                                    channels::kDepth, channels::kBaryBound, channels::kDepthBound,
                                    channels::kEdgeDistance};
  const std::vector<std::uint32_t>& source = impl_->triangles.source;
  const std::vector<double> rightOffsets = reference::rightOffsetsOf(camera);
  reference::BandInput input{embreeScene.get(), &camera, &scene.mesh,
                             source.empty() ? nullptr : source.data(), rightOffsets.data(), impl_->clipCuts, {}, {}};
  for (const Attribute& a : scene.mesh.attributes) {
    for (int c = 0; c < a.components; ++c) names.push_back(channels::attributeChannel(a.name, c));
    names.push_back(channels::spreadChannel(a.name));
    input.attributes.push_back({a.values.data(), a.components});
  }
  fb.recycle(camera.width(), camera.height(), names);
  input.planes.push_back(fb.reuseUint(channels::kTriangleId));
  for (std::size_t i = 1; i < names.size(); ++i) {
    input.planes.push_back(reinterpret_cast<std::uint32_t*>(fb.reuseFloat(names[i])));
  }

  // Bands of rows, each traced the same way whatever the thread count. Each keeps its own
  // running maximum for embreeBaryMaxDiff: a shared per-band array had the two threads
  // writing one cache line per pixel.
  const int height = camera.height();
  const int tasks = (height + kRowsPerTask - 1) / kRowsPerTask;
  std::vector<double> embreeDiff(tasks, 0.0);  // max |Embree bary - double bary| per task
  const bool avx2 = options.avx2Recompute && __builtin_cpu_supports("avx2");
  parallelFor(tasks, threads, [&](int task) {
    const int y0 = task * kRowsPerTask, y1 = std::min(height, y0 + kRowsPerTask);
    embreeDiff[task] = avx2 ? reference::traceBandAvx2(input, y0, y1) : reference::traceBandSse2(input, y0, y1);
  });
  device.check("rtcIntersect16");

  fb.attributes[channels::header::kRenderer] = "reference";
  fb.attributes[channels::header::kMode] = "exact";
  fb.attributes[channels::header::kPrecision] = "double";
  fb.attributes["rastercheck.embreeIsa"] = options.isa;
  fb.attributes["rastercheck.embreeBuild"] = embreeBuildName(options.build);
  // Both exact, as the rasterizer's band is: compare reads them back as bounds, and six digits
  // rounded half of them down.
  fb.attributes[channels::header::kEdgeBand] = exactNumber(referenceEdgeBand(camera));
  // Embree orders hits by its float t, within the same angular error (8 (1 + k) u, relative).
  fb.attributes[channels::header::kDepthResolution] = exactNumber(8.0 * (1.0 + kMaxLengthOverDistance) * 0x1p-24);
  fb.attributes["rastercheck.embreeTriangles"] = std::to_string(source.empty() ? scene.mesh.triangleCount() : source.size());
  char diff[32];
  std::snprintf(diff, sizeof diff, "%.3g", *std::max_element(embreeDiff.begin(), embreeDiff.end()));
  fb.attributes["rastercheck.embreeBaryMaxDiff"] = diff;
  fb.attributes[channels::header::kScene] = scene.name;
  fb.attributes[channels::header::kCamera] = camera.describe();
}

}  // namespace rc
