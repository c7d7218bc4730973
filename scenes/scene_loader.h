// One entry point for every way a scene is named: a built-in scene (NAME[:key=value,...]), an
// OBJ or glTF file, or a scene file (.json), plus the command line's overrides.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace rc {

struct SceneOverrides {
  int width = 0, height = 0;              // image size; 0 keeps the scene's
  std::optional<glm::dvec3> eye, target, up;  // camera position, aim and up direction
  std::optional<double> fovYDegrees;
  std::optional<std::vector<std::string>> attributes;  // narrow the attributes written
  std::string camera;  // a glTF file's camera, by index in its `cameras` or by name; empty: the first placed
  // Files whose meshes make more triangles are refused while they load, before the triangles
  // are allocated (built-in scenes bound their own sizes).
  std::size_t maxTriangles = kNoTriangleLimit;
};

// Files are recognised by their extension (.obj, .gltf, .glb, .json, any case); anything else
// is a built-in scene name. A bare mesh (OBJ, or glTF without a camera) gets a camera framing
// its bounding box (scenes/loaders/framing.h). A glTF file is seen through the camera
// `overrides.camera` names, by default the first its hierarchy places; one rastercheck cannot
// render through (orthographic) is refused unless --eye and --target replace it.
// Throws usageError / badInput / ioError.
Scene loadScene(const std::string& spec, const SceneOverrides& overrides = {});

// The extension of a path's file name, with its dot, in lower case: ".obj", ".png"; "" for none.
std::string lowerExtension(const std::string& path);

}  // namespace rc
