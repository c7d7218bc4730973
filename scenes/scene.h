// A scene: one mesh and one camera, both renderers' only input.
#pragma once

#include <string>

#include "scenes/camera.h"
#include "scenes/mesh.h"

namespace rc {

struct Scene {
  std::string name;         // as given on the command line, e.g. "blob:tris=100000"
  std::string description;  // one line
  Mesh mesh;
  Camera camera;
};

}  // namespace rc
