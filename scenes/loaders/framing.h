// The default camera of a bare mesh: it frames the mesh's bounding sphere.
#pragma once

#include "scenes/camera.h"
#include "scenes/mesh.h"

namespace rc {

// Looks at the bounding box's centre from the direction (0.5, 0.4, 1) (front, right, above for
// a Y-up mesh), far enough that the bounding sphere fits the narrower field of view with 5%
// to spare; near is half the distance to the sphere, far is infinite.
CameraSpec frameMesh(const Mesh& mesh, double fovYDegrees = 45.0, int width = 800, int height = 600);

}  // namespace rc
