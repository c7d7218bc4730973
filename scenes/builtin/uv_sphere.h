// A UV-sphere tessellation shared by "sphere" and "blob": rows of constant latitude, a seam
// column duplicated so UVs are continuous, one triangle (not a degenerate quad) at each pole.
#pragma once

#include <functional>

#include "scenes/mesh.h"

namespace rc::builtin {

// position(theta, phi) gives the surface point for polar angle theta in [0, pi] and azimuth
// phi in [0, 2 pi]. Adds "uv" = (phi / 2pi, theta / pi); the caller adds normals. The seam
// column and the pole rows repeat their positions exactly, so a position function that is
// continuous in phi gives a closed surface.
Mesh makeUvSphereMesh(int stacks, int slices,
                      const std::function<glm::vec3(double theta, double phi)>& position);

// Area-weighted vertex normals of the mesh, added as attribute "normal".
void addVertexNormals(Mesh& mesh);

}  // namespace rc::builtin
