// "cube": a unit cube, rotated, with per-face UVs (24 vertices, 12 triangles), so every face
// carries its own [0,1]^2 parameterisation and three faces are seen in perspective.
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/builtin/builtin.h"

namespace rc::builtin {

Scene makeCube(SceneArgs&) {
  Mesh mesh;
  // Each face: a normal axis, and the two in-plane axes that carry u and v.
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const glm::mat4 rotation = glm::rotate(glm::mat4(1.f), 0.5f, glm::normalize(glm::vec3(1, 1, 0)));
  HugeVector<float> uvs;
  for (const glm::vec3& n : normals) {
    const glm::vec3 a = (n.x != 0.f) ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    const glm::vec3 b = glm::cross(n, a);
    const unsigned base = static_cast<unsigned>(mesh.positions.size());
    const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
      const glm::vec3 p = n + c[0] * a + c[1] * b;
      mesh.positions.push_back(glm::vec3(rotation * glm::vec4(p, 1.f)));
      uvs.push_back(0.5f * (c[0] + 1.f));
      uvs.push_back(0.5f * (c[1] + 1.f));
    }
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
  }
  mesh.attributes.push_back({"uv", 2, std::move(uvs)});
  mesh.closedSolid = true;  // convex, every face counter-clockwise seen from outside
  const CameraSpec camera = lookAt({2.6, 2.2, 3.4}, {0.0, 0.0, 0.0}, 50.0, 0.1);
  return Scene{"cube", "", std::move(mesh), Camera(camera, "scene cube")};
}

}  // namespace rc::builtin
