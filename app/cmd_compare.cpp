// `rastercheck compare TEST.exr REF.exr [--heatmap FILE.exr] [--json FILE] [thresholds]`
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/junit.h"
#include "app/options.h"
#include "app/outputs.h"
#include "compare/baseline.h"
#include "compare/heatmap_png.h"
#include "compare/report.h"
#include "core/atomic_file.h"
#include "core/clock.h"
#include "core/exr_io.h"
#include "core/png_io.h"

namespace rc::app {
namespace {

struct CompareArgs {
  std::string test, reference, heatmap, heatmapPng, json, junit;
  Thresholds thresholds;
  BaselineUse baseline;
  std::vector<std::string> givenLimits;  // the fixed limits given on the command line
  ExrCompression compression = ExrCompression::kZip;
  int threads = 0;
};

int runCompare(CompareArgs& args) {
  const long long started = nowNanoseconds();
  takeStandardOutputByName(args.json);
  takeStandardOutputByName(args.junit);
  const std::vector<OutputOption> outputList = {{"--heatmap", args.heatmap, ".exr"},
                                                {"--heatmap-png", args.heatmapPng, ".png"},
                                                {"--json", args.json, "", true},
                                                {"--junit", args.junit, ".xml", true}};
  const bool holdToBaseline = !args.baseline.file.empty();
  std::vector<std::string> inputs = {args.test, args.reference};
  if (holdToBaseline) inputs.push_back(args.baseline.file);
  checkOutputs(outputList, inputs);
  checkOutputFolders(outputList);
  routeTextAwayFromStandardOutput(outputList);
  setExrThreads(args.threads);
  const Baseline baseline = holdToBaseline ? readBaseline(args.baseline.file, false) : Baseline{};
  const Framebuffer test = readExr(args.test);
  const Framebuffer reference = readExr(args.reference);
  Framebuffer heatmap;
  CompareReport report = compareImages(test, args.test, reference, args.reference, args.thresholds,
                                       args.heatmap.empty() && args.heatmapPng.empty() ? nullptr : &heatmap,
                                       args.threads);
  if (holdToBaseline) holdReportToBaseline(report, baseline.at("").front(), args.baseline);
  std::printf("test      %s\nreference %s\n%s", args.test.c_str(), args.reference.c_str(),
              reportToTable(report).c_str());
  std::fflush(stdout);
  noteUnappliedLimits(args.givenLimits, {&report});
  noteIdleFailOnWarnings(args.thresholds, args.baseline);
  WrittenOutputs outputs;
  outputs.write(args.heatmap, [&](const std::string& path) { writeExr(heatmap, path, args.compression); });
  outputs.write(args.heatmapPng, [&](const std::string& path) { writePng(heatmapImage(heatmap), path); });
  outputs.writeText(args.json, jsonDocument(reportToJson(report)));
  if (!args.junit.empty()) {
    const JUnitCase only{args.test, millisecondsSince(started) * 1e-3, report.reasons, gateFigures(report),
                         report.warnings};
    outputs.writeText(args.junit, junitXml("rastercheck compare", {{"reference", args.reference}}, {only}));
  }
  outputs.keep();
  return report.pass ? 0 : 1;
}

}  // namespace

void registerCompare(CLI::App& root, Action& action) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* command = root.add_subcommand(
      "compare", "compare a test EXR against a reference EXR and gate on the result");
  command->add_option("test", args->test, "test image (e.g. the rasterizer's EXR)")->required();
  command->add_option("reference", args->reference, "reference image")->required();
  command->add_option("--heatmap", args->heatmap, "write an error heatmap EXR here");
  command->add_option("--heatmap-png", args->heatmapPng, "write the heatmap as a PNG with a legend here");
  command->add_option("--json", args->json, "write the JSON report here ('-': standard output, and the table to stderr)");
  command->add_option("--junit", args->junit,
                      "write the verdict as JUnit XML for CI test reports, one test case named by the test image ('-': standard output)");
  addThresholdOptions(command, args->thresholds);
  addBaselineOptions(command, args->baseline, "rastercheck compare --json");
  addThreadsOption(command, args->threads,
                   "threads decoding and encoding the EXR files and measuring the channel families");
  addListOption(
      command, "--attributes", [args](std::vector<std::string> names) { args->thresholds.attributes = std::move(names); },
      "compare only these attributes (e.g. uv,normal), leaving out any other either image carries; default: every one, "
      "each required in both")
      ->type_name("NAME[,NAME]");
  addExrCompressionOption(command, args->compression);
  command->callback([args, command, &action] {
    args->givenLimits = givenLimits(*command);
    action = [args] { return runCompare(*args); };
  });
}

}  // namespace rc::app
