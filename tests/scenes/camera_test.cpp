// The camera contract: rays and projection agree, row 0 is the top, depth is w, and
// degenerate cameras are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "scenes/camera.h"

namespace rc {
namespace {

CameraSpec obliqueSpec() {
  CameraSpec spec;
  spec.eye = {1.5, -2.0, 4.0};
  spec.target = {0.2, 0.3, -0.7};
  spec.up = {0.1, 1.0, 0.2};
  spec.fovYDegrees = 37.0;
  spec.zNear = 0.25;
  spec.zFar = 100.0;
  spec.width = 160;
  spec.height = 90;
  return spec;
}

TEST(Camera, RayThroughPixelProjectsBackToThePixelCentre) {
  for (double zFar : {100.0, std::numeric_limits<double>::infinity()}) {
    CameraSpec spec = obliqueSpec();
    spec.zFar = zFar;
    const Camera camera(spec);
    const glm::dmat4 clipFromWorld = camera.clipFromWorld();
    for (int y : {0, 17, 89}) {
      for (int x : {0, 80, 159}) {
        const CameraRay ray = camera.rayThroughPixel(x, y);
        for (double t : {0.5, 3.0, 40.0}) {
          const glm::dvec4 clip = clipFromWorld * glm::dvec4(ray.origin + t * ray.direction, 1.0);
          EXPECT_NEAR(clip.w, t, 1e-12 * t) << "w must equal depth along forward";
          EXPECT_NEAR(camera.rasterXFromNdc(clip.x / clip.w), x + 0.5, 1e-9);
          EXPECT_NEAR(camera.rasterYFromNdc(clip.y / clip.w), y + 0.5, 1e-9);
        }
        EXPECT_NEAR(glm::dot(ray.direction, camera.forward()), 1.0, 1e-15);
      }
    }
  }
}

// docs/your-renderer.md tells a renderer that writes NDC depth z/w (nvdiffrast) how to turn
// it into depth.z; the formulas must give clip w under rastercheck's own projection.
TEST(Camera, DepthFollowsFromNdcDepthAsYourRendererGuideSays) {
  for (double zFar : {100.0, std::numeric_limits<double>::infinity()}) {
    CameraSpec spec = obliqueSpec();
    spec.zFar = zFar;
    const Camera camera(spec);
    const double n = spec.zNear, f = spec.zFar;
    for (double t : {0.3, 1.0, 7.5, 60.0, 99.0}) {
      const CameraRay ray = camera.rayThroughPixel(31, 72);
      const glm::dvec4 clip = camera.clipFromWorld() * glm::dvec4(ray.origin + t * ray.direction, 1.0);
      const double ndcZ = clip.z / clip.w;
      const double depth = std::isinf(f) ? 2.0 * n / (1.0 - ndcZ) : 2.0 * f * n / ((f + n) - ndcZ * (f - n));
      EXPECT_NEAR(depth, t, 1e-9 * t) << "far " << f;
    }
  }
}

TEST(Camera, RowZeroIsTheTopAndViewSpaceLooksDownMinusZ) {
  CameraSpec spec;  // eye (0,0,5) looking at the origin, up +y
  const Camera camera(spec);
  const glm::dvec4 above = camera.clipFromWorld() * glm::dvec4(0.0, 1.0, 0.0, 1.0);
  EXPECT_LT(camera.rasterYFromNdc(above.y / above.w), spec.height / 2.0);
  const glm::dvec4 right = camera.clipFromWorld() * glm::dvec4(1.0, 0.0, 0.0, 1.0);
  EXPECT_GT(camera.rasterXFromNdc(right.x / right.w), spec.width / 2.0);
  const glm::dvec4 view = camera.viewFromWorld() * glm::dvec4(0.0, 0.0, 0.0, 1.0);
  EXPECT_NEAR(view.z, -5.0, 1e-12);
}

// `reason`: what the refusal must say after "test: camera: ", values and all.
void expectRefused(CameraSpec spec, const char* what, const std::string& reason) {
  try {
    Camera camera(spec, "test");
    ADD_FAILURE() << "accepted a camera with " << what;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kBadInput) << what;
    EXPECT_EQ(std::string(e.what()), "test: camera: " + reason) << what;
  }
}

TEST(Camera, DegenerateCamerasAreRefusedWithTheirReason) {
  CameraSpec spec;
  spec.fovYDegrees = 0.0;
  expectRefused(spec, "a zero field of view", "vertical field of view must be 0.001 to 179.999 degrees, got 0");
  spec.fovYDegrees = 1e-25;  // the gate failed the rasterizer for most of the frame
  expectRefused(spec, "a field of view the paths cannot resolve",
                "vertical field of view must be 0.001 to 179.999 degrees, got 1e-25");
  spec.fovYDegrees = 180.0;
  expectRefused(spec, "a 180-degree field of view", "vertical field of view must be 0.001 to 179.999 degrees, got 180");
  spec.fovYDegrees = 179.9991;
  expectRefused(spec, "a field of view just past the widest", "vertical field of view must be 0.001 to 179.999 degrees, got 179.9991");
  spec = {};
  spec.eye = {0.0, 0.0, 1e200};  // its distance to the target overflowed: "the same point"
  expectRefused(spec, "an eye far beyond any mesh",
                "eye and target must lie within 1e18 of the origin on each axis, as mesh positions do, got eye=(0,0,1e+200) "
                "target=(0,0,0)");
  spec = {};
  spec.target = {-2e18, 0.0, 0.0};
  expectRefused(spec, "a target far beyond any mesh",
                "eye and target must lie within 1e18 of the origin on each axis, as mesh positions do, got eye=(0,0,5) "
                "target=(-2e+18,0,0)");
  spec = {};
  spec.zNear = 0.0;
  expectRefused(spec, "near = 0", "near must be finite and > 0, got 0");
  spec = {};
  spec.zFar = spec.zNear;
  expectRefused(spec, "near = far", "far must be greater than near (or infinite), got near=0.1 far=0.1");
  spec = {};
  spec.zNear = 2e-7;  // six decimals would print both as 0.000000
  spec.zFar = 1e-7;
  expectRefused(spec, "far in front of a tiny near", "far must be greater than near (or infinite), got near=2e-07 far=1e-07");
  spec = {};
  spec.target = spec.eye;
  expectRefused(spec, "the eye at the target", "eye and target are the same point");
  spec = {};
  spec.up = {0.0, 0.0, 0.0};
  expectRefused(spec, "a zero up vector", "up vector is zero");
  spec = {};
  spec.up = {0.0, 0.0, 1.0};
  expectRefused(spec, "up parallel to the view direction", "up vector is parallel to the view direction");
  spec = {};
  spec.eye.x = std::numeric_limits<double>::quiet_NaN();
  expectRefused(spec, "a NaN eye", "eye, target and up must be finite");
  spec = {};
  spec.width = 0;
  expectRefused(spec, "zero width", "image size must be 1..16384 per side, got 0x480");
}

// The bounds of each range make cameras, and so do vectors whose squared length underflows or
// overflows a double: each of those was refused as zero, parallel or the same point.
TEST(Camera, EveryValueWithinTheRangesMakesACamera) {
  const auto accepted = [](const CameraSpec& spec, glm::dvec3 forward, const char* what) {
    try {
      const Camera camera(spec, "test");
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(camera.forward()[i], forward[i], 1e-15) << what;
    } catch (const Error& e) {
      ADD_FAILURE() << what << ": " << e.what();
    }
  };
  const glm::dvec3 ahead(0.0, 0.0, -1.0);  // the default spec's view direction
  CameraSpec spec;
  spec.fovYDegrees = kMinFovYDegrees;
  accepted(spec, ahead, "the narrowest field of view");
  spec.fovYDegrees = kMaxFovYDegrees;
  accepted(spec, ahead, "the widest field of view");
  spec = {};
  spec.up = {0.0, 1e-300, 0.0};  // was "up vector is zero"
  accepted(spec, ahead, "a tiny up vector");
  spec.up = {1e-320, 1e200, 0.0};  // was "up vector is parallel to the view direction"
  accepted(spec, ahead, "a huge up vector");
  spec = {};
  spec.eye = {0.0, 0.0, 1e-300};  // was "eye and target are the same point"
  accepted(spec, ahead, "an eye next to the target");
  spec = {};
  spec.eye = {1e18, -1e18, 1e18};
  spec.target = -spec.eye;
  accepted(spec, glm::dvec3(-1.0, 1.0, -1.0) / std::sqrt(3.0), "eye and target at the largest coordinates");
}

}  // namespace
}  // namespace rc
