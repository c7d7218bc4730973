// glTF 2.0 scenes (.gltf with embedded or neighbouring buffers, and .glb) through tinygltf.
#pragma once

#include <optional>
#include <string>

#include "scenes/camera.h"
#include "scenes/mesh.h"

namespace rc {

struct GltfContent {
  Mesh mesh;                          // every triangle primitive of the default scene, in world space
  std::optional<CameraSpec> camera;   // the first camera met in the node hierarchy, if any
};

// Reads POSITION, NORMAL ("normal"), TEXCOORD_n ("uv", "uv1"...), COLOR_n ("color", "color1"...)
// and application-specific "_name" attributes ("name"); attributes that
// not every primitive carries are dropped. Node transforms (matrix or TRS) are applied, and
// morph targets at the weights in force, and skins as their joints stand. Sparse accessors, KHR_mesh_quantization and
// EXT_meshopt_compression are read (docs/scene-file.md).
// Triangle lists, strips and fans are read; points and lines are skipped (no surface).
// A URI is never expanded, executed or fetched: only data: URIs and relative paths inside the
// file's own folder are read. Orthographic cameras are refused.
// Throws ioError / badInput naming the file and the place (JSON path or byte offset).
GltfContent loadGltf(const std::string& path);

}  // namespace rc
