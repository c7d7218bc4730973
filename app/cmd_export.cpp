// `rastercheck export SCENE... (-o FILE.gltf|FILE.glb | --out DIR)`: scenes as glTF 2.0 files,
// so that another renderer can draw exactly what rastercheck measures, the built-in and hard
// cases included, and its output be compared with `rastercheck compare`.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "app/commands.h"
#include "app/options.h"
#include "app/outputs.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "scenes/loaders/gltf_writer.h"
#include "scenes/registry.h"

namespace rc::app {
namespace {

enum class Format { kGltf, kGlb };

struct ExportArgs {
  std::vector<std::string> scenes;
  std::string output, out;
  Format format = Format::kGltf;
  RenderSettings settings;
};

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && lowerCase(text.substr(text.size() - suffix.size())) == suffix;
}

int runExport(ExportArgs& args) {
  args.scenes = expandSceneGroups(args.scenes);
  if (args.output.empty() == args.out.empty()) throw usageError("give -o FILE (one scene) or --out DIR (any number)");
  if (!args.output.empty() && args.scenes.size() != 1) {
    throw usageError("-o writes one scene, but " + std::to_string(args.scenes.size()) + " are given; use --out DIR");
  }
  if (!args.output.empty() && !endsWith(args.output, ".gltf") && !endsWith(args.output, ".glb")) {
    throw usageError("-o " + args.output + ": name a .gltf or .glb file");
  }
  // Load every scene first, so a bad name or file fails before anything is written.
  std::vector<Scene> scenes;
  for (const std::string& spec : args.scenes) scenes.push_back(loadScene(spec, args.settings));

  std::vector<std::string> paths;
  if (!args.output.empty()) {
    paths.push_back(args.output);
  } else {
    std::set<std::string> stems;
    for (const Scene& scene : scenes) {
      paths.push_back((std::filesystem::path(args.out) / (fileStem(scene.name, stems) + (args.format == Format::kGlb ? ".glb" : ".gltf"))).string());
    }
  }
  std::vector<OutputOption> outputList;
  for (const std::string& path : paths) outputList.push_back({args.output.empty() ? "--out" : "-o", path, endsWith(path, ".glb") ? ".glb" : ".gltf"});
  checkOutputs(outputList, args.scenes);  // a scene file is not overwritten by its own export
  WrittenOutputs outputs;
  if (!args.out.empty()) outputs.makeFolder(args.out);
  checkOutputFolders(outputList);
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const Scene& scene = scenes[i];
    const std::string document = gltfFromScene(scene, endsWith(paths[i], ".glb"));
    outputs.write(paths[i], [&](const std::string& path) { writeTextFile(path, document); });
    const std::size_t attributes = scene.mesh.attributes.size();
    std::printf("%s: %zu triangles, %zu attribute%s, %dx%d -> %s\n", scene.name.c_str(), scene.mesh.triangleCount(),
                attributes, attributes == 1 ? "" : "s", scene.camera.width(), scene.camera.height(), paths[i].c_str());
  }
  outputs.keep();
  return 0;
}

}  // namespace

void registerExport(CLI::App& root, Action& action) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* command = root.add_subcommand(
      "export", "write scenes as glTF 2.0 files (mesh, attributes, camera), for another renderer to draw (docs/scene-file.md)");
  command->add_option("scene", args->scenes, "built-in NAME[:key=value,...] or a group (default, hard), .obj, .gltf/.glb or .json scene file")
      ->required();
  command->add_option("-o,--output", args->output, "the .gltf or .glb file to write (one scene)");
  command->add_option("--out", args->out, "folder to write one file per scene into, named as check --out names them");
  addChoice<Format>(command, "--format", args->format, {{"gltf", Format::kGltf}, {"glb", Format::kGlb}},
                    "with --out: .gltf (JSON, the buffer embedded) or .glb (binary)");
  addSceneOptions(command, args->settings);
  command->callback([args, &action] { action = [args] { return runExport(*args); }; });
}

}  // namespace rc::app
