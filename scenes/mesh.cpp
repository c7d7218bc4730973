// Mesh helpers and validation.
#include "scenes/mesh.h"

#include <cmath>

#include "core/error.h"

namespace rc {
namespace {

// Embree silently skips triangles with coordinates above about 1.8e18; both paths must see
// the same geometry, so such meshes are refused here.
constexpr float kMaxCoordinate = 1e18f;

bool validName(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

const Attribute* Mesh::findAttribute(const std::string& name) const {
  for (const Attribute& a : attributes) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

Attribute& Mesh::addAttribute(const std::string& name, int components) {
  attributes.push_back({name, components, std::vector<float>(positions.size() * components)});
  return attributes.back();
}

void validateMesh(const Mesh& mesh, const std::string& where) {
  if (mesh.positions.size() >= 0xFFFFFFFFu || mesh.triangles.size() >= 0xFFFFFFFFu) {
    throw badInput(where, "too many vertices or triangles for 32-bit ids");
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p[k]) || std::fabs(p[k]) > kMaxCoordinate) {
        throw badInput(where + ": vertex " + std::to_string(i),
                       "position is not finite or exceeds 1e18 in magnitude");
      }
    }
  }
  const std::size_t n = mesh.positions.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    if (tri.x >= n || tri.y >= n || tri.z >= n) {
      throw badInput(where + ": triangle " + std::to_string(t),
                     "vertex index out of range (mesh has " + std::to_string(n) + " vertices)");
    }
  }
  for (std::size_t a = 0; a < mesh.attributes.size(); ++a) {
    const Attribute& attr = mesh.attributes[a];
    const std::string at = where + ": attribute '" + attr.name + "'";
    if (!validName(attr.name)) throw badInput(at, "name must be 1-64 of [A-Za-z0-9_]");
    for (std::size_t b = 0; b < a; ++b) {
      if (mesh.attributes[b].name == attr.name) throw badInput(at, "declared twice");
    }
    if (attr.components < 1 || attr.components > 4) throw badInput(at, "needs 1 to 4 components");
    if (attr.values.size() != n * std::size_t(attr.components)) {
      throw badInput(at, "has " + std::to_string(attr.values.size()) + " values, expected " +
                             std::to_string(n * attr.components));
    }
    for (std::size_t i = 0; i < attr.values.size(); ++i) {
      if (!std::isfinite(attr.values[i])) {
        throw badInput(at + ", vertex " + std::to_string(i / attr.components), "value is not finite");
      }
    }
  }
}

}  // namespace rc
