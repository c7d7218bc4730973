// The reference: Embree chooses the triangle, values are recomputed in double.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/channels.h"
#include "raytracer_ref/embree_device.h"
#include "raytracer_ref/ray_triangle.h"
#include "raytracer_ref/reference.h"
#include "raytracer_ref/subdivide.h"
#include "scenes/registry.h"
#include "tests/analytic.h"
#include "tests/limited_memory.h"
#include "tests/same_bits.h"
#include "tests/test_scenes.h"

namespace rc {
namespace {

ReferenceOptions singleThread() {
  ReferenceOptions o;
  o.threads = 1;
  return o;
}

TEST(EmbreeUv, MapsToB1AndB2) {
  const glm::dvec3 b = baryFromEmbreeUv(0.25f, 0.5f);
  EXPECT_DOUBLE_EQ(b[0], 0.25);
  EXPECT_DOUBLE_EQ(b[1], 0.25);
  EXPECT_DOUBLE_EQ(b[2], 0.5);
}

TEST(RayTriangle, BarycentricsRotateWithTheVertexOrder) {
  const glm::dvec3 o(0.1, 0.2, 3.0), d(0.01, -0.02, -1.0);
  const glm::dvec3 v0(-1, -1, 0), v1(1, -0.5, 0.5), v2(0, 1, -0.5);
  const DoubleHit a = intersectRayTriangle(o, d, v0, v1, v2);
  const DoubleHit b = intersectRayTriangle(o, d, v1, v2, v0);
  ASSERT_TRUE(a.valid && b.valid);
  // Moeller-Trumbore is not symmetric in the vertices: the two agree within their bounds.
  const double bound = a.baryBound + b.baryBound;
  EXPECT_GT(bound, 0.0);
  EXPECT_LT(bound, 1e-13);
  EXPECT_NEAR(a.b[0], b.b[2], bound);
  EXPECT_NEAR(a.b[1], b.b[0], bound);
  EXPECT_NEAR(a.b[2], b.b[1], bound);
  EXPECT_NEAR(a.t, b.t, (a.depthBound + b.depthBound) * a.t);
  EXPECT_NEAR(a.b[0] + a.b[1] + a.b[2], 1.0, 1e-15);
}

TEST(RayTriangle, ParallelRayHasNoHit) {
  const DoubleHit h = intersectRayTriangle({0, 0, 1}, {1, 0, 0}, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  EXPECT_FALSE(h.valid);
}

TEST(Reference, MatchesAnalyticBarycentricsAndDepth) {
  const Scene scene = testing::makeTriangleScene({{-1.2f, -0.9f, -2.0f}, {1.4f, -0.5f, 0.8f}, {0.1f, 1.1f, -0.4f}});
  const Framebuffer fb = renderReference(scene, singleThread());
  const auto& ids = fb.find(channels::kTriangleId)->uints;
  int covered = 0;
  for (int y = 0; y < fb.height(); ++y) {
    for (int x = 0; x < fb.width(); ++x) {
      const std::size_t i = std::size_t(y) * fb.width() + x;
      if (ids[i] == channels::kNoTriangle) continue;
      ++covered;
      const testing::Analytic truth = testing::analyticHit(scene, ids[i], x, y);
      for (int k = 0; k < 3; ++k) {
        ASSERT_NEAR(fb.find(channels::kBary[k])->floats[i], double(truth.b[k]), 1e-7) << x << "," << y;
      }
      ASSERT_NEAR(fb.find(channels::kDepth)->floats[i], double(truth.depth), 1e-7 * double(truth.depth));
    }
  }
  EXPECT_GT(covered, 300);
  EXPECT_EQ(fb.attributes.at("rastercheck.renderer"), "reference");
}

TEST(Reference, NothingNearerThanTheNearPlaneIsHit) {
  const Scene scene =
      testing::makeTriangleScene({{-1.0f, -0.6f, 0.0f}, {1.0f, -0.6f, 0.0f}, {0.0f, -0.3f, 6.0f}});
  const Framebuffer fb = renderReference(scene, singleThread());
  int covered = 0;
  for (std::size_t i = 0; i < fb.pixelCount(); ++i) {
    if (fb.find(channels::kTriangleId)->uints[i] == channels::kNoTriangle) continue;
    ++covered;
    ASSERT_GE(fb.find(channels::kDepth)->floats[i], float(scene.camera.zNear()) * (1 - 1e-6f));
  }
  EXPECT_GT(covered, 300);
}

// compare reads the reference's edge band and depth resolution back from its header as bounds:
// each must read back as the very double docs/numerics.md's formula gives (written with six
// digits, half of them read back smaller than they are).
TEST(Reference, HeaderBoundsReadBackExactly) {
  for (const char* name : {"cube", "sphere", "floor", "grazing"}) {
    const Scene scene = makeBuiltinScene(name);
    const Framebuffer fb = renderReference(scene, singleThread());
    const double tanY = scene.camera.tanHalfFovY(), tanX = tanY * scene.camera.aspect();
    const double resolution = 8.0 * (1.0 + kMaxLengthOverDistance) * 0x1p-24;
    const double band = resolution * (scene.camera.height() / (2.0 * tanY)) * (1.0 + tanX * tanX + tanY * tanY);
    EXPECT_EQ(std::stod(fb.attributes.at(channels::header::kEdgeBand)), band) << name;
    EXPECT_EQ(std::stod(fb.attributes.at(channels::header::kDepthResolution)), resolution) << name;
  }
}

// spread.NAME: at each hit, the largest over the components of max - min of the hit triangle's
// three vertex values, rounded up to float; 0 where nothing was hit.
TEST(Reference, WritesEachAttributesSpreadOverTheHitTriangle) {
  for (const char* name : {"sphere", "attributes"}) {
    const Scene scene = makeBuiltinScene(name);
    const Framebuffer fb = renderReference(scene, singleThread());
    const auto& ids = fb.find(channels::kTriangleId)->uints;
    for (const Attribute& a : scene.mesh.attributes) {
      const Channel* spread = fb.find(channels::spreadChannel(a.name));
      ASSERT_NE(spread, nullptr) << name << ": " << a.name;
      std::size_t hits = 0;
      for (std::size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] == channels::kNoTriangle) {
          ASSERT_EQ(spread->floats[i], 0.0f);
          continue;
        }
        double expected = 0.0;
        const glm::uvec3 t = scene.mesh.triangles[ids[i]];
        for (int c = 0; c < a.components; ++c) {
          const auto value = [&](int k) { return double(a.values[std::size_t(t[k]) * a.components + c]); };
          expected = std::max(expected, std::max({value(0), value(1), value(2)}) - std::min({value(0), value(1), value(2)}));
        }
        ASSERT_GE(double(spread->floats[i]), expected) << name << " " << a.name << " at " << i;
        ASSERT_LE(double(spread->floats[i]), expected * (1.0 + 0x1p-22)) << name << " " << a.name << " at " << i;
        ++hits;
      }
      EXPECT_GT(hits, 0u) << name << ": " << a.name;
    }
  }
}

// Embree out of memory (its device cannot be made where the address space is full) is named,
// exit 4 like a full disk, not an internal error (exit 5) that asks for a report; once memory
// is back a device is made.
TEST(Reference, EmbreeOutOfMemoryIsNamedWithExitCode4) {
#if defined(RC_TEST_UNDER_ASAN)
  GTEST_SKIP() << "the sanitizer's shadow memory does not run in a limited address space";
#endif
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const auto makeDevice = [] { EmbreeDevice device("threads=2"); };
  EXPECT_EXIT(testing::exitAfterRunningOutOfMemory(1 << 20, makeDevice,
                                                  [&] {
                                                    makeDevice();
                                                    return true;
                                                  }),
              ::testing::ExitedWithCode(4), "Embree: out of memory creating its device \\(config 'threads=2'\\)");
}

TEST(Reference, OutputBitsAreIdenticalForOneAndTwoThreads) {
  const Scene scene = makeBuiltinScene("sphere");
  const Framebuffer one = renderReference(scene, singleThread());
  ReferenceOptions two;
  two.threads = 2;
  const Framebuffer other = renderReference(scene, two);
  EXPECT_EQ(testing::differingChannels(one, other), std::vector<std::string>{});
}

// Embree's build quality moves only which triangle wins a tie (a pixel centre on a shared edge,
// within Embree's own rounding): every pixel hit by the same triangle has the same bits in
// every channel, whatever the build, and on any number of threads.
TEST(Reference, TheBuildQualityMovesOnlyTiesAndNoValue) {
  const Scene scene = makeBuiltinScene("blob");  // 100k triangles at 1920x1080
  ReferenceOptions options;
  options.threads = 2;
  const Framebuffer low = renderReference(scene, options);  // the default
  EXPECT_EQ(low.attributes.at("rastercheck.embreeBuild"), "low");
  options.threads = 1;
  EXPECT_EQ(testing::differingChannels(low, renderReference(scene, options)), std::vector<std::string>{})
      << "the low-quality build on 1 thread";
  for (EmbreeBuild build : {EmbreeBuild::kMedium, EmbreeBuild::kHigh}) {
    options.build = build;
    options.threads = 2;
    const Framebuffer other = renderReference(scene, options);
    EXPECT_EQ(other.attributes.at("rastercheck.embreeBuild"), embreeBuildName(build));
    const std::uint32_t* idLow = low.find(channels::kTriangleId)->uints.data();
    const std::uint32_t* idOther = other.find(channels::kTriangleId)->uints.data();
    std::size_t covered = 0, moved = 0, differingValues = 0;
    for (std::size_t p = 0; p < low.pixelCount(); ++p) {
      covered += idLow[p] != channels::kNoTriangle;
      if (idLow[p] != idOther[p]) {
        ++moved;
        continue;
      }
      for (const Channel& c : low.channels()) {
        if (c.type != ChannelType::kFloat) continue;
        const float a = c.floats[p], b = other.find(c.name)->floats[p];
        differingValues += std::memcmp(&a, &b, sizeof a) != 0;
      }
    }
    EXPECT_EQ(differingValues, 0u) << embreeBuildName(build);
    EXPECT_LT(double(moved), 1e-3 * double(covered)) << embreeBuildName(build) << ": " << moved << " of " << covered;
  }
}

std::uint32_t bitsOf(float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

// What Embree gets is the same on any number of threads: the mesh's own triangles where none
// needs splitting (blob), and the same pieces in the same order where some do (huge's
// triangles reach far past the eye; perspective's from near to far).
TEST(Reference, EmbreeTrianglesAreTheSameOnAnyNumberOfThreads) {
  for (const char* spec : {"blob:tris=100000", "huge", "perspective"}) {
    const Scene scene = makeBuiltinScene(spec);
    const EmbreeTriangles one = embreeTriangles(scene.mesh, scene.camera, 1);
    const bool split = std::string(spec) != "blob:tris=100000";
    EXPECT_EQ(one.source.empty(), !split) << spec;
    EXPECT_EQ(one.indices.empty(), !split) << spec;
    EXPECT_EQ(one.indices.size(), 3 * one.source.size()) << spec;
    EXPECT_GE(one.vertices.size(), 3 * scene.mesh.vertexCount()) << spec;
    for (int threads : {2, 3, 8}) {
      const EmbreeTriangles other = embreeTriangles(scene.mesh, scene.camera, threads);
      EXPECT_EQ(other.vertices.size(), one.vertices.size()) << spec << " " << threads;
      EXPECT_TRUE(std::equal(one.vertices.begin(), one.vertices.end(), other.vertices.begin(), other.vertices.end(),
                             [](float a, float b) { return bitsOf(a) == bitsOf(b); }))
          << spec << " " << threads;
      EXPECT_EQ(other.indices, one.indices) << spec << " " << threads;
      EXPECT_EQ(other.source, one.source) << spec << " " << threads;
    }
  }
}

// The image at another size: odd ones leave partial 4x4 blocks at the right and bottom.
Scene resized(Scene scene, int width, int height) {
  CameraSpec spec = scene.camera.spec();
  spec.width = width;
  spec.height = height;
  scene.camera = Camera(spec);
  return scene;
}

// The scene with its far plane at depth `far`.
Scene withFar(Scene scene, double far) {
  CameraSpec spec = scene.camera.spec();
  spec.zFar = far;
  scene.camera = Camera(spec);
  return scene;
}

// The band tracer recomputes four pixels at a time, sharing one triangle's frame between
// block rows. Every value it writes must be the one the formulas of ray_triangle.h give on
// one double for that pixel's ray and triangle, to the bit.
TEST(Reference, EachPixelHasTheBitsOfTheOneRayFormulas) {
  for (const Scene& scene : {makeBuiltinScene("attributes"), resized(makeBuiltinScene("blob:tris=200000"), 331, 187),
                             resized(makeBuiltinScene("slivers"), 203, 117), makeBuiltinScene("grazing"),
                             makeBuiltinScene("huge"), resized(makeBuiltinScene("nearplane"), 384, 384),
                             withFar(makeBuiltinScene("grazing"), 3.0)}) {
    for (bool avx2 : {false, true}) {
      ReferenceOptions o = singleThread();
      o.avx2Recompute = avx2;
      const Framebuffer fb = renderReference(scene, o);
      const Camera& camera = scene.camera;
      const double pixelsPerUnit = camera.height() / (2.0 * camera.tanHalfFovY());
      int checked = 0, mixed = 0, cuts = 0;
      for (int y = 0; y < fb.height(); ++y) {
        for (int x = 0; x < fb.width(); ++x) {
          const std::size_t i = std::size_t(y) * fb.width() + x;
          const std::uint32_t id = fb.find(channels::kTriangleId)->uints[i];
          if (id == channels::kNoTriangle) {
            for (const Channel& c : fb.channels()) {
              if (c.type == ChannelType::kFloat) {
                ASSERT_EQ(bitsOf(c.floats[i]), 0u) << c.name;
              }
            }
            continue;
          }
          const CameraRay ray = camera.rayThroughPixel(x, y);
          const glm::uvec3 tri = scene.mesh.triangles[id];
          glm::dvec3 p[3];
          for (int k = 0; k < 3; ++k) p[k] = glm::dvec3(scene.mesh.positions[tri[k]]);
          const DoubleHit hit = intersectRayTriangle(ray.origin, ray.direction, p[0], p[1], p[2]);
          ASSERT_TRUE(hit.valid) << x << "," << y;
          const auto expect = [&](const char* channel, double value) {
            ASSERT_EQ(bitsOf(fb.find(channel)->floats[i]), bitsOf(float(value)))
                << scene.name << " " << channel << " at " << x << "," << y << " avx2 " << avx2;
          };
          for (int k = 0; k < 3; ++k) expect(channels::kBary[k], hit.b[k]);
          expect(channels::kDepth, hit.t * glm::dot(ray.direction, camera.forward()));
          expect(channels::kBaryBound, hit.baryBound + 0x1p-23);
          expect(channels::kDepthBound, hit.depthBound + 0x1p-23);
          // The planes through the eye and each edge, and through the lines where the
          // triangle's plane crosses the near or the far plane: n - (c / depth) forward.
          std::vector<glm::dvec3> planes;
          for (int k = 0; k < 3; ++k) planes.push_back(glm::cross(p[(k + 1) % 3] - ray.origin, p[(k + 2) % 3] - ray.origin));
          const glm::dvec3 f = camera.forward();
          const double depth[3] = {glm::dot(p[0] - ray.origin, f), glm::dot(p[1] - ray.origin, f),
                                   glm::dot(p[2] - ray.origin, f)};
          const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
          const double offset = -glm::dot(n, ray.origin - p[0]);
          if (std::min(std::min(depth[0], depth[1]), depth[2]) < camera.zNear()) {
            planes.push_back(n - (offset / camera.zNear()) * f);
          }
          if (std::max(std::max(depth[0], depth[1]), depth[2]) > camera.zFar()) {
            planes.push_back(n - (offset / camera.zFar()) * f);
          }
          cuts += planes.size() > 3;
          double nearest = std::numeric_limits<double>::infinity();
          for (const glm::dvec3& normal : planes) {
            const double length = glm::length(normal - glm::dot(normal, f) * f);
            if (length > 0.0) {
              nearest = std::min(nearest, std::fabs(glm::dot(ray.direction, normal)) / length * pixelsPerUnit);
            }
          }
          expect(channels::kEdgeDistance, nearest);
          for (const Attribute& a : scene.mesh.attributes) {
            for (int c = 0; c < a.components; ++c) {
              const auto value = [&](int k) { return double(a.values[std::size_t(tri[k]) * a.components + c]); };
              expect(channels::attributeChannel(a.name, c).c_str(),
                     hit.b[0] * value(0) + hit.b[1] * value(1) + hit.b[2] * value(2));
            }
          }
          if (::testing::Test::HasFailure()) return;  // one pixel's report is enough
          ++checked;
          // A block row of 4 pixels on more than one triangle takes the per-lane path.
          if (x % 4 == 3 && fb.find(channels::kTriangleId)->uints[i - 3] != id) ++mixed;
        }
      }
      EXPECT_GT(checked, 1000) << scene.name;
      EXPECT_GT(mixed, 10) << scene.name;
      if (scene.name == "nearplane" || std::isfinite(camera.zFar())) {
        EXPECT_GT(cuts, 100) << scene.name << ": pixels whose triangle the near or far plane cuts";
      }
    }
  }
}

// The baseline build of the band tracer and its AVX2 build run the same IEEE operations.
TEST(Reference, OutputBitsAreIdenticalForBaselineAndAvx2Recomputation) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this CPU has no AVX2";
  for (const char* spec : {"blob:tris=20000", "attributes", "huge", "nearplane", "faroffset"}) {
    const Scene scene = makeBuiltinScene(spec);
    ReferenceOptions o;
    o.avx2Recompute = false;
    const Framebuffer baseline = renderReference(scene, o);
    o.avx2Recompute = true;
    const Framebuffer avx2 = renderReference(scene, o);
    EXPECT_EQ(testing::differingChannels(baseline, avx2), std::vector<std::string>{}) << spec;
    EXPECT_EQ(baseline.attributes, avx2.attributes) << spec;
  }
}

}  // namespace
}  // namespace rc
