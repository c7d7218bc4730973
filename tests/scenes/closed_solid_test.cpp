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

#include "scenes/registry.h"

namespace rc {
namespace {

// Empty when `mesh` bounds a solid that is star-shaped about the centre c of its bounding box,
// else the first problem found. Sufficient for Mesh::closedSolid:
//  1. closed and consistently wound: with vertices welded by position, every directed edge
//     (a, b) occurs once and its reverse (b, a) once;
//  2. every triangle faces away from c: det[p0 - c, p1 - c, p2 - c] > 0, so seen from c each
//     triangle is clockwise and seen from outside counter-clockwise;
//  3. the solid angles the triangles subtend at c sum to 4 pi.
// By 2, projecting the surface from c onto a sphere around c is orientation-preserving on every
// triangle; by 1 it is then a covering of the sphere, of degree 1 by 3: each ray from c
// crosses the surface once. So the surface does not cross itself, and a ray from outside
// enters the solid (through a front face) before it can leave it.
std::string closedSolidProblem(const Mesh& mesh) {
  std::map<std::array<float, 3>, unsigned> weld;  // +0.0f added: -0 and +0 weld
  std::vector<unsigned> id(mesh.positions.size());
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = mesh.positions[i];
    id[i] = weld.emplace(std::array<float, 3>{p.x + 0.0f, p.y + 0.0f, p.z + 0.0f}, unsigned(weld.size())).first->second;
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const glm::dvec3 c = 0.5 * (lo + hi);
  std::vector<std::pair<unsigned, unsigned>> edges;
  double solidAngle = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    const unsigned v[3] = {id[tri.x], id[tri.y], id[tri.z]};
    for (int k = 0; k < 3; ++k) edges.emplace_back(v[k], v[(k + 1) % 3]);
    const glm::dvec3 a = glm::dvec3(mesh.positions[tri.x]) - c, b = glm::dvec3(mesh.positions[tri.y]) - c,
                     d = glm::dvec3(mesh.positions[tri.z]) - c;
    const double det = glm::dot(a, glm::cross(b, d));
    if (!(det > 0.0)) return "triangle " + std::to_string(t) + " does not face away from the centre";
    // Van Oosterom and Strackee: tan(omega / 2) = det / (|a||b||d| + (a.b)|d| + (a.d)|b| + (b.d)|a|).
    const double la = glm::length(a), lb = glm::length(b), ld = glm::length(d);
    solidAngle += 2.0 * std::atan2(det, la * lb * ld + glm::dot(a, b) * ld + glm::dot(a, d) * lb + glm::dot(b, d) * la);
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto [a, b] = edges[i];
    if (i + 1 < edges.size() && edges[i + 1] == edges[i]) {
      return "edge " + std::to_string(a) + "-" + std::to_string(b) + " is used twice in one direction";
    }
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a))) {
      return "edge " + std::to_string(a) + "-" + std::to_string(b) + " has no opposite: the surface is open";
    }
  }
  if (std::fabs(solidAngle - 4.0 * M_PI) > 1e-6) {
    return "the solid angles sum to " + std::to_string(solidAngle) + ", not 4 pi";
  }
  return "";
}

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
