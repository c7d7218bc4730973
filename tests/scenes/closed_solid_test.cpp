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
  // A double cone whose rim of 10 distinct vertices goes round the axis twice (radius 1 the
  // first time, 2 the second): closed, every edge paired, every triangle facing away from the
  // centre, and yet it wraps the centre twice, which only the solid angles show.
  Mesh doubled;
  constexpr int kRim = 10;
  for (int i = 0; i < kRim; ++i) {
    const double angle = 2.0 * M_PI * (i % 5) / 5.0, r = i < 5 ? 1.0 : 2.0;
    doubled.positions.push_back(glm::vec3(float(r * std::cos(angle)), float(r * std::sin(angle)), 0.0f));
  }
  doubled.positions.push_back({0, 0, 1});   // top, kRim
  doubled.positions.push_back({0, 0, -1});  // bottom, kRim + 1
  for (unsigned i = 0; i < kRim; ++i) {
    const unsigned next = (i + 1) % kRim;
    doubled.triangles.push_back({kRim, i, next});
    doubled.triangles.push_back({kRim + 1, next, i});
  }
  EXPECT_NE(closedSolidProblem(doubled).find("the solid angles sum to 25.13"), std::string::npos) << closedSolidProblem(doubled);
  EXPECT_NE(closedSolidProblem(makeBuiltinScene("floor").mesh), "");
}

}  // namespace
}  // namespace rc
