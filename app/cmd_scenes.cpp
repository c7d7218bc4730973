// `rastercheck scenes [SCENE...]`: without scenes, the built-in ones, a line each; with scenes,
// what each holds as it would be rendered: triangles, attributes, camera (and a glTF file's
// other cameras).
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "app/options.h"
#include "scenes/registry.h"

namespace rc::app {
namespace {

struct ScenesArgs {
  std::vector<std::string> scenes;
  RenderSettings settings;
};

int listBuiltins() {
  for (SceneGroup group : {SceneGroup::kDefault, SceneGroup::kHardCase}) {
    std::printf(group == SceneGroup::kDefault
                    ? "Default set (`rastercheck check` with no scene, or the group name \"default\"):\n"
                    : "\nHard cases (the group name \"hard\"; each file in scenes/hard/ says what must hold):\n");
    for (const BuiltinScene& s : builtinScenes()) {
      if (s.group != group) continue;
      std::printf("  %-12s %s\n", s.name, s.description);
      if (*s.parameters) std::printf("  %-12s   parameters: %s\n", "", s.parameters);
    }
  }
  std::printf("\nParameters are given as NAME:key=value,key=value, e.g. blob:tris=1000000.\n");
  std::printf("`rastercheck scenes SCENE...` describes scenes, files included, as they would be rendered.\n");
  return 0;
}

int describeScenes(const ScenesArgs& args) {
  // Load every scene first, so that a bad one fails before anything is printed.
  std::vector<Scene> scenes;
  for (const std::string& spec : expandSceneGroups(args.scenes)) scenes.push_back(loadScene(spec, args.settings));
  for (const Scene& scene : scenes) {
    std::string attributes;
    for (const Attribute& a : scene.mesh.attributes) {
      attributes += (attributes.empty() ? "" : ", ") + a.name + " (" + std::to_string(a.components) + ")";
    }
    std::printf("%s\n  %s\n  %zu triangles, %zu vertices%s\n  attributes: %s\n  camera: %s\n", scene.name.c_str(),
                scene.description.c_str(), scene.mesh.triangleCount(), scene.mesh.vertexCount(),
                scene.mesh.closedSolid ? ", a closed solid (--cull auto drops its back faces)" : "",
                attributes.empty() ? "none" : attributes.c_str(), scene.camera.describe().c_str());
  }
  return 0;
}

}  // namespace

void registerScenes(CLI::App& root, Action& action) {
  auto args = std::make_shared<ScenesArgs>();
  CLI::App* command = root.add_subcommand(
      "scenes", "list the built-in scenes, or describe the scenes given (triangles, attributes, camera)");
  command->add_option("scene", args->scenes,
                      "built-in NAME[:key=value,...] or a group (default, hard), .obj, .gltf/.glb or .json scene file");
  addSceneOptions(command, args->settings);
  command->callback([&action, args] {
    action = [args] { return args->scenes.empty() ? listBuiltins() : describeScenes(*args); };
  });
}

}  // namespace rc::app
