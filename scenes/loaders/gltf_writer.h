// Writing a scene as glTF 2.0 (`rastercheck export`), so that another renderer can draw exactly
// the scene rastercheck measures: the built-in and hard-case scenes included.
#pragma once

#include <string>

#include "scenes/scene.h"

namespace rc {

// The scene as one glTF 2.0 document: a `.glb` (binary) or a `.gltf` with its buffer embedded as
// a data: URI. The mesh is one primitive of float positions, 32-bit indices in the mesh's
// triangle order, and its attributes ("normal" as NORMAL, "uv", "uv1"... as TEXCOORD_n, "color",
// "color1"... as COLOR_n, any other as the application-specific "_name"), all as stored, bit
// for bit. The camera
// is a perspective camera on a node placed by a matrix (glTF's convention: looking down -Z, +Y
// up). glTF has no image size and keeps only yfov and the pose, so the camera's extras also hold
// rastercheck's camera exactly ("rastercheck_camera": eye, target, up, fov_y_degrees, near, far,
// width, height), which loadGltf uses while they agree with the node (docs/scene-file.md).
std::string gltfFromScene(const Scene& scene, bool binary);

}  // namespace rc
