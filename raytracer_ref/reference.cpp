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
  // Everything written for one hit is recomputed in double from the mesh and the camera's ray.
  const auto shade = [&](int x, int y, const CameraRay& ray, unsigned primID, float u, float v, float tfar,
                         double& embreeDiffMax) {
    const glm::uvec3 tri = mesh.triangles[primID];
    const glm::dvec3 embreeBary = baryFromEmbreeUv(u, v);
    DoubleHit hit = intersectRayTriangle(ray.origin, ray.direction, glm::dvec3(mesh.positions[tri.x]),
                                         glm::dvec3(mesh.positions[tri.y]), glm::dvec3(mesh.positions[tri.z]));
    if (!hit.valid) hit = {true, embreeBary, double(tfar)};  // parallel to the plane: keep Embree's
    embreeDiffMax = std::max(embreeDiffMax, glm::length(hit.b - embreeBary));
    const std::size_t pixel = std::size_t(y) * width + x;
    planes.id[pixel] = primID;
    for (int i = 0; i < 3; ++i) planes.bary[i][pixel] = float(hit.b[i]);
    planes.depth[pixel] = float(hit.t * glm::dot(ray.direction, camera.forward()));
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
  // Coherent packets of 8 rays over 4x2 pixel blocks (the performance notes measured packets
  // with the coherent flag several times faster than single rays).
  parallelFor(tasks, threads, [&](int task) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    const int yEnd = std::min(height, (task + 1) * kRowsPerTask);
    for (int y0 = task * kRowsPerTask; y0 < yEnd; y0 += 2) {
      for (int x0 = 0; x0 < width; x0 += 4) {
        alignas(32) int valid[8];
        alignas(32) RTCRayHit8 rh{};
        CameraRay rays[8];
        for (int lane = 0; lane < 8; ++lane) {
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
        rtcIntersect8(valid, embreeScene.get(), &context, &rh);
        for (int lane = 0; lane < 8; ++lane) {
          if (!valid[lane] || rh.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID) continue;
          shade(x0 + lane % 4, y0 + lane / 4, rays[lane], rh.hit.primID[lane], rh.hit.u[lane], rh.hit.v[lane],
                rh.ray.tfar[lane], embreeDiff[task]);
        }
      }
    }
  });
  device.check("rtcIntersect8");

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
