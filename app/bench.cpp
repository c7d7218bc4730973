// bench: measurements and their renderings.
#include "app/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/resource.h>
#include <unistd.h>

#include "compare/compare.h"
#include "compare/report.h"
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
  for (std::size_t r = 0; r < row.rasterRuns.size(); ++r) {  // each round's trace over its own frame
    const double ratio = row.traceRuns[r] / row.rasterRuns[r];
    row.speedupMin = r == 0 ? ratio : std::min(row.speedupMin, ratio);
    row.speedupMax = r == 0 ? ratio : std::max(row.speedupMax, ratio);
  }
  row.speedupWithBuild = (smallerSum.buildMs + smallerSum.traceMs) / row.rasterMs;
  row.speedupWithBuildQuality = smallerSum.build;
}

void countAgainstDefault(std::vector<BenchRow>& rows, std::size_t first) {
  const auto isDefault = [](const BenchRow& r) { return r.isDefault; };
  const auto found = std::find_if(rows.begin() + std::ptrdiff_t(first), rows.end(), isDefault);
  if (found == rows.end()) return;
  const BenchRow def = *found;
  for (std::size_t i = first; i < rows.size(); ++i) {
    BenchRow& row = rows[i];
    row.overDefault = row.rasterMs / def.rasterMs;
    for (std::size_t r = 0; r < row.rasterRuns.size(); ++r) {  // each round's frame over the default's
      const double ratio = row.rasterRuns[r] / def.rasterRuns[r];
      row.overDefaultMin = r == 0 ? ratio : std::min(row.overDefaultMin, ratio);
      row.overDefaultMax = r == 0 ? ratio : std::max(row.overDefaultMax, ratio);
    }
  }
}

std::vector<BenchRow> runBench(const std::vector<Scene>& scenes, const RenderSettings& settings,
                               const std::vector<BenchSetting>& sweep, int runs, bool alsoLowBuild,
                               const std::function<void(const std::string&)>& step) {
  std::vector<BenchRow> rows;
  for (const Scene& scene : scenes) {
    const LoadMeter meter;
    const std::size_t firstRow = rows.size();
    // Steady-state frames: each renderer keeps its framebuffer (and the rasterizer its working
    // memory) from one run to the next, as a renderer drawing frame after frame does; one
    // untimed frame first faults the memory in. Neither timing includes the RGB preview.
    //
    // The reference's BVH builds are timed first, one after another. Then everything else is
    // timed in rounds: each round traces the reference twice (the second trace timed) and gives
    // every setting one untimed frame (its caches warm again after the others) and one timed
    // frame. A slow spell of the machine (seconds long on a shared one) then falls on the
    // reference's trace and the settings alike instead of on all the runs of whichever it met,
    // so the medians and the ratios between them stay put. (Built in the rounds too, the BVH
    // took 183 to 220 ms at 1M triangles instead of 153 to 161, and the ratios counting the
    // build would have gained from it.)
    // The settings take their turns from a different one each round (round r starts with
    // setting r): in a fixed order, the first setting of every round, the default, had the
    // widest spread of all at 1M triangles (docs/report-format.md).
    // The settings that write the same channels draw into one framebuffer in turn (every
    // frame writes every pixel of every plane): two framebuffers per scene, not one per setting
    // (a bench of the default scenes peaked at 2.24 GB with one each, 1.0 GB with two).
    step(scene.name + ": reference builds");
    // The reference in each build quality measured: the one asked for and, unless it is low,
    // the low-quality build beside it (built faster; traced faster or slower by the scene).
    struct Built {
      ReferenceOptions options;
      std::vector<double> build, trace;
      std::unique_ptr<ReferenceTracer> tracer;
      Framebuffer frame;
    };
    std::vector<Built> references(alsoLowBuild && settings.reference.build != EmbreeBuild::kLow ? 2 : 1);
    references[0].options = settings.reference;
    if (references.size() == 2) {
      references[1].options = settings.reference;
      references[1].options.build = EmbreeBuild::kLow;
    }
    for (Built& b : references) {
      for (int r = 0; r < runs; ++r) {
        const long long t0 = nowNanoseconds();
        const ReferenceTracer built(scene, b.options);
        b.build.push_back(millisecondsSince(t0));
      }
      b.tracer = std::make_unique<ReferenceTracer>(scene, b.options);
      b.tracer->trace(b.frame);  // faults the memory in
    }
    const Framebuffer& reference = references[0].frame;  // the errors are measured against it
    struct Live {
      const BenchSetting* setting;
      std::unique_ptr<Rasterizer> rasterizer;
      Framebuffer* raster;
      std::vector<double> times, transform, setup, bin, tiles;
    };
    std::vector<Live> live(sweep.size());
    Framebuffer withDiagnostics, withoutDiagnostics;
    for (std::size_t i = 0; i < sweep.size(); ++i) {
      live[i].setting = &sweep[i];
      live[i].rasterizer = std::make_unique<Rasterizer>(sweep[i].raster);
      live[i].raster = sweep[i].raster.diagnostics ? &withDiagnostics : &withoutDiagnostics;
      live[i].rasterizer->render(scene, *live[i].raster);  // faults the memory in
    }
    for (int r = 0; r < runs; ++r) {
      step(scene.name + ": round " + std::to_string(r + 1) + " of " + std::to_string(runs));
      for (Built& b : references) {
        b.tracer->trace(b.frame);
        const long long start = nowNanoseconds();
        b.tracer->trace(b.frame);
        b.trace.push_back(millisecondsSince(start));
      }
      for (std::size_t k = 0; k < live.size(); ++k) {
        Live& l = live[(k + std::size_t(r)) % live.size()];
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
    step(scene.name + ": errors, EXR writing and memory floors");
    for (Live& l : live) {
      const BenchSetting& setting = *l.setting;
      Framebuffer& raster = *l.raster;
      l.rasterizer->render(scene, raster);  // its own frame again: the other settings drew over it
      const std::vector<double>& times = l.times;
      std::vector<double> exr;
      if (setting.isDefault) {  // after every timed frame, so they run as they would without it
        const TemporaryFile file;
        for (int r = 0; r < std::min(runs, kExrRuns); ++r) {
          const long long t0 = nowNanoseconds();
          writeExr(raster, file.path);
          exr.push_back(millisecondsSince(t0));
        }
      }
      const CompareReport report = compareImages(raster, setting.name, reference, "reference", Thresholds{}, nullptr,
                                                 setting.raster.threads);
      // Last, since it overwrites the frame's planes.
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
      row.rasterMs = median(times);
      row.rasterMsMin = *std::min_element(times.begin(), times.end());
      row.rasterMsMax = *std::max_element(times.begin(), times.end());
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
      row.rasterRuns = times;
      std::vector<ReferenceRuns> measured;
      for (const Built& b : references) measured.push_back({embreeBuildName(b.options.build), b.build, b.trace});
      countAgainstReference(row, measured);
      row.trianglesPerSecond = double(row.triangles) / (row.rasterMs * 1e-3);
      row.pixelsPerSecond = double(row.width) * row.height / (row.rasterMs * 1e-3);
      row.baryMax = report.families[0].stats.max;
      row.baryP999 = report.families[0].stats.p999;
      row.disagreementFraction = report.disagreementFraction;
      rows.push_back(row);
    }
    countAgainstDefault(rows, firstRow);
    const std::optional<BenchLoad> load = meter.load();
    for (std::size_t i = firstRow; i < rows.size(); ++i) rows[i].load = load;
  }
  return rows;
}

std::string cpuDescription(const std::string& cpuinfo, const std::vector<CpuCache>& caches) {
  // The fields of the first processor block, values trimmed.
  std::map<std::string, std::string> field;
  std::istringstream in(cpuinfo);
  for (std::string line; std::getline(in, line) && !line.empty();) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = line.substr(0, colon), rest = line.substr(colon + 1);
    const std::size_t keyEnd = key.find_last_not_of(" \t"), start = rest.find_first_not_of(" \t");
    if (keyEnd == std::string::npos) continue;
    field.emplace(key.substr(0, keyEnd + 1), start == std::string::npos ? "" : rest.substr(start));
  }
  const auto value = [&](const char* key) {
    const auto it = field.find(key);
    return it == field.end() ? std::string() : it->second;
  };
  std::string cpu = value("model name");
  if (cpu.empty()) cpu = "unknown";
  // The model name alone can be a family's (a virtual machine's "AMD EPYC"): the numbers tell
  // its generations apart.
  std::vector<std::string> details;
  if (!value("cpu family").empty() && !value("model").empty()) {
    std::string id = "family " + value("cpu family") + ", model " + value("model");
    if (!value("stepping").empty()) id += ", stepping " + value("stepping");
    details.push_back(id);
  }
  std::string sizes;
  for (const CpuCache& cache : caches) sizes += (sizes.empty() ? "" : ", ") + cache.name + " " + cache.size;
  if (!sizes.empty()) details.push_back(sizes);
  for (std::size_t i = 0; i < details.size(); ++i) cpu += (i == 0 ? " (" : "; ") + details[i];
  return details.empty() ? cpu : cpu + ")";
}

namespace {

// The data and unified caches of CPU 0 as sysfs lists them, by level: "L1d", "L2", "L3".
// A file's first line; empty where it cannot be read (a kernel file absent on this machine).
std::string firstLine(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string text;
  std::getline(in, text);
  return text;
}

std::vector<CpuCache> cpu0Caches() {
  std::vector<CpuCache> caches;
  for (int index = 0;; ++index) {
    const std::filesystem::path dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(index);
    const std::string level = firstLine(dir / "level"), type = firstLine(dir / "type"), size = firstLine(dir / "size");
    if (level.empty()) break;
    if (type == "Instruction" || size.empty()) continue;
    caches.push_back({"L" + level + (type == "Data" ? "d" : ""), size});
  }
  return caches;
}

}  // namespace

BenchMachine benchMachine() {
  BenchMachine m;
  std::ifstream cpuinfo("/proc/cpuinfo");
  m.cpu = cpuDescription(std::string(std::istreambuf_iterator<char>(cpuinfo), {}), cpu0Caches());
  m.logicalCpus = resolveThreadCount(0);
  m.widestKernelIsa = kernelIsaName(resolveKernelIsa(KernelIsa::kAuto));
  m.fastestEmbreeIsa = fastestEmbreeIsa();
#if defined(__clang__)
  m.compiler = "clang " __clang_version__;
#else
  m.compiler = "GCC " __VERSION__;
#endif
  m.embree = embreeVersion();
  m.rastercheck = RASTERCHECK_VERSION;
  return m;
}

std::string describeHardware(const BenchMachine& m) {
  return m.cpu + ", " + std::to_string(m.logicalCpus) + " logical CPU" + (m.logicalCpus == 1 ? "" : "s") +
         " (kernels up to " + m.widestKernelIsa + ", Embree " + m.fastestEmbreeIsa + ")";
}

std::string describeBuilds(const BenchMachine& m) {
  return m.compiler + ", Embree " + m.embree + ", rastercheck " + m.rastercheck;
}

std::string describe(const BenchMachine& m) { return describeHardware(m) + "; " + describeBuilds(m); }

std::optional<CpuTimes> parseProcStat(const std::string& text) {
  std::istringstream in(text);
  std::string label;
  if (!(in >> label) || label != "cpu") return std::nullopt;
  // user nice system idle iowait irq softirq steal (guest and guest_nice, after them, are
  // already counted in user and nice); older kernels stop after idle, or before steal.
  double field[8] = {};
  int count = 0;
  while (count < 8 && in >> field[count]) ++count;
  if (count < 4) return std::nullopt;
  CpuTimes t;
  t.busy = field[0] + field[1] + field[2] + field[5] + field[6];
  t.steal = field[7];
  for (const double f : field) t.total += f;
  return t;
}

BenchLoad loadBetween(const CpuTimes& before, const CpuTimes& after, double ownTicks) {
  const double total = after.total - before.total;
  if (!(total > 0)) return {};
  // The kernel counts in ticks and this process's own time more finely: clamped.
  const auto share = [&](double ticks) { return std::clamp(ticks / total, 0.0, 1.0); };
  return {share(after.busy - before.busy - ownTicks), share(after.steal - before.steal)};
}

namespace {

// This process's CPU time, all its threads, in /proc/stat's ticks.
double ownTicks() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return (seconds(usage.ru_utime) + seconds(usage.ru_stime)) * double(sysconf(_SC_CLK_TCK));
}

}  // namespace

LoadMeter::LoadMeter() : start_(parseProcStat(firstLine("/proc/stat"))), ownStart_(ownTicks()) {}

std::optional<BenchLoad> LoadMeter::load() const {
  const std::optional<CpuTimes> now = parseProcStat(firstLine("/proc/stat"));
  if (!start_ || !now) return std::nullopt;
  return loadBetween(*start_, *now, ownTicks() - ownStart_);
}

std::string percentOf(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f%%", 100 * share);
  return text;
}

std::string describe(const BenchLoad& load) {
  return "other processes used " + percentOf(load.others) + " of the CPUs' time, the hypervisor's other guests " +
         percentOf(load.steal) + " (steal)";
}

std::string busyNote(const BenchLoad& load) {
  constexpr double kBusy = 0.05;
  return load.others + load.steal > kBusy ? "a busy machine, so slower and noisier figures than an idle one gives" : "";
}

std::string benchJson(const std::vector<BenchRow>& rows, const BenchMachine& machine, const std::optional<BenchLoad>& load) {
  nlohmann::json list = nlohmann::json::array();
  for (const BenchRow& r : rows) {
    nlohmann::json row = {{"scene", r.scene}, {"triangles", r.triangles}, {"width", r.width}, {"height", r.height},
                          {"threads", r.threads}, {"setting", r.setting}, {"default", r.isDefault}, {"runs", r.runs},
                          {"raster_ms", r.rasterMs}, {"raster_ms_min", r.rasterMsMin}, {"raster_ms_max", r.rasterMsMax},
                          {"store_floor_ms", r.storeFloorMs},
                          {"stage_ms", {{"transform", r.transformMs}, {"setup", r.setupMs}, {"bin", r.binMs},
                                        {"tiles", r.tilesMs}}},
                          {"raster_isa", r.rasterIsa}, {"diagnostics", r.diagnostics}, {"cull", r.cull},
                          {"reference_isa", r.referenceIsa}, {"reference_build", r.referenceBuild},
                          {"reference_build_ms", r.referenceBuildMs}, {"reference_trace_ms", r.referenceTraceMs},
                          {"speedup", r.speedup}, {"speedup_min", r.speedupMin}, {"speedup_max", r.speedupMax},
                          {"speedup_with_build", r.speedupWithBuild},
                          {"speedup_with_build_quality", r.speedupWithBuildQuality},
                          {"triangles_per_second", r.trianglesPerSecond}, {"pixels_per_second", r.pixelsPerSecond},
                          {"bary_max_error", r.baryMax}, {"bary_p999_error", r.baryP999},
                          {"disagreement_fraction", r.disagreementFraction}};
    if (r.exrWriteMs >= 0) row["exr_write_ms"] = r.exrWriteMs;
    if (r.load) row["load"] = {{"other_processes", r.load->others}, {"steal", r.load->steal}};
    if (r.overDefault > 0) {
      row["raster_over_default"] = r.overDefault;
      row["raster_over_default_min"] = r.overDefaultMin;
      row["raster_over_default_max"] = r.overDefaultMax;
    }
    nlohmann::json builds = nlohmann::json::array();
    for (const BenchRow::ReferenceBuild& b : r.referenceBuilds) {
      builds.push_back({{"build", b.build}, {"build_ms", b.buildMs}, {"trace_ms", b.traceMs}});
    }
    row["reference_builds"] = builds;
    row["raster_ms_runs"] = r.rasterRuns;
    row["reference_trace_ms_runs"] = r.traceRuns;
    row["stage_ms_runs"] = {{"transform", r.transformRuns}, {"setup", r.setupRuns}, {"bin", r.binRuns},
                            {"tiles", r.tilesRuns}};
    list.push_back(row);
  }
  const nlohmann::json about = {{"cpu", machine.cpu},
                                {"logical_cpus", machine.logicalCpus},
                                {"widest_kernel_isa", machine.widestKernelIsa},
                                {"fastest_embree_isa", machine.fastestEmbreeIsa},
                                {"compiler", machine.compiler},
                                {"embree", machine.embree},
                                {"rastercheck", machine.rastercheck}};
  nlohmann::json doc = {{"format_version", 1}, {"machine", about}};
  if (load) doc["load"] = {{"other_processes", load->others}, {"steal", load->steal}};
  doc["rows"] = list;
  return jsonDocument(doc);
}

namespace {

// A load as benchJson writes it, at `at` (the file and the JSON pointer): each share a number
// from 0 to 1, as loadBetween gives it.
BenchLoad readLoad(const nlohmann::json& j, const std::string& at) {
  const auto share = [&](const char* field) {
    if (!j.is_object() || !j.contains(field) || !j[field].is_number()) {
      throw badInput(at + "/" + field, "missing, or not a number");
    }
    const double value = j[field].get<double>();
    if (!(value >= 0 && value <= 1)) {
      throw badInput(at + "/" + field, "is " + formatNumber(value) + "; must be a share from 0 to 1");
    }
    return value;
  };
  return {share("other_processes"), share("steal")};
}

}  // namespace

BenchResults readBenchJson(const std::string& path) {
  const nlohmann::json doc = readJsonFile(path, "bench results");
  if (!doc.is_object() || doc.value("format_version", 0) != 1 || !doc.contains("rows") || !doc["rows"].is_array()) {
    throw badInput(path, "not a rastercheck bench report (format_version 1 with rows)");
  }
  std::vector<BenchRow> rows;
  for (std::size_t i = 0; i < doc["rows"].size(); ++i) {
    const nlohmann::json& j = doc["rows"][i];
    const std::string at = path + ": /rows/" + std::to_string(i);
    try {
      BenchRow r;
      r.scene = j.at("scene").get<std::string>();
      r.setting = j.at("setting").get<std::string>();
      r.isDefault = j.at("default").get<bool>();
      r.triangles = j.at("triangles").get<std::size_t>();
      r.width = j.at("width").get<int>();
      r.height = j.at("height").get<int>();
      r.threads = j.at("threads").get<int>();
      r.runs = j.value("runs", 0);
      r.rasterMs = j.at("raster_ms").get<double>();
      r.storeFloorMs = j.value("store_floor_ms", 0.0);
      r.rasterIsa = j.value("raster_isa", std::string());
      r.diagnostics = j.value("diagnostics", true);
      r.cull = j.value("cull", std::string("auto"));
      r.referenceIsa = j.value("reference_isa", std::string());
      r.referenceBuild = j.value("reference_build", std::string());
      r.speedupWithBuildQuality = j.value("speedup_with_build_quality", std::string());
      r.referenceBuildMs = j.at("reference_build_ms").get<double>();
      r.referenceTraceMs = j.at("reference_trace_ms").get<double>();
      r.speedup = j.at("speedup").get<double>();
      r.speedupMin = j.value("speedup_min", 0.0);
      r.speedupMax = j.value("speedup_max", 0.0);
      r.overDefault = j.value("raster_over_default", 0.0);
      r.overDefaultMin = j.value("raster_over_default_min", 0.0);
      r.overDefaultMax = j.value("raster_over_default_max", 0.0);
      r.rasterRuns = j.value("raster_ms_runs", std::vector<double>{});
      r.traceRuns = j.value("reference_trace_ms_runs", std::vector<double>{});
      r.baryMax = j.at("bary_max_error").get<double>();
      r.baryP999 = j.at("bary_p999_error").get<double>();
      r.disagreementFraction = j.at("disagreement_fraction").get<double>();
      if (j.contains("load")) r.load = readLoad(j["load"], at + "/load");
      // The chart places these on log axes (an error of 0 on a row of its own).
      const auto finite = [&](const char* field, double value, bool positive) {
        if (std::isfinite(value) && (positive ? value > 0 : value >= 0)) return;
        throw badInput(at + "/" + field, "is " + formatNumber(value) + (positive ? "; must be finite and > 0" : "; must be finite and >= 0"));
      };
      finite("raster_ms", r.rasterMs, true);
      finite("bary_p999_error", r.baryP999, false);
      finite("disagreement_fraction", r.disagreementFraction, false);
      rows.push_back(r);
    } catch (const nlohmann::json::exception& e) {
      throw badInput(at, std::string("missing or mistyped field: ") + e.what());
    }
  }
  if (rows.empty()) throw badInput(path + ": /rows", "no rows");
  BenchResults results{rows, std::nullopt, std::nullopt};
  if (doc.contains("machine")) {
    const nlohmann::json& j = doc["machine"];
    try {
      BenchMachine m;
      m.cpu = j.at("cpu").get<std::string>();
      m.logicalCpus = j.at("logical_cpus").get<int>();
      m.widestKernelIsa = j.at("widest_kernel_isa").get<std::string>();
      m.fastestEmbreeIsa = j.at("fastest_embree_isa").get<std::string>();
      m.compiler = j.at("compiler").get<std::string>();
      m.embree = j.at("embree").get<std::string>();
      m.rastercheck = j.at("rastercheck").get<std::string>();
      results.machine = m;
    } catch (const nlohmann::json::exception& e) {
      throw badInput(path + ": /machine", std::string("missing or mistyped field: ") + e.what());
    }
  }
  if (doc.contains("load")) results.load = readLoad(doc["load"], path + ": /load");
  return results;
}

namespace {

// A CSV field in quotes, a quote in it doubled (RFC 4180): a file name may hold either.
std::string csvQuoted(const std::string& field) {
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string benchCsv(const std::vector<BenchRow>& rows) {
  std::ostringstream out;
  out << "scene,triangles,width,height,threads,setting,default,runs,raster_ms,raster_ms_min,raster_ms_max,"
         "transform_ms,setup_ms,bin_ms,tiles_ms,reference_build_ms,reference_trace_ms,speedup,speedup_with_build,"
         "triangles_per_second,pixels_per_second,bary_max_error,bary_p999_error,disagreement_fraction,exr_write_ms,"
         "reference_isa,raster_isa,store_floor_ms,diagnostics,cull,speedup_min,speedup_max,reference_build,"
         "reference_low_build_ms,reference_low_trace_ms,reference_medium_build_ms,reference_medium_trace_ms,"
         "speedup_with_build_quality,load_other_processes,load_steal,raster_over_default,raster_over_default_min,"
         "raster_over_default_max\n";
  char line[768];  // every field after the scene: numbers and short names
  for (const BenchRow& r : rows) {
    char exr[32] = "";  // empty: not measured for this setting
    if (r.exrWriteMs >= 0) std::snprintf(exr, sizeof exr, "%.4g", r.exrWriteMs);
    char load[2][32] = {};  // other processes, steal; empty where not measured
    if (r.load) {
      std::snprintf(load[0], sizeof load[0], "%.4g", r.load->others);
      std::snprintf(load[1], sizeof load[1], "%.4g", r.load->steal);
    }
    char overDefault[3][32] = {};  // the median's ratio, the least and the greatest round's; empty where none
    if (r.overDefault > 0) {
      std::snprintf(overDefault[0], sizeof overDefault[0], "%.4g", r.overDefault);
      std::snprintf(overDefault[1], sizeof overDefault[1], "%.4g", r.overDefaultMin);
      std::snprintf(overDefault[2], sizeof overDefault[2], "%.4g", r.overDefaultMax);
    }
    char builds[2][2][32] = {};  // low, medium: build, trace; empty where not measured
    for (const BenchRow::ReferenceBuild& b : r.referenceBuilds) {
      const int k = b.build == "low" ? 0 : b.build == "medium" ? 1 : -1;
      if (k < 0) continue;
      std::snprintf(builds[k][0], sizeof builds[k][0], "%.4g", b.buildMs);
      std::snprintf(builds[k][1], sizeof builds[k][1], "%.4g", b.traceMs);
    }
    std::snprintf(line, sizeof line,
                  ",%zu,%d,%d,%d,%s,%s,%d,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,"
                  "%.4g,%.4g,%s,%s,%s,%.4g,%s,%s,%.4g,%.4g,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n",
                  r.triangles, r.width, r.height, r.threads, r.setting.c_str(),
                  r.isDefault ? "true" : "false", r.runs, r.rasterMs, r.rasterMsMin, r.rasterMsMax, r.transformMs,
                  r.setupMs, r.binMs, r.tilesMs, r.referenceBuildMs, r.referenceTraceMs, r.speedup,
                  r.speedupWithBuild, r.trianglesPerSecond, r.pixelsPerSecond, r.baryMax, r.baryP999,
                  r.disagreementFraction, exr, r.referenceIsa.c_str(), r.rasterIsa.c_str(), r.storeFloorMs,
                  r.diagnostics ? "true" : "false", r.cull.c_str(), r.speedupMin, r.speedupMax, r.referenceBuild.c_str(),
                  builds[0][0], builds[0][1], builds[1][0], builds[1][1], r.speedupWithBuildQuality.c_str(), load[0],
                  load[1], overDefault[0], overDefault[1], overDefault[2]);
    out << csvQuoted(r.scene) << line;
  }
  return out.str();
}

}  // namespace rc::app
