// Mesh helpers and validation.
#include "scenes/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "core/error.h"

namespace rc {

bool validAttributeName(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_';
    if (!ok) return false;
  }
  return true;
}


const Attribute* Mesh::findAttribute(const std::string& name) const {
  for (const Attribute& a : attributes) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

Attribute& Mesh::addAttribute(const std::string& name, int components) {
  attributes.push_back({name, components, HugeVector<float>(positions.size() * components)});
  return attributes.back();
}

glm::dvec4 movedTangent(const glm::dmat3& linear, const glm::dvec4& tangent) {
  return {linear * glm::dvec3(tangent), glm::determinant(linear) < 0.0 ? -tangent.w : tangent.w};
}

void appendMesh(Mesh& into, const Mesh& part, const glm::dmat4& worldFromPart) {
  const bool first = into.positions.empty() && into.triangles.empty();
  const auto base = static_cast<unsigned>(into.positions.size());
  into.closedSolid = false;  // two solids may overlap: their union is not known to be one
  if (first) {
    into.attributes.clear();
    for (const Attribute& a : part.attributes) into.attributes.push_back({a.name, a.components, {}});
  } else {
    std::erase_if(into.attributes, [&](const Attribute& a) {
      const Attribute* other = part.findAttribute(a.name);
      return !other || other->components != a.components;
    });
  }
  for (const glm::vec3& p : part.positions) {
    into.positions.push_back(glm::vec3(worldFromPart * glm::dvec4(glm::dvec3(p), 1.0)));
  }
  for (const glm::uvec3& t : part.triangles) into.triangles.push_back(t + glm::uvec3(base));
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(worldFromPart)));
  for (Attribute& a : into.attributes) {
    const Attribute& source = *part.findAttribute(a.name);
    if (a.name == "normal" && a.components == 3) {
      for (std::size_t i = 0; i < part.positions.size(); ++i) {
        glm::dvec3 n = normalMatrix * glm::dvec3(source.values[3 * i], source.values[3 * i + 1],
                                                 source.values[3 * i + 2]);
        const double length = glm::length(n);
        if (length > 0.0) n /= length;
        for (int k = 0; k < 3; ++k) a.values.push_back(float(n[k]));
      }
    } else if (a.name == "tangent" && a.components == 4) {
      const glm::dmat3 linear(worldFromPart);
      for (std::size_t i = 0; i < part.positions.size(); ++i) {
        const float* t = &source.values[4 * i];
        glm::dvec4 moved = movedTangent(linear, glm::dvec4(t[0], t[1], t[2], t[3]));
        const double length = glm::length(glm::dvec3(moved));
        if (length > 0.0) moved = glm::dvec4(glm::dvec3(moved) / length, moved.w);
        for (int k = 0; k < 4; ++k) a.values.push_back(float(moved[k]));
      }
    } else {
      a.values.insert(a.values.end(), source.values.begin(), source.values.end());
    }
  }
}

void selectAttributes(Mesh& mesh, const std::vector<std::string>& names, const std::string& where) {
  for (const std::string& name : names) {
    if (!mesh.findAttribute(name)) {
      std::string available;
      for (const Attribute& a : mesh.attributes) available += (available.empty() ? "" : ", ") + a.name;
      throw usageError(where + ": --attributes names '" + name + "', which the scene does not carry (it has: " +
                       (available.empty() ? "none" : available) + ")");
    }
  }
  std::erase_if(mesh.attributes, [&](const Attribute& a) {
    return std::find(names.begin(), names.end(), a.name) == names.end();
  });
}

void refuseTriangles(std::size_t limit, const std::string& where, const std::string& what) {
  throw badInput(where, what + " takes the scene past " + std::to_string(limit) +
                            " triangles, the most it may have (--max-triangles)");
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
    if (!validAttributeName(attr.name)) throw badInput(at, "name must be 1-64 of [A-Za-z0-9_]");
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

std::string closedSolidProblem(const Mesh& mesh) {
  // Weld: vertices at one position (+0.0f added: -0 and +0 weld) are one, named by the first
  // of them. By sorting, not a std::map: the map took about a second at 1M triangles.
  const std::size_t n = mesh.positions.size();
  std::vector<std::array<std::uint32_t, 3>> key(n);
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 p = mesh.positions[i] + 0.0f;
    std::memcpy(key[i].data(), &p, sizeof p);  // equal bits <=> equal coordinates: all finite
    lo = glm::min(lo, glm::dvec3(mesh.positions[i]));
    hi = glm::max(hi, glm::dvec3(mesh.positions[i]));
  }
  std::vector<std::uint32_t> order(n), id(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = std::uint32_t(i);
  const auto same = [&](std::uint32_t a, std::uint32_t b) {
    return key[a][0] == key[b][0] && key[a][1] == key[b][1] && key[a][2] == key[b][2];
  };
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    for (int k = 0; k < 3; ++k) {
      if (key[a][k] != key[b][k]) return key[a][k] < key[b][k];
    }
    return a < b;
  });
  for (std::size_t k = 0; k < n; ++k) {
    id[order[k]] = k > 0 && same(order[k], order[k - 1]) ? id[order[k - 1]] : order[k];
  }
  const glm::dvec3 c = 0.5 * (lo + hi);
  // Each welded vertex's outgoing edges, as a compressed list (first counted, then filled).
  std::vector<std::size_t> first(n + 1, 0);
  double solidAngle = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) ++first[id[tri[k]] + 1];
    const glm::dvec3 a = glm::dvec3(mesh.positions[tri.x]) - c, b = glm::dvec3(mesh.positions[tri.y]) - c,
                     d = glm::dvec3(mesh.positions[tri.z]) - c;
    const double det = glm::dot(a, glm::cross(b, d));
    if (!(det > 0.0)) return "triangle " + std::to_string(t) + " does not face away from the centre";
    // Van Oosterom and Strackee: tan(omega / 2) = det / (|a||b||d| + (a.b)|d| + (a.d)|b| + (b.d)|a|).
    const double la = glm::length(a), lb = glm::length(b), ld = glm::length(d);
    solidAngle += 2.0 * std::atan2(det, la * lb * ld + glm::dot(a, b) * ld + glm::dot(a, d) * lb + glm::dot(b, d) * la);
  }
  for (std::size_t v = 0; v < n; ++v) first[v + 1] += first[v];
  std::vector<std::uint32_t> to(first[n]);
  std::vector<std::size_t> cursor(first.begin(), first.end() - 1);
  for (const glm::uvec3& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) to[cursor[id[tri[k]]]++] = id[tri[(k + 1) % 3]];
  }
  for (std::size_t v = 0; v < n; ++v) {
    std::sort(to.begin() + std::ptrdiff_t(first[v]), to.begin() + std::ptrdiff_t(first[v + 1]));
  }
  // In order of (a, b): each edge once, and its reverse once.
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t j = first[a]; j < first[a + 1]; ++j) {
      const std::uint32_t b = to[j];
      if (j + 1 < first[a + 1] && to[j + 1] == b) {
        return "edge " + std::to_string(a) + "-" + std::to_string(b) + " is used twice in one direction";
      }
      if (!std::binary_search(to.begin() + std::ptrdiff_t(first[b]), to.begin() + std::ptrdiff_t(first[b + 1]),
                              std::uint32_t(a))) {
        return "edge " + std::to_string(a) + "-" + std::to_string(b) + " has no opposite: the surface is open";
      }
    }
  }
  if (std::fabs(solidAngle - 4.0 * M_PI) > 1e-6) {
    return "the solid angles sum to " + std::to_string(solidAngle) + ", not 4 pi";
  }
  return "";
}


}  // namespace rc
