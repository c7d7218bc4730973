// "sphere": a unit UV sphere with normals and UVs; segments=N sets the stack count (slices are
// twice that): 4N^2 - 4N triangles (3,968 at the default 32).
#include <cmath>

#include "scenes/builtin/builtin.h"
#include "scenes/builtin/uv_sphere.h"

namespace rc::builtin {

Scene makeSphere(SceneArgs& args) {
  const int stacks = static_cast<int>(args.getInt("segments", 32, 4, 1024));
  Mesh mesh = makeUvSphereMesh(stacks, 2 * stacks, [](double theta, double phi) {
    return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                     float(-std::sin(theta) * std::sin(phi)));
  });
  addVertexNormals(mesh);
  mesh.closedSolid = true;
  const CameraSpec camera = lookAt({0.0, 0.8, 2.8}, {0.0, 0.0, 0.0}, 50.0, 0.1);
  return Scene{"sphere", "", std::move(mesh), Camera(camera, "scene sphere")};
}

}  // namespace rc::builtin
