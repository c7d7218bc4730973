// `rastercheck check [SCENE...]`: both paths, compare, one row per scene; exit 0 only if every
// scene passes the gate.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "app/check.h"
#include "app/commands.h"
#include "compare/report.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/exr_io.h"
#include "scenes/registry.h"

namespace rc::app {
namespace {

struct CheckArgs {
  std::vector<std::string> scenes;
  std::string out, json;
  bool verbose = false;
  RenderSettings settings;
  Thresholds thresholds;
};

// Output file stem of a scene: a file's own stem ("../data/spot.obj" -> "spot"), a built-in
// scene's spec made safe ("blob:tris=1000" -> "blob_tris-1000"); "-2", "-3"... on collisions.
std::string fileStem(const std::string& scene, std::set<std::string>& used) {
  const std::filesystem::path path(scene);
  const std::string source = path.has_extension() ? path.stem().string() : scene;
  std::string stem;
  for (char c : source) {
    const bool plain = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
    stem += plain ? c : (c == '=' ? '-' : '_');
  }
  std::string unique = stem;
  for (int n = 2; !used.insert(unique).second; ++n) unique = stem + "-" + std::to_string(n);
  return unique;
}

void writeOutputs(const std::string& dir, const std::string& stem, const CheckResult& r) {
  const std::string base = (std::filesystem::path(dir) / stem).string();
  writeExr(r.raster, base + ".raster.exr");
  writeExr(r.reference, base + ".reference.exr");
  writeExr(r.heatmap, base + ".heatmap.exr");
}

int runCheck(CheckArgs& args) {
  finishRenderSettings(args.settings);
  setExrThreads(args.settings.threads);
  if (args.scenes.empty()) args.scenes = defaultSceneNames();
  if (!args.out.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(args.out, ec);
    if (!std::filesystem::is_directory(args.out)) {
      throw ioError(args.out, "cannot create the output folder" + (ec ? ": " + ec.message() : ""));
    }
  }
  // Load every scene first, so a bad name fails before any work is done.
  std::vector<Scene> scenes;
  for (const std::string& spec : args.scenes) scenes.push_back(loadScene(spec, args.settings));

  std::printf("%-22s %9s %11s %-7s %9s %9s %9s %9s %9s %9s\n", "scene", "triangles", "size", "verdict",
              "bary max", "bary p999", "depth max", "disagree", "raster ms", "ref ms");
  nlohmann::json rows = nlohmann::json::array();
  bool allPass = true;
  std::set<std::string> stems;
  for (const Scene& scene : scenes) {
    const CheckResult r = checkScene(scene, args.settings, args.thresholds, !args.out.empty());
    const FamilyStats& bary = r.report.families[0].stats;
    const FamilyStats& depth = r.report.families[1].stats;
    const std::string size = std::to_string(r.report.width) + "x" + std::to_string(r.report.height);
    std::printf("%-22s %9zu %11s %-7s %9s %9s %9s %9s %9.1f %9.1f\n", scene.name.c_str(), r.triangles,
                size.c_str(), r.report.pass ? "PASS" : "FAIL", formatNumber(bary.max).c_str(),
                formatNumber(bary.p999).c_str(), formatNumber(depth.max).c_str(),
                formatNumber(r.report.disagreementFraction).c_str(), r.rasterMs, r.referenceMs);
    for (const std::string& reason : r.report.reasons) std::printf("    - %s\n", reason.c_str());
    if (args.verbose) std::printf("%s\n", reportToTable(r.report).c_str());
    if (!args.out.empty()) writeOutputs(args.out, fileStem(scene.name, stems), r);
    allPass = allPass && r.report.pass;
    nlohmann::json row = {{"scene", scene.name},
                    {"triangles", r.triangles},
                    {"mode", interpolationName(args.settings.raster.interpolation)},
                    {"precision", precisionName(args.settings.raster.precision)},
                    {"subpixel_bits", args.settings.raster.subpixelBits},
                    {"threads", resolveThreadCount(args.settings.threads)},
                    {"raster_ms", r.rasterMs},
                    {"reference_ms", r.referenceMs},
                    {"report", reportToJson(r.report)}};
    rows.push_back(row);
  }
  std::printf("%zu scene(s): %s\n", scenes.size(), allPass ? "all pass" : "GATE FAILED");
  if (!args.json.empty()) {
    nlohmann::json j = {{"format_version", kReportFormatVersion},
                        {"verdict", allPass ? "pass" : "fail"},
                        {"scenes", rows}};
    writeTextFile(args.json, j.dump(2) + "\n");
  }
  return allPass ? 0 : 1;
}

}  // namespace

void registerCheck(CLI::App& root, Action& action) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* command = root.add_subcommand(
      "check", "render scenes with both paths, compare them and gate (the CI accuracy gate)");
  command->add_option("scenes", args->scenes,
                      "scenes: built-in NAME[:key=value,...], .obj, .gltf/.glb or .json scene file; default: the built-in default set");
  command->add_option("--out", args->out, "write raster, reference and heatmap EXRs to this folder");
  command->add_option("--json", args->json, "write a JSON report of every scene here");
  command->add_flag("-v,--verbose", args->verbose, "print the full comparison table per scene");
  addRenderOptions(command, args->settings);
  addThresholdOptions(command, args->thresholds);
  command->callback([args, &action] { action = [args] { return runCheck(*args); }; });
}

}  // namespace rc::app
