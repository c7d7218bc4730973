// Speed against error: for each scene and each rasterizer setting, the median frame time
// (rendering only), the reference's build and trace times, and the setting's error against the
// reference, all measured in one process.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/bench_conditions.h"
#include "app/settings.h"

namespace rc::app {

struct BenchSetting {
  std::string name;     // e.g. "perspective-float-8bit"
  RasterOptions raster;
  bool isDefault = false;
};

// The settings bench sweeps, from the command line's rasterizer options: the default, affine,
// double precision, 4 and 16 subpixel bits, the default on one thread (the thread-scaling
// ratio), with the SSE2 kernels (what SIMD width buys; and the AVX2 ones where the default
// resolves to AVX-512), without the diagnostic channels and without culling, each where `base`
// does not run it so already; and last the combination of mode, precision and subpixel bits
// that `base` names, where it is none of those.
std::vector<BenchSetting> benchSettings(const RasterOptions& base);
// "perspective-float-8bit", "affine-double-nosnap", ...: a sweep row's name before its suffix.
std::string benchSettingName(Interpolation mode, Precision precision, int subpixelBits);
// The settings of `sweep` that `names` names (by the names bench's rows give them, or "default"
// for the default's), in the sweep's order; every one where `names` is empty. A name that no
// setting has is a usage error naming it and listing the names there are.
std::vector<BenchSetting> pickSettings(const std::vector<BenchSetting>& sweep, const std::vector<std::string>& names);

struct BenchRow {
  std::string scene, setting;
  bool isDefault = false;
  std::size_t triangles = 0;
  int width = 0, height = 0, threads = 0, runs = 0;
  double rasterMs = 0;            // median over runs
  double rasterMsMin = 0, rasterMsMax = 0;  // the spread of the runs: how noisy the machine was
  // Medians over runs of the rasterizer's stages (Rasterizer::stageTimes).
  double transformMs = 0, setupMs = 0, binMs = 0, tilesMs = 0;
  // Each stage of every timed frame, in round order: round r's stages ran inside rasterRuns[r].
  std::vector<double> transformRuns, setupRuns, binRuns, tilesRuns;
  // Median time to write the setting's output as `render -o` does (ZIP EXR, through a
  // temporary file), measured for the default setting only; negative for the others.
  double exrWriteMs = -1;
  // Median time of writeOutPass over the setting's output planes (rasterizer.h): writing them
  // alone with the kernels' stores, on the setting's threads, after the timed frames. The
  // floor that memory bandwidth sets under rasterMs; 0 where not measured (older reports).
  double storeFloorMs = 0;
  std::string rasterIsa;          // the rasterizer's kernels as this setting resolved on this CPU
  bool diagnostics = true;        // wrote the four diagnostic channels
  std::string cull = "auto";      // --cull: "auto" or "none"
  std::string referenceIsa;       // Embree's
  // The reference in every build quality measured (--embree-build's, or medium and low): its
  // build and trace, medians over runs.
  struct ReferenceBuild {
    std::string build;  // embreeBuildName
    double buildMs = 0, traceMs = 0;
  };
  std::vector<ReferenceBuild> referenceBuilds;
  std::string referenceBuild;     // the quality that traced faster, whose figures follow
  double referenceBuildMs = 0;    // median over runs
  double referenceTraceMs = 0;    // median over runs
  double speedup = 0;             // referenceTraceMs / rasterMs: against the faster trace
  // The least and the greatest of the rounds' own ratios: each round's trace over the same
  // round's frame, taken within about a second of each other. How far a slow spell moved the
  // ratio; with an odd number of runs they bracket `speedup`. 0 where not measured (older reports).
  double speedupMin = 0, speedupMax = 0;
  // This row's frame over its scene's default setting's: the medians' ratio (rasterMs over the
  // default row's), and the least and the greatest of the rounds' own (each round's frame over
  // the default's frame of the same round, taken within about a second of each other). What
  // the setting costs against the default: the one-thread row's says what the second thread
  // buys, the affine row's what perspective correction costs. 1 for the default itself; 0
  // where the scene has no default row (--settings without it) and in files from before
  // session 45.
  double overDefault = 0, overDefaultMin = 0, overDefaultMax = 0;
  // Every timed frame and trace, in round order (round r: rasterRuns[r], traceRuns[r]).
  std::vector<double> rasterRuns, traceRuns;
  // (build + trace) / raster, with the build quality whose sum is the smaller (the reference at
  // its best for one frame): speedupWithBuildQuality names it.
  double speedupWithBuild = 0;
  std::string speedupWithBuildQuality;
  double trianglesPerSecond = 0, pixelsPerSecond = 0;
  double baryMax = 0, baryP999 = 0, disagreementFraction = 0;
  // Pixels one path covers and the other does not, over those either covers (compare's
  // coverage_fraction); -1 in files from before session 49, which lack it.
  double coverageFraction = 0;
  // How busy other work kept the machine while this row's scene was measured (its builds,
  // rounds, errors and EXR writes; every row of a scene has the same); none where /proc/stat
  // cannot be read, and in files from before session 44.
  std::optional<BenchLoad> load;
};

// Which of the reference's builds each speed-up counts against: the one that traced faster
// (speedup), and the one whose build and trace took less (speedupWithBuild); the first on a tie.
struct BestReference {
  std::size_t fasterTrace = 0, smallerSum = 0;
};
BestReference bestReference(const std::vector<BenchRow::ReferenceBuild>& builds);

// A build quality of the reference as measured: its build and trace times of each round.
struct ReferenceRuns {
  std::string build;  // embreeBuildName
  std::vector<double> buildRuns, traceRuns;
};
// Fills a row's reference figures (referenceBuilds, referenceBuild and its times, traceRuns)
// and its speed-ups, each against the reference at its best for it (bestReference), from every
// build quality measured: round r traced traceRuns[r] beside the row's rasterRuns[r]. The
// row's rasterMs and rasterRuns must be set.
void countAgainstReference(BenchRow& row, const std::vector<ReferenceRuns>& references);

// Fills overDefault and its bounds in rows[first] onwards, one scene's rows, against the default
// among them; leaves them 0 where none is the default. Their rasterMs and rasterRuns must be set.
void countAgainstDefault(std::vector<BenchRow>& rows, std::size_t first);

// How the times were taken, for the table and the chart: "medians of 7 runs", or "one run".
std::string timingPhrase(int runs);

// `step` is called before each measured unit of work (progress).
// The reference is built and traced with settings.reference; with `alsoLowBuild` (and another
// quality there) the low-quality build is timed and traced beside it, for speedupWithBuild.
// The rasterizer runs each setting of `sweep` (benchSettings, or those pickSettings chose).
std::vector<BenchRow> runBench(const std::vector<Scene>& scenes, const RenderSettings& settings,
                               const std::vector<BenchSetting>& sweep, int runs, bool alsoLowBuild,
                               const std::function<void(const std::string&)>& step);

}  // namespace rc::app
