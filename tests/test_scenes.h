// Small hand-built scenes for tests: one or a few triangles in front of a camera.
#pragma once

#include <cctype>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace rc::testing {

// A GoogleTest parameter name for a scene spec: "closed:seed=1" -> "closed_seed_1".
inline std::string sceneTestName(const std::string& spec) {
  std::string name;
  for (char c : spec) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

// A scene named `name` with the given triangles (each three consecutive positions), an
// attribute "uv" equal to each vertex's (x, y), and a camera at `eye` looking at the origin.
inline Scene makeTriangleScene(const std::vector<glm::vec3>& corners, int width = 64,
                               int height = 48, glm::dvec3 eye = {0.0, 0.0, 3.0},
                               double zNear = 0.1, const char* name = "test") {
  Mesh mesh;
  mesh.positions.assign(corners.begin(), corners.end());
  for (unsigned i = 0; i + 2 < corners.size(); i += 3) mesh.triangles.push_back({i, i + 1, i + 2});
  Attribute& uv = mesh.addAttribute("uv", 2);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    uv.values[2 * i] = corners[i].x;
    uv.values[2 * i + 1] = corners[i].y;
  }
  CameraSpec spec;
  spec.eye = eye;
  spec.target = {0.0, 0.0, 0.0};
  spec.fovYDegrees = 60.0;
  spec.zNear = zNear;
  spec.width = width;
  spec.height = height;
  validateMesh(mesh, name);
  return Scene{name, "test scene", std::move(mesh), Camera(spec, name)};
}

}  // namespace rc::testing
