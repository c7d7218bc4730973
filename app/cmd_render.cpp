// `rastercheck render SCENE --backend raster|reference -o FILE.exr`
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "app/options.h"
#include "app/outputs.h"
#include "core/clock.h"
#include "core/exr_io.h"

namespace rc::app {
namespace {

enum class Backend { kRaster, kReference };

struct RenderArgs {
  std::string scene;
  Backend backend = Backend::kRaster;
  std::string output;
  RenderSettings settings;
  ExrCompression compression = ExrCompression::kZip;
};

int runRender(RenderArgs& args) {
  finishRenderSettings(args.settings);
  const std::vector<OutputOption> outputList = {{"-o", args.output, ".exr"}};
  checkOutputs(outputList, {args.scene});  // a scene file is not overwritten by its render
  checkOutputFolders(outputList);
  const Scene scene = loadScene(args.scene, args.settings);
  setExrThreads(args.settings.threads);
  const long long start = nowNanoseconds();
  const bool raster = args.backend == Backend::kRaster;
  const Framebuffer fb = raster ? rasterize(scene, args.settings.raster) : renderReference(scene, args.settings.reference);
  const double ms = millisecondsSince(start);
  writeExr(fb, args.output, args.compression);
  std::printf("%s: %s %dx%d, %zu triangles, %.1f ms -> %s\n", scene.name.c_str(), raster ? "raster" : "reference",
              fb.width(), fb.height(), scene.mesh.triangleCount(), ms, args.output.c_str());
  return 0;
}

}  // namespace

void registerRender(CLI::App& root, Action& action) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* command = root.add_subcommand("render", "render one scene with one backend to an EXR file");
  command->add_option("scene", args->scene, "built-in NAME[:key=value,...], .obj, .gltf/.glb or .json scene file")->required();
  addChoice<Backend>(command, "--backend", args->backend, {{"raster", Backend::kRaster}, {"reference", Backend::kReference}},
                     "the rasterizer or the Embree reference");
  command->add_option("-o,--output", args->output, "output EXR file")->required();
  addRenderOptions(command, args->settings);
  addExrCompressionOption(command, args->compression);
  command->callback([args, &action] { action = [args] { return runRender(*args); }; });
}

}  // namespace rc::app
