// Wavefront OBJ meshes through tinyobjloader.
#pragma once

#include <string>

#include "scenes/mesh.h"

namespace rc {

// Positions, and "uv" (from vt) and "normal" (from vn) when every face corner has them.
// Polygons are fan-triangulated. Corners whose v, vt and vn indices differ (face-varying
// attributes) become separate vertices with identical positions, so both renderers see the
// same triangles and values. Materials are ignored and no other file is opened.
// Throws ioError / badInput naming the file and, where it can, the line.
// A file whose faces take the scene past budget.limit triangles is refused before it is parsed.
Mesh loadObj(const std::string& path, TriangleBudget budget = {});

}  // namespace rc
