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

Scene meshScene(const std::string& spec, Mesh mesh, std::optional<CameraSpec> camera, const SceneOverrides& o) {
  const int width = o.width ? o.width : (camera ? camera->width : 800);
  const int height = o.height ? o.height : (camera ? camera->height : 600);
  CameraSpec spec2 = camera ? *camera : frameMesh(mesh, 45.0, width, height);
  return Scene{spec, camera ? "glTF scene with its camera" : "mesh with a framing camera", std::move(mesh),
               Camera(spec2, spec)};
}

}  // namespace

Scene loadScene(const std::string& spec, const SceneOverrides& o) {
  const std::string extension = lowerExtension(spec);
  Scene scene = [&] {
    if (extension == ".obj") return meshScene(spec, loadObj(spec), std::nullopt, o);
    if (extension == ".gltf" || extension == ".glb") {
      GltfContent content = loadGltf(spec);
      return meshScene(spec, std::move(content.mesh), content.camera, o);
    }
    if (extension == ".json") return loadSceneFile(spec);
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
