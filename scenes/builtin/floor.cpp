// "floor": the seed notes' case. Two triangles make a 200x200 floor with a checker UV
// (8 units across, 64 checks in the preview), seen from 1 unit above it, looking 2.3 degrees
// below the horizon. The floor reaches behind the eye, so both triangles cross the near
// plane. Screen-space (affine) interpolation visibly bends the checker; the gate must fail it.
#include "scenes/builtin/builtin.h"

namespace rc::builtin {

Scene makeFloor(SceneArgs&) {
  Mesh mesh;
  mesh.positions = {{-100.f, 0.f, -100.f}, {100.f, 0.f, -100.f}, {100.f, 0.f, 100.f},
                    {-100.f, 0.f, 100.f}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  Attribute& uv = mesh.addAttribute("uv", 2);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    uv.values[2 * i + 0] = (mesh.positions[i].x + 100.f) / 25.f;
    uv.values[2 * i + 1] = (mesh.positions[i].z + 100.f) / 25.f;
  }
  CameraSpec camera;
  camera.eye = {0.0, 1.0, 0.0};
  camera.target = {0.0, 0.6, -10.0};
  camera.fovYDegrees = 60.0;
  camera.zNear = 0.05;
  camera.width = 800;
  camera.height = 600;
  return Scene{"floor", "", std::move(mesh), Camera(camera, "scene floor")};
}

}  // namespace rc::builtin
