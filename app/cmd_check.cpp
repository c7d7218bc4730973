// `rastercheck check [SCENE...]`: both paths, compare, one row per scene; exit 0 only if every
// scene passes the gate. --out writes EXRs and PNGs, --report an HTML report, --json a report.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "app/bench_files.h"
#include "app/check.h"
#include "app/commands.h"
#include "app/html_report.h"
#include "app/junit.h"
#include "app/options.h"
#include "app/outputs.h"
#include "app/progress.h"
#include "compare/baseline.h"
#include "compare/heatmap_png.h"
#include "compare/report.h"
#include "core/atomic_file.h"
#include "core/channels.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/parallel.h"
#include "core/png_io.h"
#include "scenes/registry.h"

namespace rc::app {
namespace {

namespace fs = std::filesystem;

struct CheckArgs {
  std::vector<std::string> scenes;
  std::string out, report, json, junit, benchJson;
  bool verbose = false, quiet = false;
  RenderSettings settings;
  Thresholds thresholds;
  BaselineUse baseline;
  std::vector<std::string> givenLimits;  // the fixed limits given on the command line
  ExrCompression compression = ExrCompression::kZip;
};

// The three pictures of a scene, made once and written to every folder that wants them.
struct ScenePictures {
  Rgb8Image raster, reference, heatmap;
};

void writePngs(const std::string& dir, const std::string& stem, const ScenePictures& p, WrittenOutputs& outputs) {
  const std::string base = (fs::path(dir) / stem).string();
  // (No structured binding: clang 14 cannot capture one in the lambda.)
  for (const auto& file : {std::pair{&p.raster, ".raster.png"}, std::pair{&p.reference, ".reference.png"},
                           std::pair{&p.heatmap, ".heatmap.png"}}) {
    outputs.write(base + file.second, [&](const std::string& path) { writePng(*file.first, path); });
  }
}

void writeExrs(const std::string& dir, const std::string& stem, const CheckResult& r, ExrCompression compression,
               WrittenOutputs& outputs) {
  const std::string base = (fs::path(dir) / stem).string();
  for (const auto& file : {std::pair{&r.raster, ".raster.exr"}, std::pair{&r.reference, ".reference.exr"},
                           std::pair{&r.heatmap, ".heatmap.exr"}}) {
    outputs.write(base + file.second, [&](const std::string& path) { writeExr(*file.first, path, compression); });
  }
}

std::string settingsLine(const RenderSettings& s) {
  return std::string("rasterizer: ") + interpolationName(s.raster.interpolation) + ", " +
         precisionName(s.raster.precision) + ", " +
         (s.raster.subpixelBits == 0 ? std::string("no snapping") : std::to_string(s.raster.subpixelBits) + " subpixel bits") +
         (s.raster.fillRule == FillRule::kTopLeft ? std::string()
                                                  : std::string(", ") + fillRuleName(s.raster.fillRule) +
                                                        " fill rule (wrong on purpose)") +
         "; reference: Embree " + s.reference.isa + "; " +
         std::to_string(resolveThreadCount(s.threads)) + " threads; rastercheck " RASTERCHECK_VERSION;
}

// Every attribute --max-attr or --warn-attr names must be one the scene's renders carry: a name
// that gates nothing is a typo, refused before any scene is rendered.
void requireAttributeLimitsApply(const Scene& scene, const std::string& spec, const Thresholds& thresholds,
                                 const RenderSettings& settings) {
  for (const auto& [option, limits] : {std::pair{"--max-attr", &thresholds.attributeByName},
                                       std::pair{"--warn-attr", &thresholds.warn.attributeByName}}) {
    for (const auto& [name, limit] : *limits) {
      const auto& chosen = settings.attributes;
      const std::string names = spec + ": " + option + " names '" + name + "', which ";
      if (!chosen.empty() && std::find(chosen.begin(), chosen.end(), name) == chosen.end()) {
        throw usageError(names + "--attributes leaves out");
      }
      if (scene.mesh.findAttribute(name)) continue;
      std::string carried;
      for (const Attribute& a : scene.mesh.attributes) carried += (carried.empty() ? "" : ", ") + a.name;
      throw usageError(names + "the scene does not carry (it has: " + (carried.empty() ? "none" : carried) + ")");
    }
  }
}

// Holds a scene's report to its figures in the baseline (--baseline), the `occurrence`th of its
// name there as here: a scene the baseline lacks, or had with another triangle count, is a
// warning of its own, and its figures are not held.
void holdSceneToBaseline(CompareReport& report, const std::string& scene, std::size_t occurrence, std::size_t triangles,
                         const Baseline& baseline, const BaselineUse& use) {
  const auto it = baseline.find(scene);
  const BaselineFigures* before = it != baseline.end() && occurrence < it->second.size() ? &it->second[occurrence] : nullptr;
  if (before && before->triangles == triangles) return holdReportToBaseline(report, *before, use);
  report.warnings.push_back(!before ? "not in the baseline " + use.file + ": not held to it"
                                    : "the baseline's scene had " + std::to_string(*before->triangles) +
                                          " triangles, this one " + std::to_string(triangles) + ": not held to it");
  report.baseline = use;
  report.settleWarnings();
}

nlohmann::json auditPixel(const CoverageAudit::Pixel& p) {
  if (p.x < 0) return nullptr;
  const auto id = [](std::uint32_t t) { return t == channels::kNoTriangle ? nlohmann::json(nullptr) : nlohmann::json(t); };
  return {{"x", p.x}, {"y", p.y}, {"written", id(p.written)}, {"owner", id(p.owner)}};
}

nlohmann::json auditDiagnostic(std::size_t count, const CoverageAudit::Diagnostic& d) {
  if (count == 0) return nullptr;
  return {{"x", d.x}, {"y", d.y}, {"triangle", d.triangle}, {"written", d.written}, {"audited", d.audited}};
}

nlohmann::json auditToJson(const CoverageAudit& a) {
  return {{"covered", a.covered},          {"on_edge", a.onEdge},
          {"not_owned", a.notOwned},       {"lost", a.lost},
          {"off_grid", a.offGrid},         {"first_off_grid", a.offGrid == 0 ? nlohmann::json(nullptr) : nlohmann::json(a.firstOffGrid)},
          {"first_not_owned", auditPixel(a.firstNotOwned)}, {"first_lost", auditPixel(a.firstLost)},
          {"diagnosed", a.diagnosed},
          {"edge_distance_short", a.edgeDistanceShort},
          {"first_edge_distance_short", auditDiagnostic(a.edgeDistanceShort, a.firstEdgeDistanceShort)},
          {"depth_tie_wide", a.depthTieWide},
          {"first_depth_tie_wide", auditDiagnostic(a.depthTieWide, a.firstDepthTieWide)},
          {"bound_wide", a.boundWide},
          {"first_bound_wide", auditDiagnostic(a.boundWide, a.firstBoundWide)},
          {"edge_band", a.edgeBand},
          {"edge_band_limit", a.edgeBandLimit},
          {"camera_mismatch", a.cameraMismatch},
          {"ms", a.ms}};
}

// The scene's line of check's table, then its reasons and warnings (with --verbose, its whole
// report and the coverage audit).
void printSceneLine(const Scene& scene, const CheckResult& r, int nameWidth, bool verbose) {
  const FamilyStats& bary = r.report.families[0].stats;
  const FamilyStats& depth = r.report.families[1].stats;
  const std::string size = std::to_string(r.report.width) + "x" + std::to_string(r.report.height);
  std::printf("%-*s %9zu %11s %-7s %9s %9s %9s %9s %9.1f %9.1f\n", nameWidth, scene.name.c_str(), r.triangles, size.c_str(),
              r.report.pass ? "PASS" : "FAIL", formatNumber(bary.max).c_str(), formatNumber(bary.p999).c_str(),
              formatNumber(depth.max).c_str(), formatNumber(r.report.disagreementFraction).c_str(), r.rasterMs,
              r.referenceMs);
  for (const std::string& reason : r.report.reasons) std::printf("    - %s\n", reason.c_str());
  for (const std::string& warning : r.report.warnings) std::printf("    warning: %s\n", warning.c_str());
  if (verbose) std::printf("%s\n%s\n", reportToTable(r.report).c_str(), auditLine(r.audit).c_str());
  std::fflush(stdout);
}

// The scene's row of check --json (docs/report-format.md).
nlohmann::json checkJsonRow(const Scene& scene, const CheckResult& r, const RenderSettings& settings) {
  // A float frame's pixels resolved in double (docs/rasterizer.md); null for a double frame.
  const auto promoted = r.raster.attributes.find(channels::header::kPromotedPixels);
  return {{"scene", scene.name},
          {"triangles", r.triangles},
          {"mode", interpolationName(settings.raster.interpolation)},
          {"precision", precisionName(settings.raster.precision)},
          {"subpixel_bits", settings.raster.subpixelBits},
          {"fill_rule", fillRuleName(settings.raster.fillRule)},
          {"threads", resolveThreadCount(settings.threads)},
          {"raster_ms", r.rasterMs},
          {"reference_ms", r.referenceMs},
          {"promoted_pixels", promoted == r.raster.attributes.end() ? nlohmann::json(nullptr)
                                                                    : nlohmann::json(std::stoull(promoted->second))},
          {"coverage_audit", auditToJson(r.audit)},
          {"report", reportToJson(r.report)}};
}

// What check gathers scene by scene, for its summary line and the files written at the end.
struct CheckTally {
  nlohmann::json rows = nlohmann::json::array();  // check --json's scenes
  std::vector<ReportScene> reportScenes;
  std::vector<JUnitCase> junitCases;
  std::set<std::string> stems;                    // the file names taken so far
  std::map<std::string, std::size_t> occurrences;  // of each scene name so far, to pair with the baseline's
  bool allPass = true;
  std::size_t warned = 0;  // scenes with a warning
};

// Every scene loaded before any is rendered, so that a bad name or file fails before any work.
std::vector<Scene> loadCheckScenes(const CheckArgs& args, Progress& progress) {
  std::vector<Scene> scenes;
  for (const std::string& spec : args.scenes) {
    progress.step("loading " + spec);
    scenes.push_back(loadScene(spec, args.settings));
    requireAttributeLimitsApply(scenes.back(), spec, args.thresholds, args.settings);
  }
  return scenes;
}

// One scene: both paths, the comparison and the baseline; its line of the table, its EXRs and
// pictures (--out, --report) and its entries in the tally.
void checkOneScene(const Scene& scene, const CheckArgs& args, const Baseline& baseline, int nameWidth,
                   Progress& progress, WrittenOutputs& outputs, CheckTally& tally) {
  progress.step(scene.name + ": rasterizer, reference, compare");
  const long long started = nowNanoseconds();
  const bool wantPictures = !args.out.empty() || !args.report.empty();
  CheckResult r = checkScene(scene, args.settings, args.thresholds, wantPictures);
  const std::size_t occurrence = tally.occurrences[scene.name]++;
  if (!args.baseline.file.empty()) {
    holdSceneToBaseline(r.report, scene.name, occurrence, r.triangles, baseline, args.baseline);
  }
  const double seconds = millisecondsSince(started) * 1e-3;
  printSceneLine(scene, r, nameWidth, args.verbose);
  tally.warned += !r.report.warnings.empty();
  const std::string stem = fileStem(scene.name, tally.stems);
  const ScenePictures pictures = wantPictures ? ScenePictures{displayImage(r.raster), displayImage(r.reference),
                                                             heatmapImage(r.heatmap)}
                                             : ScenePictures{};
  if (!args.out.empty()) {
    progress.step(scene.name + ": writing EXR and PNG files");
    writeExrs(args.out, stem, r, args.compression, outputs);
    writePngs(args.out, stem, pictures, outputs);
  }
  if (!args.report.empty()) {
    progress.step(scene.name + ": writing report images");
    writePngs(args.report, stem, pictures, outputs);
  }
  tally.allPass = tally.allPass && r.report.pass;
  tally.reportScenes.push_back({scene.name, stem, r.triangles, r.rasterMs, r.referenceMs, r.report, auditLine(r.audit)});
  tally.rows.push_back(checkJsonRow(scene, r, args.settings));
  tally.junitCases.push_back({scene.name, seconds, r.report.reasons,
                              std::to_string(r.triangles) + " triangles, " + gateFigures(r.report) + "; raster " +
                                  formatNumber(r.rasterMs) + " ms, reference " + formatNumber(r.referenceMs) + " ms",
                              r.report.warnings});
}

// The summary after the table, the notes on limits that did nothing, and the files that cover
// every scene: the HTML report, --json and --junit.
void finishCheck(const CheckArgs& args, const CheckTally& tally, const BenchResults& bench, WrittenOutputs& outputs) {
  // The two times are for orientation; say so, so that nobody reads them as the speed-up.
  std::printf("(raster ms, ref ms: one cold render each, the reference's with its BVH build; "
              "rastercheck bench measures speed)\n");
  std::printf("%zu scene(s): %s%s\n", tally.reportScenes.size(), tally.allPass ? "all pass" : "GATE FAILED",
              tally.warned == 0 ? "" : ("; " + std::to_string(tally.warned) + " with warnings").c_str());
  std::fflush(stdout);
  std::vector<const CompareReport*> reports;
  for (const ReportScene& s : tally.reportScenes) reports.push_back(&s.report);
  noteUnappliedLimits(args.givenLimits, reports);
  noteIdleFailOnWarnings(args.thresholds, args.baseline);
  if (!args.report.empty()) {
    outputs.write((fs::path(args.report) / "index.html").string(), [&](const std::string&) {
      writeHtmlReport(args.report, tally.reportScenes, settingsLine(args.settings), bench);
    });
  }
  if (!args.json.empty()) {
    const nlohmann::json j = {{"format_version", kReportFormatVersion}, {"verdict", tally.allPass ? "pass" : "fail"},
                              {"settings", settingsLine(args.settings)}, {"scenes", tally.rows}};
    outputs.writeText(args.json, jsonDocument(j));
  }
  if (!args.junit.empty()) {
    outputs.writeText(args.junit, junitXml("rastercheck check", {{"settings", settingsLine(args.settings)}}, tally.junitCases));
  }
}

int runCheck(CheckArgs& args) {
  finishRenderSettings(args.settings);
  setExrThreads(args.settings.threads);
  args.scenes = args.scenes.empty() ? defaultSceneNames() : expandSceneGroups(args.scenes);
  std::vector<std::string> inputs = args.scenes;  // scenes given as files, and the bench results
  if (!args.benchJson.empty()) inputs.push_back(args.benchJson);
  if (!args.baseline.file.empty()) inputs.push_back(args.baseline.file);
  if (!args.benchJson.empty() && args.report.empty()) throw usageError("--bench-json goes with --report");
  takeStandardOutputByName(args.json);
  takeStandardOutputByName(args.junit);
  const std::vector<OutputOption> outputList = {{"--json", args.json, "", true}, {"--junit", args.junit, ".xml", true}};
  checkOutputs(outputList, inputs);
  const BenchResults bench = args.benchJson.empty() ? BenchResults{} : readBenchJson(args.benchJson);
  const Baseline baseline = args.baseline.file.empty() ? Baseline{} : readBaseline(args.baseline.file, true);
  const int outputsPerScene = int(!args.out.empty()) + int(!args.report.empty());
  Progress progress(int(args.scenes.size()) * (2 + outputsPerScene), args.quiet);
  const std::vector<Scene> scenes = loadCheckScenes(args, progress);
  // The folders are made before any scene is rendered, so one that cannot be fails first.
  WrittenOutputs outputs;
  if (!args.out.empty()) outputs.makeFolder(args.out);
  if (!args.report.empty()) outputs.makeFolder(args.report);
  checkOutputFolders(outputList);
  routeTextAwayFromStandardOutput(outputList);

  int nameWidth = 22;  // wider for a long path, so that the columns stay aligned
  for (const Scene& scene : scenes) nameWidth = std::max(nameWidth, int(scene.name.size()));
  std::printf("%-*s %9s %11s %-7s %9s %9s %9s %9s %9s %9s\n", nameWidth, "scene", "triangles", "size", "verdict", "bary max",
              "bary p999", "depth max", "disagree", "raster ms", "ref ms");
  CheckTally tally;
  for (const Scene& scene : scenes) checkOneScene(scene, args, baseline, nameWidth, progress, outputs, tally);
  finishCheck(args, tally, bench, outputs);
  outputs.keep();
  return tally.allPass ? 0 : 1;
}

}  // namespace

void registerCheck(CLI::App& root, Action& action) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* command = root.add_subcommand(
      "check", "render scenes with both paths, compare them and gate (the CI accuracy gate)");
  command->add_option("scenes", args->scenes,
                      "scenes: built-in NAME[:key=value,...], .obj, .gltf/.glb or .json scene file; default: the built-in default set");
  command->add_option("--out", args->out, "write raster, reference and heatmap EXRs and PNGs to this folder");
  command->add_option("--report", args->report, "write a self-contained HTML report (index.html and images) to this folder");
  command->add_option("--json", args->json, "write a JSON report of every scene here ('-': standard output, and the table to stderr)");
  command->add_option("--junit", args->junit,
                      "write the verdicts as JUnit XML for CI test reports, a test case per scene ('-': standard output)");
  command->add_option("--bench-json", args->benchJson, "with --report: show these bench results (rastercheck bench --json) as a chart");
  command->add_flag("-v,--verbose", args->verbose, "print the full comparison table per scene");
  command->add_flag("-q,--quiet", args->quiet, "no progress on stderr");
  addRenderOptions(command, args->settings);
  addThresholdOptions(command, args->thresholds);
  addBaselineOptions(command, args->baseline, "rastercheck check --json");
  addExrCompressionOption(command, args->compression);
  command->callback([args, command, &action] {
    args->givenLimits = givenLimits(*command);
    action = [args] { return runCheck(*args); };
  });
}

}  // namespace rc::app
