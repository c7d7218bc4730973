// loadScene: dispatch on the kind of scene, then apply the overrides.
#include "scenes/scene_loader.h"

#include <filesystem>

#include "core/error.h"
#include "scenes/loaders/framing.h"
#include "scenes/loaders/gltf_loader.h"
#include "scenes/loaders/obj_loader.h"
#include "scenes/loaders/scene_file.h"
#include "scenes/registry.h"

namespace rc {
std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

namespace {

Scene meshScene(const std::string& spec, Mesh mesh, std::optional<CameraSpec> camera, std::string description,
                const SceneOverrides& o) {
  const int width = o.width ? o.width : (camera ? camera->width : 800);
  const int height = o.height ? o.height : (camera ? camera->height : 600);
  CameraSpec spec2 = camera ? *camera : frameMesh(mesh, 45.0, width, height);
  return Scene{spec, std::move(description), std::move(mesh), Camera(spec2, spec)};
}

// A glTF file's scene through the camera --camera chooses (by default the first placed). A
// camera rastercheck cannot render through is refused, unless --eye and --target replace its
// pose: the mesh is then framed as a bare mesh would be, and seen from there.
Scene gltfScene(const std::string& spec, const SceneOverrides& o) {
  GltfContent content = loadGltf(spec, {o.maxTriangles});
  const GltfCamera* chosen = selectGltfCamera(content, o.camera, spec);
  if (!chosen) return meshScene(spec, std::move(content.mesh), std::nullopt, "glTF mesh with a framing camera", o);
  std::string which = gltfCameraName(*chosen);
  if (content.cameras.size() > 1) which += " (it places " + listGltfCameras(content) + ")";
  if (chosen->spec) return meshScene(spec, std::move(content.mesh), chosen->spec, "glTF scene through its " + which, o);
  if (!(o.eye && o.target)) {
    throw Error(ExitCode::kBadInput, chosen->refusal + " (choose another of the file's cameras with --camera, or give "
                                                       "--eye and --target to view the scene from elsewhere)");
  }
  return meshScene(spec, std::move(content.mesh), std::nullopt,
                   "glTF mesh with a framing camera (" + which + " cannot be used)", o);
}
}  // namespace

Scene loadScene(const std::string& spec, const SceneOverrides& o) {
  const std::string extension = lowerExtension(spec);
  const bool gltf = extension == ".gltf" || extension == ".glb";
  if (!o.camera.empty() && !gltf) {
    throw usageError("--camera " + o.camera + ": chooses among a glTF file's cameras, and " + spec + " is not a glTF file");
  }
  Scene scene = [&] {
    if (extension == ".obj") return meshScene(spec, loadObj(spec, {o.maxTriangles}), std::nullopt, "mesh with a framing camera", o);
    if (gltf) return gltfScene(spec, o);
    if (extension == ".json") return loadSceneFile(spec, o.maxTriangles);
    return makeBuiltinScene(spec);
  }();
  if (o.width || o.height || o.eye || o.target || o.up || o.fovYDegrees) {
    CameraSpec camera = scene.camera.spec();
    if (o.width) camera.width = o.width;
    if (o.height) camera.height = o.height;
    if (o.eye) camera.eye = *o.eye;
    if (o.target) camera.target = *o.target;
    if (o.up) camera.up = *o.up;
    if (o.fovYDegrees) camera.fovYDegrees = *o.fovYDegrees;
    scene.camera = Camera(camera, "command line (--eye, --target, --up, --fov, --size)");
  }
  if (o.attributes) selectAttributes(scene.mesh, *o.attributes, spec);
  return scene;
}

}  // namespace rc
