// bench's sweep and its figures: the settings it times, the machine it names, each speed-up
// against the reference build best for it, each row against its scene's default round by
// round, and the load of other work during the run (the chart in bench_chart_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "app/bench.h"
#include "app/bench_conditions.h"
#include "core/error.h"
#include "core/parallel.h"
#include "tests/test_files.h"

namespace {

using rc::app::BenchRow;
using rc::app::BestReference;
using rc::app::bestReference;


TEST(BenchSettings, TheCommandLinesCombinationJoinsTheSweepUnlessItIsThere) {
  const auto names = [](const rc::RasterOptions& base) {
    std::vector<std::string> out;
    for (const rc::app::BenchSetting& s : rc::app::benchSettings(base)) out.push_back(s.name);
    return out;
  };
  const std::vector<std::string> sweep = names(rc::RasterOptions{});
  ASSERT_FALSE(sweep.empty());
  EXPECT_EQ(sweep.front(), "perspective-float-8bit");
  EXPECT_EQ(std::count(sweep.begin(), sweep.end(), "perspective-float-8bit"), 1);
  for (int bits : {4, 16, 0}) {  // in the sweep already: nothing joins
    rc::RasterOptions base;
    base.subpixelBits = bits;
    EXPECT_EQ(names(base).size(), sweep.size()) << bits;
  }
  rc::RasterOptions asked;
  asked.interpolation = rc::Interpolation::kAffine;
  asked.precision = rc::Precision::kDouble;
  asked.subpixelBits = 4;
  const std::vector<rc::app::BenchSetting> settings = rc::app::benchSettings(asked);
  ASSERT_EQ(settings.size(), sweep.size() + 1);
  const rc::app::BenchSetting& last = settings.back();
  EXPECT_EQ(last.name, "affine-double-4bit");
  EXPECT_FALSE(last.isDefault);
  EXPECT_EQ(last.raster.interpolation, rc::Interpolation::kAffine);
  EXPECT_EQ(last.raster.precision, rc::Precision::kDouble);
  EXPECT_EQ(last.raster.subpixelBits, 4);
  // The sweep itself is unchanged by the command line's arithmetic: its first row is the default.
  EXPECT_EQ(settings.front().name, "perspective-float-8bit");
  EXPECT_EQ(settings.front().raster.interpolation, rc::Interpolation::kPerspective);
  EXPECT_EQ(settings.front().raster.subpixelBits, 8);
  EXPECT_EQ(rc::app::benchSettingName(rc::Interpolation::kPerspective, rc::Precision::kFloat, 0),
            "perspective-float-nosnap");
}

// --threads 1, --raster-isa sse2, --no-diagnostics and --cull none apply to every row, and the
// variants they make the same as the default are left out rather than timed twice.
TEST(BenchSettings, VariantsTheCommandLineAlreadyRunsAreLeftOut) {
  rc::RasterOptions base;
  base.threads = 1;
  base.isa = rc::KernelIsa::kSse2;
  base.diagnostics = false;
  base.culling = rc::Culling::kNone;
  const std::vector<rc::app::BenchSetting> settings = rc::app::benchSettings(base);
  std::vector<std::string> names;
  for (const rc::app::BenchSetting& s : settings) {
    names.push_back(s.name);
    EXPECT_EQ(s.raster.threads, 1) << s.name;
    EXPECT_FALSE(s.raster.diagnostics) << s.name;
    EXPECT_EQ(s.raster.culling, rc::Culling::kNone) << s.name;
    if (s.name != "perspective-float-8bit-avx2") {
      EXPECT_EQ(s.raster.isa, rc::KernelIsa::kSse2) << s.name;
    }
  }
  for (const char* gone : {"perspective-float-8bit-1thread", "perspective-float-8bit-sse2",
                           "perspective-float-8bit-nodiag", "perspective-float-8bit-nocull"}) {
    EXPECT_EQ(std::count(names.begin(), names.end(), gone), 0) << gone;
  }
  EXPECT_EQ(names.size(), 6u) << "the default, affine, double, 4, 16 bits and none";
  // On the tool's defaults every variant is there.
  std::vector<std::string> all;
  for (const rc::app::BenchSetting& s : rc::app::benchSettings(rc::RasterOptions{})) all.push_back(s.name);
  const bool oneCore = rc::resolveThreadCount(0) == 1;  // there the default runs on 1 thread already
  for (const std::string variant : {"perspective-float-8bit-1thread", "perspective-float-8bit-sse2",
                                    "perspective-float-8bit-nodiag", "perspective-float-8bit-nocull"}) {
    const bool expected = !(oneCore && variant == "perspective-float-8bit-1thread");
    EXPECT_EQ(std::count(all.begin(), all.end(), variant), expected ? 1 : 0) << variant;
  }
}

// --settings: the named settings in the sweep's order whatever order they are named in,
// "default" for the default's, each once; a name the sweep lacks (here the one-thread row where
// every row runs on one thread) is refused with the names there are.
TEST(BenchSettings, PickSettingsKeepsTheNamedInTheSweepsOrder) {
  const std::vector<rc::app::BenchSetting> sweep = rc::app::benchSettings(rc::RasterOptions{});
  const auto names = [](const std::vector<rc::app::BenchSetting>& settings) {
    std::vector<std::string> out;
    for (const rc::app::BenchSetting& s : settings) out.push_back(s.name);
    return out;
  };
  EXPECT_EQ(names(rc::app::pickSettings(sweep, {})), names(sweep));
  const std::vector<rc::app::BenchSetting> picked =
      rc::app::pickSettings(sweep, {"perspective-float-4bit", "default", "affine-float-8bit", "default"});
  EXPECT_EQ(names(picked),
            (std::vector<std::string>{"perspective-float-8bit", "affine-float-8bit", "perspective-float-4bit"}));
  ASSERT_EQ(picked.size(), 3u);
  EXPECT_TRUE(picked[0].isDefault);
  EXPECT_EQ(picked[1].raster.interpolation, rc::Interpolation::kAffine);
  EXPECT_EQ(picked[2].raster.subpixelBits, 4);
  EXPECT_EQ(names(rc::app::pickSettings(sweep, {"perspective-float-8bit"})), names(rc::app::pickSettings(sweep, {"default"})));
  rc::testing::expectError([&] { rc::app::pickSettings(sweep, {"default", "perspective-float-3bit"}); },
                           rc::ExitCode::kUsage,
                           {"--settings: no setting is named 'perspective-float-3bit'; with these options bench has "
                            "default, perspective-float-8bit, affine-float-8bit, "},
                           "a 3-bit setting");
  rc::RasterOptions oneThread;
  oneThread.threads = 1;
  rc::testing::expectError(
      [&] { rc::app::pickSettings(rc::app::benchSettings(oneThread), {"perspective-float-8bit-1thread"}); },
      rc::ExitCode::kUsage, {"no setting is named 'perspective-float-8bit-1thread'"}, "the one-thread row on one thread");
}

// What bench says it measured on: the first processor's model name, family, model and stepping
// from /proc/cpuinfo, and the caches, since a virtual machine may name a whole family alike.
TEST(BenchMachine, TheCpuIsNamedWithItsGenerationAndCaches) {
  const std::string two = "processor\t: 0\nvendor_id\t: AuthenticAMD\ncpu family\t: 26\nmodel\t\t: 2\n"
                          "model name\t: AMD EPYC\nstepping\t: 1\nflags\t\t: fpu sse2 avx2\n\n"
                          "processor\t: 1\ncpu family\t: 25\nmodel\t\t: 17\nmodel name\t: Other\nstepping\t: 0\n\n";
  const std::vector<rc::app::CpuCache> caches = {{"L1d", "48K"}, {"L2", "1024K"}, {"L3", "32768K"}};
  EXPECT_EQ(rc::app::cpuDescription(two, caches), "AMD EPYC (family 26, model 2, stepping 1; L1d 48K, L2 1024K, L3 32768K)");
  EXPECT_EQ(rc::app::cpuDescription(two, {}), "AMD EPYC (family 26, model 2, stepping 1)");
  // Other architectures name other fields: what is there is said, the rest left out.
  EXPECT_EQ(rc::app::cpuDescription("processor\t: 0\nBogoMIPS\t: 50.00\nCPU part\t: 0xd0c\n", {{"L2", "1024K"}}),
            "unknown (L2 1024K)");
  EXPECT_EQ(rc::app::cpuDescription("", {}), "unknown");
  EXPECT_EQ(rc::app::cpuDescription("model name\t:\ncpu family\t: 6\nmodel\t\t: 85\n", {}), "unknown (family 6, model 85)");
}

// The speed-ups count against the reference at its best for each: at 1M triangles the medium
// build traced faster and the low one took less in all (session 30's figures).
TEST(BenchReference, EachSpeedupTakesTheBuildThatIsBestForIt) {
  using B = BenchRow::ReferenceBuild;
  const BestReference best = bestReference({B{"medium", 156.5, 53.7}, B{"low", 56.6, 58.3}});
  EXPECT_EQ(best.fasterTrace, 0u);
  EXPECT_EQ(best.smallerSum, 1u);
  const BestReference swapped = bestReference({B{"low", 56.6, 58.3}, B{"medium", 156.5, 53.7}});
  EXPECT_EQ(swapped.fasterTrace, 1u);
  EXPECT_EQ(swapped.smallerSum, 0u);
  const BestReference cube = bestReference({B{"medium", 0.27, 3.73}, B{"low", 0.19, 2.93}});
  EXPECT_EQ(cube.fasterTrace, 1u);
  EXPECT_EQ(cube.smallerSum, 1u);
  const BestReference one = bestReference({B{"high", 200, 50}});
  EXPECT_EQ(one.fasterTrace, 0u);
  EXPECT_EQ(one.smallerSum, 0u);
  const BestReference tie = bestReference({B{"medium", 10, 5}, B{"low", 5, 5}});
  EXPECT_EQ(tie.fasterTrace, 0u);  // the first on a tie
  EXPECT_EQ(tie.smallerSum, 1u);
}

// A row's speed-ups from the builds' runs: the speed-up against the faster trace's median, the
// one with the build against the smaller sum's, both over the median frame, and the rounds' own
// ratios bracketing them. Figures where the two builds differ on purpose: in a real run the same
// quality can be best for both, and a bench run could not tell them apart (session 42's CI).
TEST(BenchReference, EachSpeedupCountsTheMediansOfTheBuildBestForIt) {
  BenchRow row;
  row.rasterRuns = {12, 10, 8};
  row.rasterMs = 10;
  row.rasterMsMin = 8;
  rc::app::countAgainstReference(row, {{"medium", {150, 156.5, 160}, {60, 53.7, 50}}, {"low", {50, 56.6, 57}, {58.3, 60, 58}}});
  ASSERT_EQ(row.referenceBuilds.size(), 2u);
  EXPECT_EQ(row.referenceBuilds[0].build, "medium");
  EXPECT_DOUBLE_EQ(row.referenceBuilds[0].buildMs, 156.5);
  EXPECT_DOUBLE_EQ(row.referenceBuilds[0].traceMs, 53.7);
  EXPECT_EQ(row.referenceBuilds[1].build, "low");
  EXPECT_DOUBLE_EQ(row.referenceBuilds[1].buildMs, 56.6);
  EXPECT_DOUBLE_EQ(row.referenceBuilds[1].traceMs, 58.3);
  EXPECT_EQ(row.referenceBuild, "medium");
  EXPECT_DOUBLE_EQ(row.referenceBuildMs, 156.5);
  EXPECT_DOUBLE_EQ(row.referenceTraceMs, 53.7);
  EXPECT_EQ(row.traceRuns, (std::vector<double>{60, 53.7, 50}));
  EXPECT_DOUBLE_EQ(row.speedup, 5.37);                     // 53.7 / 10, not / 8
  EXPECT_DOUBLE_EQ(row.speedupMin, 5.0);                   // 60 / 12
  EXPECT_DOUBLE_EQ(row.speedupMax, 6.25);                  // 50 / 8
  EXPECT_EQ(row.speedupWithBuildQuality, "low");
  EXPECT_DOUBLE_EQ(row.speedupWithBuild, (56.6 + 58.3) / 10);  // not medium's (156.5 + 53.7) / 10
  // One quality pinned: both speed-ups count against it.
  BenchRow pinned;
  pinned.rasterRuns = {4};
  pinned.rasterMs = pinned.rasterMsMin = 4;
  rc::app::countAgainstReference(pinned, {{"high", {200}, {50}}});
  EXPECT_EQ(pinned.referenceBuild, "high");
  EXPECT_EQ(pinned.speedupWithBuildQuality, "high");
  EXPECT_DOUBLE_EQ(pinned.speedup, 12.5);
  EXPECT_DOUBLE_EQ(pinned.speedupMin, 12.5);
  EXPECT_DOUBLE_EQ(pinned.speedupMax, 12.5);
  EXPECT_DOUBLE_EQ(pinned.speedupWithBuild, 62.5);
}

// Each row's frame over its scene's default's: the medians' ratio, and the rounds' own ratios
// (a round's frame over the default's frame of the same round, not over the default's median).
// The rows from `first` on are one scene's; those before it are left alone, and a scene without
// a default row gets no ratio.
TEST(BenchDefault, EachRowCountsAgainstItsScenesDefaultRoundByRound) {
  BenchRow earlier, affine, def, oneThread, lone;
  earlier.rasterMs = 7;  // another scene's row, before `first`
  affine.rasterRuns = {9, 22, 11};
  affine.rasterMs = 11;
  def.isDefault = true;
  def.rasterRuns = {10, 20, 10};
  def.rasterMs = 10;
  oneThread.rasterRuns = {20, 30, 40};
  oneThread.rasterMs = 30;
  std::vector<BenchRow> rows = {earlier, affine, def, oneThread};
  rc::app::countAgainstDefault(rows, 1);
  EXPECT_EQ(rows[0].overDefault, 0.0) << "another scene's row";
  EXPECT_DOUBLE_EQ(rows[1].overDefault, 1.1);     // 11 / 10: the default comes after it
  EXPECT_DOUBLE_EQ(rows[1].overDefaultMin, 0.9);  // 9 / 10
  EXPECT_DOUBLE_EQ(rows[1].overDefaultMax, 1.1);  // 22 / 20 and 11 / 10
  EXPECT_DOUBLE_EQ(rows[2].overDefault, 1.0);
  EXPECT_DOUBLE_EQ(rows[2].overDefaultMin, 1.0);
  EXPECT_DOUBLE_EQ(rows[2].overDefaultMax, 1.0);
  EXPECT_DOUBLE_EQ(rows[3].overDefault, 3.0);     // 30 / 10
  EXPECT_DOUBLE_EQ(rows[3].overDefaultMin, 1.5);  // 30 / 20, round 2's; not 20 / 10
  EXPECT_DOUBLE_EQ(rows[3].overDefaultMax, 4.0);  // 40 / 10
  // Without a default row (bench --settings naming others only): nothing to count against.
  lone.rasterRuns = {5};
  lone.rasterMs = 5;
  rows.push_back(lone);
  rc::app::countAgainstDefault(rows, 4);
  EXPECT_EQ(rows[4].overDefault, 0.0);
  EXPECT_EQ(rows[4].overDefaultMin, 0.0);
  EXPECT_EQ(rows[4].overDefaultMax, 0.0);
  EXPECT_DOUBLE_EQ(rows[3].overDefault, 3.0) << "the earlier scene's rows stay";
}

// How busy other work kept the machine, from two readings of /proc/stat's first line and this
// process's own CPU time between them.
TEST(BenchLoad, OtherWorkIsTheMachinesBusyTimeLessBenchsOwn) {
  // user nice system idle iowait irq softirq steal guest guest_nice, as Linux 6 writes them.
  const std::optional<rc::app::CpuTimes> t = rc::app::parseProcStat("cpu  100 2 30 5000 40 5 6 7 50 1\ncpu0 1 2 3 4\n");
  ASSERT_TRUE(t.has_value());
  EXPECT_DOUBLE_EQ(t->busy, 100 + 2 + 30 + 5 + 6);  // iowait is idle; guest is already in user
  EXPECT_DOUBLE_EQ(t->steal, 7);
  EXPECT_DOUBLE_EQ(t->total, 100 + 2 + 30 + 5000 + 40 + 5 + 6 + 7);
  // An old kernel's four fields: no steal.
  const std::optional<rc::app::CpuTimes> old = rc::app::parseProcStat("cpu 10 0 5 85");
  ASSERT_TRUE(old.has_value());
  EXPECT_DOUBLE_EQ(old->busy, 15);
  EXPECT_DOUBLE_EQ(old->steal, 0);
  EXPECT_DOUBLE_EQ(old->total, 100);
  for (const char* text : {"", "cpu0 1 2 3 4", "cpu 1 2 3", "intr 5 6 7 8", "cpu x 2 3 4"}) {
    EXPECT_FALSE(rc::app::parseProcStat(text).has_value()) << text;
  }

  // 2000 ticks of all CPUs' time passed; the machine was busy for 600 of them, 400 of which
  // were bench's own; 20 went to other guests.
  const rc::app::CpuTimes before{1000, 10, 5000}, after{1600, 30, 7000};
  const rc::app::BenchLoad load = rc::app::loadBetween(before, after, 400);
  EXPECT_DOUBLE_EQ(load.others, 0.1);
  EXPECT_DOUBLE_EQ(load.steal, 0.01);
  EXPECT_EQ(rc::app::describe(load), "other processes used 10.0% of the CPUs' time, the hypervisor's other guests 1.0% (steal)");
  // Bench's own time, measured more finely than the kernel's ticks, can pass the busy time a
  // little: no negative share.
  EXPECT_DOUBLE_EQ(rc::app::loadBetween(before, after, 603).others, 0.0);
  // No time passed: nothing to share.
  const rc::app::BenchLoad none = rc::app::loadBetween(before, before, 0);
  EXPECT_DOUBLE_EQ(none.others, 0.0);
  EXPECT_DOUBLE_EQ(none.steal, 0.0);
}

}  // namespace
