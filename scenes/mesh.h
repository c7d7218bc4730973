// The renderer-neutral triangle mesh: float positions, triangles as index triples, and any
// number of named per-vertex float attributes. A mesh carries only the attributes its scene
// declares; those are exactly the ones interpolated and written.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/plane_allocator.h"

namespace rc {

struct Attribute {
  std::string name;           // channel-safe: [A-Za-z0-9_]+, e.g. "uv", "normal", "color"
  int components = 0;         // 1..4
  HugeVector<float> values;   // vertexCount * components, vertex-major
};

// The arrays are HugeVectors (core/plane_allocator.h): from 256 KB up they take 2 MB-aligned
// memory advised to use transparent huge pages. Building the 1M-triangle blob took 10,545 page
// faults in 4 KB pages, and takes 3,690.
struct Mesh {
  HugeVector<glm::vec3> positions;     // world space
  HugeVector<glm::uvec3> triangles;    // indices into positions; (b0, b1, b2) follow this order
  std::vector<Attribute> attributes;
  // The triangles bound a solid: the surface is closed, does not cross itself, and every
  // triangle is counter-clockwise seen from outside. A ray that starts outside the solid then
  // meets a front face first, so the rasterizer may cull back faces (docs/rasterizer.md,
  // "Back faces"). Only a scene that guarantees it by construction sets it, or a file that
  // claims it and passes closedSolidProblem; the tests check it for every built-in scene that
  // sets it (tests/scenes/closed_solid_test.cpp).
  bool closedSolid = false;

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return triangles.size(); }
  const Attribute* findAttribute(const std::string& name) const;
  Attribute& addAttribute(const std::string& name, int components);  // sized for the vertices
};

// Empty when `mesh` bounds a solid that is star-shaped about the centre c of its bounding box,
// else the first problem found (a vertex named by the first mesh vertex at its position).
// Sufficient for Mesh::closedSolid:
//  1. closed and consistently wound: with vertices welded by position, every directed edge
//     (a, b) occurs once and its reverse (b, a) once;
//  2. every triangle faces away from c: det[p0 - c, p1 - c, p2 - c] > 0, so seen from c each
//     triangle is clockwise and seen from outside counter-clockwise;
//  3. the solid angles the triangles subtend at c sum to 4 pi.
// By 2, projecting the surface from c onto a sphere around c is orientation-preserving on every
// triangle; by 1 it is then a covering of the sphere, of degree 1 by 3: each ray from c
// crosses the surface once. So the surface does not cross itself, and a ray from outside
// enters the solid (through a front face) before it can leave it.
std::string closedSolidProblem(const Mesh& mesh);

// 1 to 64 of [A-Za-z0-9_]: what an attribute's name may be, since it names EXR channels.
bool validAttributeName(const std::string& name);

// A tangent as glTF stores it (xyz, and in w the sign that makes the bitangent cross(normal,
// xyz) * w), moved by a transform's linear part: xyz by the part itself (not renormalised), w
// negated where the transform mirrors, so that the bitangent keeps pointing the way it moved.
glm::dvec4 movedTangent(const glm::dmat3& linear, const glm::dvec4& tangent);

// Whether `m`'s last row is (0, 0, 0, 1): a mesh is placed only by such a matrix, since
// appendMesh maps positions without dividing by w.
inline bool isAffine(const glm::dmat4& m) { return m[0][3] == 0.0 && m[1][3] == 0.0 && m[2][3] == 0.0 && m[3][3] == 1.0; }

// Appends `part` to `into`, its positions mapped by `worldFromPart` (affine; in double, rounded once),
// an attribute named "normal" with 3 components by its inverse transpose and one named
// "tangent" with 4 by movedTangent (both renormalised).
// Only attributes carried by both (same name and component count) survive: a merged mesh never
// has channels some of its triangles cannot fill. `into` may start empty (then it takes all of
// part's attributes).
void appendMesh(Mesh& into, const Mesh& part, const glm::dmat4& worldFromPart);

// Keeps only the named attributes; throws usageError naming an unknown one and listing those
// the mesh has.
void selectAttributes(Mesh& mesh, const std::vector<std::string>& names, const std::string& where);

// The largest magnitude a mesh position (and a camera's eye or target) may have on any axis.
// Embree silently skips triangles with coordinates above about 1.8e18; both paths must see
// the same geometry, so such meshes are refused.
inline constexpr double kMaxCoordinate = 1e18;

// Throws badInput(where + ...) naming the first problem: a non-finite or out-of-range
// position, an index out of range, an attribute of the wrong size or with a bad name.
void validateMesh(const Mesh& mesh, const std::string& where);

// No limit on a scene's triangles (the loaders' default).
inline constexpr std::size_t kNoTriangleLimit = ~std::size_t(0);

// Throws badInput naming where() and what() adds (a face, a node's mesh) when a scene of
// `have` triangles would have more than `limit` with `adding` more. The loaders check before
// they allocate, so that a small file (one mesh placed by a hundred thousand nodes, a short
// face statement repeated) cannot ask for unbounded memory before the caller's limit on the
// loaded scene is ever consulted. where and what return strings and are called only for the
// message: an OBJ checks every face, and building its place each time cost a string a face.
[[noreturn]] void refuseTriangles(std::size_t limit, const std::string& where, const std::string& what);
template <typename Where, typename What>
void checkTriangleBudget(std::size_t have, std::size_t adding, std::size_t limit, const Where& where, const What& what) {
  if (have > limit || adding > limit - have) refuseTriangles(limit, where(), what());
}

// What a loader may add to a scene: the scene's limit, and the triangles it has before the file's.
struct TriangleBudget {
  std::size_t limit = kNoTriangleLimit;
  std::size_t have = 0;
};

}  // namespace rc
