// "floor": the seed notes' case. Two triangles make a 20x20 floor whose UV spans [0,1]^2 (an
// 8x8 checkerboard in the preview), seen from 1 unit above it. It runs from 1 to 21 units in
// front of the eye, so the far rows are seen at under 3 degrees and w varies 20x across each
// triangle: screen-space (affine) interpolation visibly bends the checker and breaks it along
// the diagonal, while perspective-correct interpolation keeps every line straight.
#include "scenes/builtin/builtin.h"

namespace rc::builtin {

Scene makeFloor(SceneArgs&) {
  Mesh mesh;
  mesh.positions = {{-10.f, 0.f, -21.f}, {10.f, 0.f, -21.f}, {10.f, 0.f, -1.f}, {-10.f, 0.f, -1.f}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  Attribute& uv = mesh.addAttribute("uv", 2);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    uv.values[2 * i + 0] = (mesh.positions[i].x + 10.f) / 20.f;
    uv.values[2 * i + 1] = (mesh.positions[i].z + 21.f) / 20.f;
  }
  const CameraSpec camera = lookAt({0.0, 1.0, 0.0}, {0.0, 0.0, -9.0}, 60.0, 0.05, 800, 600);
  return Scene{"floor", "", std::move(mesh), Camera(camera, "scene floor")};
}

}  // namespace rc::builtin
