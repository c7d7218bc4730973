// glTF 2.0 scenes (.gltf with embedded or neighbouring buffers, and .glb) through tinygltf.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scenes/camera.h"
#include "scenes/mesh.h"

namespace rc {

// A camera that a node of the default scene places.
struct GltfCamera {
  int index = -1;                  // in the file's `cameras`
  std::string name;                // its `name`, or empty
  std::string type;                // "perspective", "orthographic" (as the file says)
  std::optional<CameraSpec> spec;  // the camera, where rastercheck can render through it
  std::string refusal;             // otherwise why not, naming the file and the place
};

struct GltfContent {
  Mesh mesh;                        // every triangle primitive of the default scene, in world space
  std::vector<GltfCamera> cameras;  // each camera the hierarchy places, first met first (a camera
                                    // that several nodes place: the first of them)
};

// Reads POSITION, NORMAL ("normal"), TANGENT ("tangent", 4 components), TEXCOORD_n ("uv", "uv1"...), COLOR_n ("color", "color1"...)
// and application-specific "_name" attributes ("name"); attributes that
// not every primitive carries are dropped. Node transforms (matrix or TRS) are applied, and
// morph targets at the weights in force, and skins as their joints stand. Sparse accessors, KHR_mesh_quantization and
// EXT_meshopt_compression are read (docs/scene-file.md).
// Triangle lists, strips and fans are read; points, lines and primitives without POSITION are
// skipped (no surface).
// A URI is never expanded, executed or fetched: only data: URIs and relative paths inside the
// file's own folder are read. A camera is checked only when it is used: an orthographic one,
// or one whose node collapses its view, is listed with its refusal.
// Throws ioError / badInput naming the file and the place (JSON path or byte offset).
// A file whose default scene takes the scene past budget.limit triangles is refused at the node
// where it does, before they are allocated.
GltfContent loadGltf(const std::string& path, TriangleBudget budget = {});

// "cameras[1] \"side\"": the camera's place and name, as messages show them.
std::string gltfCameraName(const GltfCamera& camera);

// The cameras the file places, for a person choosing one: `0 "side", 1 "top" (orthographic)`,
// each that cannot be used marked with why (its type, or "unusable"); past 16, how many more.
std::string listGltfCameras(const GltfContent& content);

// The camera `selector` names: its index in the file's `cameras` or its name; empty, the
// first placed. nullptr when the selector is empty and the file places no camera. Throws
// usageError naming the file and listing its cameras when none matches.
const GltfCamera* selectGltfCamera(const GltfContent& content, const std::string& selector, const std::string& path);

}  // namespace rc
