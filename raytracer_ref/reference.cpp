// The Embree reference renderer.
//
// Precision per stage: Embree gets camera-relative float geometry (vertex - eye, computed in
// double, rounded once) and rays from the origin, so its hit decision does not degrade with
// the world offset. Embree only chooses the triangle; everything written is recomputed in
// double from the mesh's own float vertices and the camera's double ray.
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

void buildGeometry(EmbreeDevice& device, EmbreeScene& scene, const Mesh& mesh,
                   const glm::dvec3& eye) {
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  device.check("rtcNewGeometry");
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertexCount()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangleCount()));
  device.check("rtcSetNewGeometryBuffer");
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    const glm::dvec3 relative = glm::dvec3(mesh.positions[i]) - eye;
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = float(relative[k]);
  }
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    for (int k = 0; k < 3; ++k) indices[3 * t + k] = mesh.triangles[t][k];
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene.get(), geometry);
  rtcReleaseGeometry(geometry);
  device.check("building the geometry");
  rtcCommitScene(scene.get());
  device.check("rtcCommitScene");
}

struct Planes {
  std::uint32_t* id;
  float* bary[3];
  float* depth;
  std::vector<std::pair<const Attribute*, std::array<float*, 4>>> attributes;
};

}  // namespace

struct ReferenceTracer::Impl {
  const Scene& scene;
  ReferenceOptions options;
  int threads;
  EmbreeDevice device;
  EmbreeScene embreeScene;

  Impl(const Scene& s, const ReferenceOptions& o)
      : scene(s), options(o), threads(resolveThreadCount(o.threads)),
        device("isa=" + o.isa + ",threads=" + std::to_string(threads) + ",verbose=0"),
        embreeScene(device, RTC_SCENE_FLAG_ROBUST) {
    buildGeometry(device, embreeScene, scene.mesh, scene.camera.spec().eye);
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
  const Scene& scene = impl_->scene;
  const ReferenceOptions& options = impl_->options;
  const int threads = impl_->threads;
  EmbreeDevice& device = impl_->device;
  const EmbreeScene& embreeScene = impl_->embreeScene;
  const Camera& camera = scene.camera;

  Framebuffer fb(camera.width(), camera.height());
  Planes planes{fb.addUint(channels::kTriangleId, channels::kNoTriangle), {}, nullptr, {}};
  for (int i = 0; i < 3; ++i) planes.bary[i] = fb.addFloat(channels::kBary[i]);
  planes.depth = fb.addFloat(channels::kDepth);
  for (const Attribute& a : scene.mesh.attributes) {
    std::array<float*, 4> out{};
    for (int c = 0; c < a.components; ++c) out[c] = fb.addFloat(channels::attributeChannel(a.name, c));
    planes.attributes.push_back({&a, out});
  }

  const Mesh& mesh = scene.mesh;
  const int width = camera.width(), height = camera.height();
  const int tasks = (height + kRowsPerTask - 1) / kRowsPerTask;
  std::vector<double> embreeDiff(tasks, 0.0);  // max |Embree bary - double bary| per task
  parallelFor(tasks, threads, [&](int task) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    const int yEnd = std::min(height, (task + 1) * kRowsPerTask);
    for (int y = task * kRowsPerTask; y < yEnd; ++y) {
      for (int x = 0; x < width; ++x) {
        const CameraRay ray = camera.rayThroughPixel(x, y);
        RTCRayHit rh{};
        rh.ray.org_x = rh.ray.org_y = rh.ray.org_z = 0.0f;  // camera-relative geometry
        rh.ray.dir_x = float(ray.direction.x);
        rh.ray.dir_y = float(ray.direction.y);
        rh.ray.dir_z = float(ray.direction.z);
        rh.ray.tnear = float(ray.tNear);
        rh.ray.tfar = std::isinf(ray.tFar) ? std::numeric_limits<float>::infinity() : float(ray.tFar);
        rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(embreeScene.get(), &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;

        const glm::uvec3 tri = mesh.triangles[rh.hit.primID];
        const glm::dvec3 embreeBary = baryFromEmbreeUv(rh.hit.u, rh.hit.v);
        DoubleHit hit = intersectRayTriangle(ray.origin, ray.direction, glm::dvec3(mesh.positions[tri.x]),
                                             glm::dvec3(mesh.positions[tri.y]),
                                             glm::dvec3(mesh.positions[tri.z]));
        if (!hit.valid) hit = {true, embreeBary, double(rh.ray.tfar)};  // grazing: keep Embree's
        const double diff = glm::length(hit.b - embreeBary);
        embreeDiff[task] = std::max(embreeDiff[task], diff);

        const std::size_t pixel = std::size_t(y) * width + x;
        planes.id[pixel] = rh.hit.primID;
        for (int i = 0; i < 3; ++i) planes.bary[i][pixel] = float(hit.b[i]);
        planes.depth[pixel] = float(hit.t * glm::dot(ray.direction, camera.forward()));
        for (const auto& [attribute, out] : planes.attributes) {
          const int n = attribute->components;
          const float* v = attribute->values.data();
          for (int c = 0; c < n; ++c) {
            out[c][pixel] = float(hit.b[0] * v[std::size_t(tri.x) * n + c] +
                                  hit.b[1] * v[std::size_t(tri.y) * n + c] +
                                  hit.b[2] * v[std::size_t(tri.z) * n + c]);
          }
        }
      }
    }
  });
  device.check("rtcIntersect1");

  addPreview(fb);
  fb.attributes[channels::header::kRenderer] = "reference";
  fb.attributes[channels::header::kMode] = "exact";
  fb.attributes[channels::header::kPrecision] = "double";
  fb.attributes["rastercheck.embreeIsa"] = options.isa;
  char diff[32];
  std::snprintf(diff, sizeof diff, "%.3g", *std::max_element(embreeDiff.begin(), embreeDiff.end()));
  fb.attributes["rastercheck.embreeBaryMaxDiff"] = diff;
  fb.attributes[channels::header::kScene] = scene.name;
  fb.attributes[channels::header::kCamera] = camera.describe();
  return fb;
}

}  // namespace rc
