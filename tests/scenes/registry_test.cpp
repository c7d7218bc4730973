// The built-in scenes build, validate and honour their parameters; meshes are validated.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "scenes/registry.h"
#include "tests/test_files.h"

namespace rc {
namespace {

int errorCode(const std::string& spec) {
  try {
    makeBuiltinScene(spec);
  } catch (const Error& e) {
    return int(e.code());
  }
  return 0;
}

TEST(Registry, EveryBuiltinSceneBuildsAndValidates) {
  for (const BuiltinScene& entry : builtinScenes()) {
    const Scene scene = makeBuiltinScene(entry.name);
    EXPECT_EQ(scene.name, entry.name);
    EXPECT_GT(scene.mesh.triangleCount(), 0u) << entry.name;
    EXPECT_NO_THROW(validateMesh(scene.mesh, entry.name));
  }
  EXPECT_FALSE(defaultSceneNames().empty());
}

TEST(Registry, ScenesCarryOnlyTheAttributesTheyDeclare) {
  EXPECT_EQ(makeBuiltinScene("floor").mesh.attributes.size(), 1u);  // uv only
  EXPECT_EQ(makeBuiltinScene("cube").mesh.attributes.size(), 1u);   // uv only
  EXPECT_NE(makeBuiltinScene("sphere").mesh.findAttribute("normal"), nullptr);
}

TEST(Registry, BlobTriangleCountFollowsItsParameter) {
  for (long long requested : {1000LL, 100000LL, 1000000LL}) {
    const Scene scene = makeBuiltinScene("blob:tris=" + std::to_string(requested));
    const double ratio = double(scene.mesh.triangleCount()) / double(requested);
    EXPECT_NEAR(ratio, 1.0, 0.1) << requested;
  }
  EXPECT_EQ(makeBuiltinScene("blob:tris=1e4").mesh.triangleCount(),
            makeBuiltinScene("blob:tris=10000").mesh.triangleCount());
}

TEST(Registry, BadNamesAndParametersAreUsageErrors) {
  EXPECT_EQ(errorCode("no-such-scene"), int(ExitCode::kUsage));
  EXPECT_EQ(errorCode("blob:tris=abc"), int(ExitCode::kUsage));
  EXPECT_EQ(errorCode("blob:tris=0"), int(ExitCode::kUsage));
  EXPECT_EQ(errorCode("blob:tris=nan"), int(ExitCode::kUsage));
  EXPECT_EQ(errorCode("blob:tris=1.5e3,tris=2"), int(ExitCode::kUsage));
  EXPECT_EQ(errorCode("blob:colour=red"), int(ExitCode::kUsage));
  EXPECT_EQ(errorCode("blob:tris"), int(ExitCode::kUsage));
  EXPECT_EQ(errorCode("floor:tris=2"), int(ExitCode::kUsage));
  // The range is given as a user would write it, not as "[8.000000, 4000000.000000]".
  rc::testing::expectError([] { makeBuiltinScene("blob:tris=3"); }, ExitCode::kUsage,
                           {"scene blob:tris=3: tris=3 is outside [8, 4000000]"}, "blob:tris=3");
  // A limit of 2^40 in full: %.10g printed it as 1.099511628e+12, which the refused seed is below.
  rc::testing::expectError([] { makeBuiltinScene("closed:seed=1099511627777"); }, ExitCode::kUsage,
                           {"scene closed:seed=1099511627777: seed=1099511627777 is outside [0, 1099511627776]"},
                           "closed:seed=2^40+1");
  EXPECT_EQ(makeBuiltinScene("closed:seed=1099511627776").name, "closed:seed=1099511627776");
}

Mesh oneTriangle() {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  return mesh;
}

int validationCode(const Mesh& mesh) {
  try {
    validateMesh(mesh, "mesh.obj");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mesh.obj"), std::string::npos) << e.what();
    return int(e.code());
  }
  return 0;
}

TEST(MeshValidation, RefusesNonFinitePositionsBadIndicesAndBadAttributes) {
  EXPECT_EQ(validationCode(oneTriangle()), 0);
  Mesh mesh = oneTriangle();
  mesh.positions[1].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(validationCode(mesh), int(ExitCode::kBadInput));
  mesh = oneTriangle();
  mesh.positions[1].y = 1e19f;  // Embree would silently skip it
  EXPECT_EQ(validationCode(mesh), int(ExitCode::kBadInput));
  mesh = oneTriangle();
  mesh.triangles[0].z = 3;
  EXPECT_EQ(validationCode(mesh), int(ExitCode::kBadInput));
  mesh = oneTriangle();
  mesh.attributes.push_back({"uv", 2, HugeVector<float>(5)});
  EXPECT_EQ(validationCode(mesh), int(ExitCode::kBadInput));
  mesh = oneTriangle();
  mesh.attributes.push_back({"bad name", 1, HugeVector<float>(3)});
  EXPECT_EQ(validationCode(mesh), int(ExitCode::kBadInput));
  mesh = oneTriangle();
  mesh.attributes.push_back({"uv", 5, HugeVector<float>(15)});
  EXPECT_EQ(validationCode(mesh), int(ExitCode::kBadInput));
}

}  // namespace
}  // namespace rc
