// The scene file: a small JSON document naming meshes (OBJ or glTF, by path relative to the
// file), their transforms, the camera, the image size and the attributes to output.
// docs/scene-file.md describes it.
#pragma once

#include <string>

#include "scenes/scene.h"

namespace rc {

// Throws badInput naming the file and the JSON pointer (or line and column for syntax errors)
// of the first problem; ioError when a mesh file cannot be read.
Scene loadSceneFile(const std::string& path, std::size_t maxTriangles = kNoTriangleLimit);

}  // namespace rc
