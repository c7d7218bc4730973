// The reference: Embree chooses the triangle, values are recomputed in double.
#include <gtest/gtest.h>

#include <cstring>

#include "core/channels.h"
#include "raytracer_ref/ray_triangle.h"
#include "raytracer_ref/reference.h"
#include "scenes/registry.h"
#include "tests/analytic.h"
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

TEST(Reference, OutputBitsAreIdenticalForOneAndTwoThreads) {
  const Scene scene = makeBuiltinScene("sphere");
  const Framebuffer one = renderReference(scene, singleThread());
  ReferenceOptions two;
  two.threads = 2;
  const Framebuffer other = renderReference(scene, two);
  EXPECT_EQ(testing::differingChannels(one, other), std::vector<std::string>{});
}

}  // namespace
}  // namespace rc
