// Mesh::closedSolid is a promise the rasterizer acts on (it culls back faces), so every built-in
// scene that makes it is checked here, and the check is shown to reject meshes that break it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scenes/mesh.h"
#include "scenes/registry.h"

namespace rc {
namespace {

TEST(ClosedSolid, EveryBuiltinSceneThatDeclaresItIsOne) {
  std::vector<std::string> specs = {"blob:tris=8", "blob:tris=1000", "blob:tris=100000", "blob:tris=1000000",
                                    "sphere:segments=4", "closed:seed=1", "closed:seed=2", "closed:seed=3",
                                    "closed:level=0", "closed:level=5"};
  for (const BuiltinScene& entry : builtinScenes()) specs.push_back(entry.name);
  int declared = 0;
  for (const std::string& spec : specs) {
    const Scene scene = makeBuiltinScene(spec);
    if (!scene.mesh.closedSolid) continue;
    ++declared;
    EXPECT_EQ(closedSolidProblem(scene.mesh), "") << spec;
  }
  // The scenes that need it most (bench's blob) do declare it.
  EXPECT_TRUE(makeBuiltinScene("blob").mesh.closedSolid);
  EXPECT_TRUE(makeBuiltinScene("sphere").mesh.closedSolid);
  EXPECT_GE(declared, 10);
}

TEST(ClosedSolid, TheCheckRejectsOpenInsideOutAndSelfCrossingMeshes) {
  const Mesh sphere = makeBuiltinScene("sphere:segments=8").mesh;
  ASSERT_EQ(closedSolidProblem(sphere), "");
  Mesh open = sphere;
  open.triangles.pop_back();
  EXPECT_NE(closedSolidProblem(open).find("open"), std::string::npos);
  Mesh flipped = sphere;
  std::swap(flipped.triangles[5].y, flipped.triangles[5].z);
  EXPECT_NE(closedSolidProblem(flipped), "");
  Mesh insideOut = sphere;
  for (glm::uvec3& t : insideOut.triangles) std::swap(t.y, t.z);
  EXPECT_NE(closedSolidProblem(insideOut).find("face away"), std::string::npos);
  Mesh twice = sphere;  // the same surface twice: closed and outward, but it wraps c twice
  const auto n = unsigned(twice.positions.size());
  twice.positions.insert(twice.positions.end(), sphere.positions.begin(), sphere.positions.end());
  for (const glm::uvec3& t : sphere.triangles) twice.triangles.push_back(t + n);
  EXPECT_NE(closedSolidProblem(twice), "");
  EXPECT_NE(closedSolidProblem(makeBuiltinScene("floor").mesh), "");
}

}  // namespace
}  // namespace rc
