// `rastercheck bench [SCENE...]`: speed against error for every rasterizer setting.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "app/bench.h"
#include "app/bench_files.h"
#include "app/bench_chart.h"
#include "app/commands.h"
#include "app/options.h"
#include "app/outputs.h"
#include "scenes/registry.h"
#include "app/progress.h"
#include "compare/report.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/parallel.h"
#include "raytracer_ref/reference.h"

namespace rc::app {
namespace {

struct BenchArgs {
  std::vector<std::string> scenes;
  std::string json, csv, chart;
  std::vector<std::string> only;  // --settings
  int runs = 5;
  bool quiet = false;
  bool pinnedIsa = false;    // --embree-isa given
  bool pinnedBuild = false;  // --embree-build given
  RenderSettings settings;
};

// bench's table: a line per scene and setting, then the legend.
void printBenchTable(const std::vector<BenchRow>& rows) {
  int nameWidth = 20;  // wider for a long path, so that the columns stay aligned
  for (const BenchRow& r : rows) nameWidth = std::max(nameWidth, int(r.scene.size()));
  std::printf("%-*s %-31s %9s %15s %21s %8s %8s %8s %9s %9s %8s %13s %8s %9s %9s %9s %9s %8s\n", nameWidth, "scene",
              "setting", "raster ms", "(min..max)", "x default (per round)", "Mtri/s", "Mpix/s", "floor ms", "ref build",
              "ref trace", "speedup", "(per round)", "w/build", "bary max", "bary p999", "disagree", "one side", "exr ms");
  for (const BenchRow& r : rows) {
    char spread[32], exr[16] = "-";
    // One decimal, as the median has two; under a millisecond three, as the median has.
    const char* format = r.rasterMsMin < 1 ? "(%.3f..%.3f)" : "(%.1f..%.1f)";
    std::snprintf(spread, sizeof spread, format, r.rasterMsMin, r.rasterMsMax);
    if (r.exrWriteMs >= 0) std::snprintf(exr, sizeof exr, "%.1f", r.exrWriteMs);
    char rounds[48];
    std::snprintf(rounds, sizeof rounds, "(%.2f..%.2f)", r.speedupMin, r.speedupMax);
    char overDefault[64] = "-";  // the default's own row, and a scene without one
    if (r.overDefault > 0 && !r.isDefault) {
      std::snprintf(overDefault, sizeof overDefault, "%.2f (%.2f..%.2f)", r.overDefault, r.overDefaultMin, r.overDefaultMax);
    }
    char median[32];
    std::snprintf(median, sizeof median, r.rasterMs < 1 ? "%.3f" : "%.2f", r.rasterMs);
    std::printf("%-*s %-31s %9s %15s %21s %8s %8.0f %8.2f %9.2f %9.2f %8.2f %13s %8.2f %9s %9s %9s %9s %8s\n", nameWidth,
                r.scene.c_str(), (r.setting + (r.isDefault ? " *" : "")).c_str(), median, spread, overDefault,
                formatNumber(r.trianglesPerSecond * 1e-6).c_str(), r.pixelsPerSecond * 1e-6, r.storeFloorMs, r.referenceBuildMs,
                r.referenceTraceMs, r.speedup, rounds, r.speedupWithBuild, formatNumber(r.baryMax).c_str(),
                formatNumber(r.baryP999).c_str(), formatNumber(r.disagreementFraction).c_str(),
                formatNumber(r.coverageFraction).c_str(), exr);
  }
  std::printf("* default setting; x default = raster / the default's raster (medians), and per round the least and\n"
              "  greatest of each round's frame / the default's frame (--json: raster_over_default);\n"
              "  Mtri/s, Mpix/s = millions of triangles, of pixels rendered a second (at the median);\n"
              "  speedup = reference trace / raster (medians), with the build quality that traced faster (ref build,\n"
              "  ref trace: its times; --json: reference_build); per round = the least and greatest of each round's\n"
              "  trace / frame, timed within a second of each other; w/build = (build + trace) / raster, with the\n"
              "  build quality whose sum is the smaller (--json: speedup_with_build_quality);\n"
              "  floor ms = writing the setting's output planes alone, as its kernels write them (memory's floor);\n"
              "  disagree = pixels where the triangle differs, one side = pixels one path covers alone, each over\n"
              "  the pixels either covers;\n"
              "  exr ms = writing the default setting's output (ZIP EXR, as render -o does; median of up to 3);\n"
              "  --json adds stage times\n");
}

int runBenchCommand(BenchArgs& args) {
  finishRenderSettings(args.settings);
  if (args.settings.raster.fillRule != FillRule::kTopLeft) {
    throw usageError(std::string("bench times the top-left fill rule; --fill-rule ") +
                     fillRuleName(args.settings.raster.fillRule) + " is wrong on purpose, for check to fail");
  }
  const std::vector<BenchSetting> sweep = pickSettings(benchSettings(args.settings.raster), args.only);
  // Speed-ups count against Embree's fastest mode here unless an ISA is pinned: the default
  // pin (for outputs that do not change with the CPU) is not always the fastest.
  if (!args.pinnedIsa) args.settings.reference.isa = fastestEmbreeIsa();
  // Likewise the build: medium (Embree's default) and low are both timed, and each speed-up
  // counts against the better for it, unless a quality is pinned.
  if (!args.pinnedBuild) args.settings.reference.build = EmbreeBuild::kMedium;
  setExrThreads(args.settings.threads);
  args.scenes = args.scenes.empty() ? std::vector<std::string>{"blob:tris=1000", "blob:tris=100000", "blob:tris=1000000"}
                                    : expandSceneGroups(args.scenes);
  takeStandardOutputByName(args.json);
  takeStandardOutputByName(args.csv);
  // Scenes given as files are inputs.
  const std::vector<OutputOption> outputList = {
      {"--json", args.json, "", true}, {"--csv", args.csv, "", true}, {"--chart", args.chart}};
  checkOutputs(outputList, args.scenes);
  if (!args.chart.empty()) checkChartCanBeMade(args.chart);  // a wrong name or no font fails now
  checkOutputFolders(outputList);
  routeTextAwayFromStandardOutput(outputList);
  std::vector<Scene> scenes;
  for (const std::string& spec : args.scenes) scenes.push_back(loadScene(spec, args.settings));
  // Per scene: the reference's builds, each round of traces and frames, then the errors.
  Progress progress(int(scenes.size()) * (args.runs + 2), args.quiet);
  const BenchMachine machine = benchMachine();
  const LoadMeter meter;
  const std::vector<BenchRow> rows =
      runBench(scenes, args.settings, sweep, args.runs, !args.pinnedBuild, [&](const std::string& what) { progress.step(what); });
  const std::optional<BenchLoad> load = meter.load();

  std::printf("%s, the reference's trace and the settings timed in turn; "
              "raster and trace times exclude EXR writing; %d threads unless the setting says 1;\n"
              "rasterizer kernels: %s unless the setting names another%s%s; reference: Embree %s%s, %s\n",
              timingPhrase(args.runs).c_str(), resolveThreadCount(args.settings.threads),
              kernelIsaName(resolveKernelIsa(args.settings.raster.isa)),
              args.settings.raster.diagnostics ? "" : "; every setting without the diagnostic channels",
              args.settings.raster.culling == Culling::kNone ? "; every setting drawing back faces (--cull none)" : "",
              args.settings.reference.isa.c_str(),
              args.pinnedIsa ? "" : " (the fastest this CPU has; --embree-isa pins another)",
              args.pinnedBuild ? (std::string(embreeBuildName(args.settings.reference.build)) + " build").c_str()
                               : "its BVH built in medium and in low quality, each timed (--embree-build pins one)");
  std::printf("machine: %s\n", describe(machine).c_str());
  const auto printLoad = [](const std::string& during, const BenchLoad& l) {
    const std::string note = busyNote(l);
    std::printf("%s: %s%s\n", during.c_str(), describe(l).c_str(), note.empty() ? "" : (": " + note).c_str());
  };
  if (load) printLoad("load during the run", *load);
  // And each scene that other work made busy, where there are several: a burst in one scene's
  // runs is spread thin over the whole run.
  for (std::size_t i = 0; i < rows.size() && scenes.size() > 1; ++i) {
    const bool first = i == 0 || rows[i].scene != rows[i - 1].scene;
    if (first && rows[i].load && !busyNote(*rows[i].load).empty()) printLoad("  during " + rows[i].scene, *rows[i].load);
  }
  printBenchTable(rows);
  // Everything is made before anything is written, so that a failure (the chart's font, say)
  // leaves no file of a partial set behind.
  const BenchChart chart = args.chart.empty() ? BenchChart{} : makeBenchChart(rows, &machine, load ? &*load : nullptr, args.chart);
  WrittenOutputs outputs;
  outputs.writeText(args.json, benchJson(rows, machine, load));
  outputs.writeText(args.csv, benchCsv(rows));
  outputs.write(args.chart, [&](const std::string& path) { writeBenchChart(chart, path); });
  outputs.keep();
  return 0;
}

}  // namespace

void registerBench(CLI::App& root, Action& action) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* command = root.add_subcommand(
      "bench", "speed against error of every rasterizer setting, medians measured in one process");
  command->add_option("scenes", args->scenes, "scenes as for check; default: blob at about 1k, 100k and 1M triangles");
  command->add_option("--runs", args->runs, "timed runs per measurement (the median is reported)")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  command->add_option("--json", args->json, "write the rows as JSON (docs/report-format.md; '-': standard output, and the table to stderr)");
  command->add_option("--csv", args->csv, "write the rows as CSV ('-': standard output, and the table to stderr)");
  command->add_option("--chart", args->chart, "write frame time against error as a chart: FILE.svg or FILE.png");
  addListOption(
      command, "--settings", [args](std::vector<std::string> names) { args->only = std::move(names); },
      "time only these settings, by their names in the table (default: the default setting's), in the table's order; "
      "default: every one")
      ->type_name("NAME[,NAME]");
  command->add_flag("-q,--quiet", args->quiet, "no progress on stderr");
  addRenderOptions(command, args->settings);
  command->get_option("--embree-isa")
      ->description("Embree instruction set of the reference; default: the fastest this CPU has (check and render "
                    "pin avx2)")
      ->default_str("fastest");
  command->get_option("--embree-build")
      ->description("quality of the reference's BVH build; default: medium for the trace and low timed beside it for "
                    "w/build (check and render build low)")
      ->default_str("both");
  command->callback([args, command, &action] {
    args->pinnedIsa = command->get_option("--embree-isa")->count() > 0;
    args->pinnedBuild = command->get_option("--embree-build")->count() > 0;
    action = [args] { return runBenchCommand(*args); };
  });
}

}  // namespace rc::app
