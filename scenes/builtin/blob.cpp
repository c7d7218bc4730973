// "blob": the scalable scene for the performance work. A bumpy ellipsoid (stretched to the
// 16:9 frame) that covers about two thirds of a 1920x1080 image. tris=N asks for about N
// triangles: the UV tessellation with s stacks and 2s slices has 4s^2 - 4s triangles, so s is
// the nearest integer to (1 + sqrt(1 + N)) / 2.
#include <cmath>

#include "scenes/builtin/builtin.h"
#include "scenes/builtin/uv_sphere.h"

namespace rc::builtin {

Scene makeBlob(SceneArgs& args) {
  const long long requested = args.getInt("tris", 100000, 8, 4000000);
  const int stacks = std::max(2, int(std::lround((1.0 + std::sqrt(1.0 + double(requested))) / 2.0)));
  Mesh mesh = makeUvSphereMesh(stacks, 2 * stacks, [](double theta, double phi) {
    const double r = 1.0 + 0.06 * std::sin(9.0 * theta) * std::cos(7.0 * phi);
    return glm::vec3(float(1.7 * r * std::sin(theta) * std::cos(phi)), float(r * std::cos(theta)),
                     float(-r * std::sin(theta) * std::sin(phi)));
  });
  addVertexNormals(mesh);
  mesh.closedSolid = true;  // r > 0 at every angle: a solid star-shaped about the origin
  const CameraSpec camera = lookAt({0.0, 0.0, 3.4}, {0.0, 0.0, 0.0}, 40.0, 0.1, 1920, 1080);
  return Scene{"blob", "", std::move(mesh), Camera(camera, "scene blob")};
}

}  // namespace rc::builtin
