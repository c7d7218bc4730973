// bench: the settings it sweeps, the rounds in which it times them beside the reference, and
// the ratios it counts from them.
#include "app/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <tuple>
#include <utility>
#include <unistd.h>

#include "compare/compare.h"
#include "compare/report.h"
#include "core/channels.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "core/parallel.h"
#include "rasterizer/rasterizer.h"
#include "raytracer_ref/reference.h"

namespace rc::app {
namespace {

// EXR writing takes about a second a frame (ZIP): it is timed at most this many times.
constexpr int kExrRuns = 3;

// Where bench writes the EXR it times: the system's temporary folder, one name per process,
// removed however the timing ends.
struct TemporaryFile {
  std::string path;
  TemporaryFile() {
    std::error_code error;
    const std::filesystem::path folder = std::filesystem::temp_directory_path(error);
    if (error) throw ioError("the temporary folder", "bench cannot time EXR writing: " + error.message());
    path = (folder / ("rastercheck-bench-" + std::to_string(::getpid()) + ".exr")).string();
  }
  ~TemporaryFile() {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

// The least and the greatest of the rounds' own ratios, numerator[r] / denominator[r], each
// pair timed in the same round; 0 and 0 without a round.
std::pair<double, double> roundRatioBounds(const std::vector<double>& numerator, const std::vector<double>& denominator) {
  double least = 0, greatest = 0;
  for (std::size_t r = 0; r < std::min(numerator.size(), denominator.size()); ++r) {
    const double ratio = numerator[r] / denominator[r];
    least = r == 0 ? ratio : std::min(least, ratio);
    greatest = r == 0 ? ratio : std::max(greatest, ratio);
  }
  return {least, greatest};
}

}  // namespace

std::string benchSettingName(Interpolation mode, Precision precision, int subpixelBits) {
  return std::string(mode == Interpolation::kAffine ? "affine" : "perspective") +
         (precision == Precision::kDouble ? "-double-" : "-float-") +
         (subpixelBits == 0 ? std::string("nosnap") : std::to_string(subpixelBits) + "bit");
}

std::vector<BenchSetting> benchSettings(const RasterOptions& base) {
  const int threads = resolveThreadCount(base.threads);
  const auto make = [&](Interpolation mode, Precision precision, int bits, int t, const char* suffix, bool isDefault) {
    RasterOptions o = base;
    o.interpolation = mode;
    o.precision = precision;
    o.subpixelBits = bits;
    o.threads = t;
    return BenchSetting{benchSettingName(mode, precision, bits) + suffix, o, isDefault};
  };
  constexpr Interpolation kPersp = Interpolation::kPerspective;
  constexpr Precision kFloat = Precision::kFloat;
  std::vector<BenchSetting> settings = {make(kPersp, kFloat, 8, threads, "", true),
                                        make(Interpolation::kAffine, kFloat, 8, threads, "", false),
                                        make(kPersp, Precision::kDouble, 8, threads, "", false),
                                        make(kPersp, kFloat, 4, threads, "", false),
                                        make(kPersp, kFloat, 16, threads, "", false),
                                        make(kPersp, kFloat, 0, threads, "", false)};
  // A variant that the command line has made the base already (--threads 1, --raster-isa sse2,
  // --no-diagnostics, --cull none) would only time the default again, and is left out.
  if (threads > 1) settings.push_back(make(kPersp, kFloat, 8, 1, "-1thread", false));
  // What the SIMD width and the four diagnostic channels cost: the same bits (respectively
  // the same channels less four), so the same error.
  BenchSetting sse2 = make(kPersp, kFloat, 8, threads, "-sse2", false);
  sse2.raster.isa = KernelIsa::kSse2;
  if (resolveKernelIsa(base.isa) != KernelIsa::kSse2) settings.push_back(sse2);
  if (resolveKernelIsa(base.isa) == KernelIsa::kAvx512) {  // what the 512-bit registers buy
    BenchSetting avx2 = make(kPersp, kFloat, 8, threads, "-avx2", false);
    avx2.raster.isa = KernelIsa::kAvx2;
    settings.push_back(avx2);
  }
  BenchSetting lean = make(kPersp, kFloat, 8, threads, "-nodiag", false);
  lean.raster.diagnostics = false;
  if (base.diagnostics) settings.push_back(lean);
  // What culling back faces saves where the scene allows it (Culling::kAuto); elsewhere this row
  // draws the same triangles as the default.
  BenchSetting all = make(kPersp, kFloat, 8, threads, "-nocull", false);
  all.raster.culling = Culling::kNone;
  if (base.culling != Culling::kNone) settings.push_back(all);
  // The combination the command line names (--mode, --precision, --subpixel-bits), where the
  // sweep above does not have it: bench times it too rather than ignore it.
  const std::string asked = benchSettingName(base.interpolation, base.precision, base.subpixelBits);
  if (std::none_of(settings.begin(), settings.end(), [&](const BenchSetting& s) { return s.name == asked; })) {
    settings.push_back(make(base.interpolation, base.precision, base.subpixelBits, threads, "", false));
  }
  return settings;
}

std::vector<BenchSetting> pickSettings(const std::vector<BenchSetting>& sweep, const std::vector<std::string>& names) {
  if (names.empty()) return sweep;
  const auto named = [&](const BenchSetting& s) {
    return std::find(names.begin(), names.end(), s.name) != names.end() ||
           (s.isDefault && std::find(names.begin(), names.end(), "default") != names.end());
  };
  for (const std::string& name : names) {
    if (name == "default" ||
        std::any_of(sweep.begin(), sweep.end(), [&](const BenchSetting& s) { return s.name == name; })) {
      continue;
    }
    std::string known = "default";
    for (const BenchSetting& s : sweep) known += ", " + s.name;
    throw usageError("--settings: no setting is named '" + name + "'; with these options bench has " + known);
  }
  std::vector<BenchSetting> picked;
  std::copy_if(sweep.begin(), sweep.end(), std::back_inserter(picked), named);
  return picked;
}

std::string timingPhrase(int runs) { return runs == 1 ? "one run" : "medians of " + std::to_string(runs) + " runs"; }

BestReference bestReference(const std::vector<BenchRow::ReferenceBuild>& builds) {
  BestReference best;
  for (std::size_t i = 1; i < builds.size(); ++i) {
    if (builds[i].traceMs < builds[best.fasterTrace].traceMs) best.fasterTrace = i;
    const BenchRow::ReferenceBuild& b = builds[best.smallerSum];
    if (builds[i].buildMs + builds[i].traceMs < b.buildMs + b.traceMs) best.smallerSum = i;
  }
  return best;
}

void countAgainstReference(BenchRow& row, const std::vector<ReferenceRuns>& references) {
  row.referenceBuilds.clear();
  for (const ReferenceRuns& r : references) row.referenceBuilds.push_back({r.build, median(r.buildRuns), median(r.traceRuns)});
  const BestReference best = bestReference(row.referenceBuilds);
  const BenchRow::ReferenceBuild& fasterTrace = row.referenceBuilds[best.fasterTrace];
  const BenchRow::ReferenceBuild& smallerSum = row.referenceBuilds[best.smallerSum];
  row.referenceBuild = fasterTrace.build;
  row.referenceBuildMs = fasterTrace.buildMs;
  row.referenceTraceMs = fasterTrace.traceMs;
  row.speedup = row.referenceTraceMs / row.rasterMs;
  row.traceRuns = references[best.fasterTrace].traceRuns;
  // Each round's trace over its own frame.
  std::tie(row.speedupMin, row.speedupMax) = roundRatioBounds(row.traceRuns, row.rasterRuns);
  row.speedupWithBuild = (smallerSum.buildMs + smallerSum.traceMs) / row.rasterMs;
  row.speedupWithBuildQuality = smallerSum.build;
}

void countAgainstDefault(std::vector<BenchRow>& rows, std::size_t first) {
  const auto isDefault = [](const BenchRow& r) { return r.isDefault; };
  const auto found = std::find_if(rows.begin() + std::ptrdiff_t(first), rows.end(), isDefault);
  if (found == rows.end()) return;
  const BenchRow& def = *found;  // the loop writes only the ratios, none of which it reads
  for (std::size_t i = first; i < rows.size(); ++i) {
    BenchRow& row = rows[i];
    row.overDefault = row.rasterMs / def.rasterMs;
    // Each round's frame over the default's of the same round.
    std::tie(row.overDefaultMin, row.overDefaultMax) = roundRatioBounds(row.rasterRuns, def.rasterRuns);
  }
}

namespace {

// The reference in one build quality: its BVH built `runs` times, each build timed, then one
// kept, with a framebuffer, for the rounds' traces (each timed into `trace`).
struct BuiltReference {
  ReferenceOptions options;
  std::vector<double> build, trace;
  std::unique_ptr<ReferenceTracer> tracer;
  Framebuffer frame;
};

// The reference in each build quality measured, its builds timed one after another: the one
// asked for and, unless it is low, the low-quality build beside it (built faster; traced faster
// or slower by the scene). Each has traced one frame, which faults its memory in.
std::vector<BuiltReference> buildReferences(const Scene& scene, const ReferenceOptions& asked, bool alsoLowBuild, int runs) {
  std::vector<BuiltReference> references(alsoLowBuild && asked.build != EmbreeBuild::kLow ? 2 : 1);
  references[0].options = asked;
  if (references.size() == 2) {
    references[1].options = asked;
    references[1].options.build = EmbreeBuild::kLow;
  }
  for (BuiltReference& b : references) {
    for (int r = 0; r < runs; ++r) {
      const long long t0 = nowNanoseconds();
      const ReferenceTracer built(scene, b.options);
      b.build.push_back(millisecondsSince(t0));
    }
    b.tracer = std::make_unique<ReferenceTracer>(scene, b.options);
    b.tracer->trace(b.frame);
  }
  return references;
}

// A setting's rasterizer, kept for the whole scene, the framebuffer it draws into, and its
// timed frames with their stages, round by round.
struct LiveSetting {
  const BenchSetting* setting;
  std::unique_ptr<Rasterizer> rasterizer;
  Framebuffer* raster;
  std::vector<double> times, transform, setup, bin, tiles;
};

// Every round traces each reference twice (the second trace timed) and gives every setting one
// untimed frame (its caches warm again after the others) and one timed frame, the settings
// taking their turns from a different one each round (round r starts with setting r).
void runRounds(const Scene& scene, std::vector<BuiltReference>& references, std::vector<LiveSetting>& live, int runs,
               const std::function<void(const std::string&)>& step) {
  for (int r = 0; r < runs; ++r) {
    step(scene.name + ": round " + std::to_string(r + 1) + " of " + std::to_string(runs));
    for (BuiltReference& b : references) {
      b.tracer->trace(b.frame);
      const long long start = nowNanoseconds();
      b.tracer->trace(b.frame);
      b.trace.push_back(millisecondsSince(start));
    }
    for (std::size_t k = 0; k < live.size(); ++k) {
      LiveSetting& l = live[(k + std::size_t(r)) % live.size()];
      l.rasterizer->render(scene, *l.raster);
      const long long t0 = nowNanoseconds();
      l.rasterizer->render(scene, *l.raster);
      l.times.push_back(millisecondsSince(t0));
      const StageTimes& stages = l.rasterizer->stageTimes();
      l.transform.push_back(stages.transformMs);
      l.setup.push_back(stages.setupMs);
      l.bin.push_back(stages.binMs);
      l.tiles.push_back(stages.tilesMs);
    }
  }
}

// A setting's row after the rounds: its frame drawn again (the other settings drew over it),
// the default's EXR writes timed, its errors against `reference`, and last its memory floor,
// which overwrites the frame's planes.
BenchRow measuredRow(const Scene& scene, const RenderSettings& settings, LiveSetting& l,
                     const std::vector<BuiltReference>& references, int runs) {
  const BenchSetting& setting = *l.setting;
  Framebuffer& raster = *l.raster;
  l.rasterizer->render(scene, raster);
  std::vector<double> exr;
  if (setting.isDefault) {  // after every timed frame, so they run as they would without it
    const TemporaryFile file;
    for (int r = 0; r < std::min(runs, kExrRuns); ++r) {
      const long long t0 = nowNanoseconds();
      writeExr(raster, file.path);
      exr.push_back(millisecondsSince(t0));
    }
  }
  const Framebuffer& reference = references[0].frame;  // the errors are measured against it
  const CompareReport report = compareImages(raster, setting.name, reference, "reference", Thresholds{}, nullptr,
                                             setting.raster.threads);
  std::vector<double> floor;
  for (int r = 0; r < runs; ++r) floor.push_back(writeOutPass(raster, std::uint32_t(r), setting.raster));
  BenchRow row;
  row.scene = scene.name;
  row.setting = setting.name;
  row.isDefault = setting.isDefault;
  row.triangles = scene.mesh.triangleCount();
  row.width = scene.camera.width();
  row.height = scene.camera.height();
  row.threads = resolveThreadCount(setting.raster.threads);
  row.runs = runs;
  row.rasterMs = median(l.times);
  row.rasterMsMin = *std::min_element(l.times.begin(), l.times.end());
  row.rasterMsMax = *std::max_element(l.times.begin(), l.times.end());
  row.transformMs = median(l.transform);
  row.setupMs = median(l.setup);
  row.binMs = median(l.bin);
  row.tilesMs = median(l.tiles);
  row.transformRuns = l.transform;
  row.setupRuns = l.setup;
  row.binRuns = l.bin;
  row.tilesRuns = l.tiles;
  row.exrWriteMs = exr.empty() ? -1.0 : median(exr);
  row.storeFloorMs = median(floor);
  row.rasterIsa = kernelIsaName(resolveKernelIsa(setting.raster.isa));
  row.diagnostics = setting.raster.diagnostics;
  row.cull = setting.raster.culling == Culling::kNone ? "none" : "auto";
  row.referenceIsa = settings.reference.isa;
  row.rasterRuns = l.times;
  std::vector<ReferenceRuns> measured;
  for (const BuiltReference& b : references) measured.push_back({embreeBuildName(b.options.build), b.build, b.trace});
  countAgainstReference(row, measured);
  row.trianglesPerSecond = double(row.triangles) / (row.rasterMs * 1e-3);
  row.pixelsPerSecond = double(row.width) * row.height / (row.rasterMs * 1e-3);
  row.baryMax = report.families[0].stats.max;
  row.baryP999 = report.families[0].stats.p999;
  row.disagreementFraction = report.disagreementFraction;
  row.coverageFraction = report.coverageFraction;
  return row;
}

// A frame in which the reference covers no pixel gives no error to set a setting's speed
// against: every error would read 0, as if each setting were exact.
void refuseEmptyReference(const Scene& scene, const Framebuffer& reference) {
  const Channel* ids = reference.find(channels::kTriangleId);
  if (ids && std::any_of(ids->uints.begin(), ids->uints.end(), [](std::uint32_t id) { return id != channels::kNoTriangle; })) return;
  throw badInput(scene.name, "the reference covers no pixel of the frame, so no setting's error can be measured; aim "
                             "the camera at the mesh (--eye, --target)");
}

}  // namespace

// Steady-state frames: each renderer keeps its framebuffer (and the rasterizer its working
// memory) from one run to the next, as a renderer drawing frame after frame does; one untimed
// frame first faults the memory in. Neither timing includes the RGB preview.
//
// The reference's BVH builds are timed first, one after another. Then everything else is timed
// in rounds (runRounds). A slow spell of the machine (seconds long on a shared one) then falls
// on the reference's trace and the settings alike instead of on all the runs of whichever it
// met, so the medians and the ratios between them stay put. (Built in the rounds too, the BVH
// took 183 to 220 ms at 1M triangles instead of 153 to 161, and the ratios counting the build
// would have gained from it.) The settings take their turns from a different one each round:
// in a fixed order, the first setting of every round, the default, had the widest spread of all
// at 1M triangles (docs/report-format.md).
// The settings that write the same channels draw into one framebuffer in turn (every frame
// writes every pixel of every plane): two framebuffers per scene, not one per setting (a bench
// of the default scenes peaked at 2.24 GB with one each, 1.0 GB with two).
std::vector<BenchRow> runBench(const std::vector<Scene>& scenes, const RenderSettings& settings,
                               const std::vector<BenchSetting>& sweep, int runs, bool alsoLowBuild,
                               const std::function<void(const std::string&)>& step) {
  std::vector<BenchRow> rows;
  for (const Scene& scene : scenes) {
    const LoadMeter meter;
    const std::size_t firstRow = rows.size();
    step(scene.name + ": reference builds");
    std::vector<BuiltReference> references = buildReferences(scene, settings.reference, alsoLowBuild, runs);
    refuseEmptyReference(scene, references[0].frame);
    std::vector<LiveSetting> live(sweep.size());
    Framebuffer withDiagnostics, withoutDiagnostics;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
      live[i].setting = &sweep[i];
      live[i].rasterizer = std::make_unique<Rasterizer>(sweep[i].raster);
      live[i].raster = sweep[i].raster.diagnostics ? &withDiagnostics : &withoutDiagnostics;
      live[i].rasterizer->render(scene, *live[i].raster);  // faults the memory in
    }
    runRounds(scene, references, live, runs, step);
    step(scene.name + ": errors, EXR writing and memory floors");
    for (LiveSetting& l : live) rows.push_back(measuredRow(scene, settings, l, references, runs));
    countAgainstDefault(rows, firstRow);
    const std::optional<BenchLoad> load = meter.load();
    for (std::size_t i = firstRow; i < rows.size(); ++i) rows[i].load = load;
  }
  return rows;
}

}  // namespace rc::app
