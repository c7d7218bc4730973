// bench's sweep of settings and its chart: the Pareto front, label placement, the SVG and the
// PNG drawn from crafted rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "app/bench.h"
#include "app/bench_files.h"
#include "app/bench_chart.h"
#include "core/error.h"
#include "core/parallel.h"
#include "tests/test_files.h"

namespace {

using rc::app::BenchRow;
using rc::app::BestReference;
using rc::app::bestReference;
namespace chart = rc::app::chart;

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

TEST(BenchChart, ParetoFrontKeepsWhatNothingElseBeatsOnBothAxes) {
  // x: time, y: error. (1, 5) and (2, 2) and (4, 0) are the front; (3, 2) is beaten by (2, 2)
  // on time alone; (1, 6) by (1, 5) on error alone; (2, 2) twice: both on the front.
  const std::vector<chart::Point> points = {{3, 2}, {1, 5}, {4, 0}, {2, 2}, {1, 6}, {5, 0}, {2, 2}};
  EXPECT_EQ(chart::paretoFront(points), (std::vector<std::size_t>{1, 3, 6, 2}));
  EXPECT_EQ(chart::paretoFront({{1, 1}}), (std::vector<std::size_t>{0}));
  EXPECT_TRUE(chart::paretoFront({}).empty());
}

TEST(BenchChart, SegmentsCrossBoxesOnlyThroughTheirInside) {
  const chart::Box box{10, 10, 20, 20};
  EXPECT_TRUE(chart::crosses({{0, 15}, {30, 15}}, box));   // straight through
  EXPECT_TRUE(chart::crosses({{12, 12}, {14, 14}}, box));  // wholly inside
  EXPECT_TRUE(chart::crosses({{0, 0}, {30, 30}}, box));    // the diagonal
  EXPECT_FALSE(chart::crosses({{0, 0}, {9, 9}}, box));     // stops short
  EXPECT_FALSE(chart::crosses({{0, 25}, {30, 25}}, box));  // passes below
  EXPECT_FALSE(chart::crosses({{0, 10}, {30, 10}}, box));  // along an edge
  EXPECT_FALSE(chart::crosses({{0, 19}, {19, 0}}, box));   // past the corner
  EXPECT_TRUE(chart::crosses({{0, 21}, {21, 0}}, box));    // across the corner
}

TEST(BenchChart, LabelsOfACrowdedRowNeitherOverlapNorCoverADot) {
  // Twelve dots 9 px apart on one line, labels 40 px wide: most cannot sit beside their dot.
  std::vector<chart::Point> points;
  for (int i = 0; i < 12; ++i) points.push_back({100 + 9.0 * i, 150});
  const std::vector<double> radii(points.size(), 4.5), widths(points.size(), 40);
  const chart::Box area{0, 0, 400, 300};
  const std::vector<chart::Segment> lines = {{{80, 160}, {300, 160}}, {{100, 150}, {100, 100}}};
  const std::vector<chart::LabelPlace> places = chart::placeLabels(points, radii, widths, 13, area, lines);
  ASSERT_EQ(places.size(), points.size());
  int leaders = 0;
  for (std::size_t i = 0; i < places.size(); ++i) {
    const chart::Box& b = places[i].box;
    EXPECT_TRUE(b.inside(area)) << i;
    EXPECT_NEAR(b.x1 - b.x0, 40, 1e-9);
    EXPECT_NEAR(b.y1 - b.y0, 13, 1e-9);
    for (std::size_t j = 0; j < places.size(); ++j) {
      if (j != i) {  // nor do they touch: a gap of 3 between labels side by side
        const chart::Box wider{b.x0 - 3, b.y0, b.x1 + 3, b.y1};
        EXPECT_FALSE(wider.overlaps(places[j].box)) << i << " and " << j;
      }
      const chart::Box dot{points[j].x - 4.5, points[j].y - 4.5, points[j].x + 4.5, points[j].y + 4.5};
      EXPECT_FALSE(b.overlaps(dot)) << "label " << i << " covers dot " << j;
    }
    for (const chart::Segment& l : lines) EXPECT_FALSE(chart::crosses(l, b)) << i;
    leaders += places[i].leader;
  }
  EXPECT_GT(leaders, 0) << "a crowded row needs labels moved away, with leader lines";
  // A lone point takes the place to its right, level with it, without a leader.
  const std::vector<chart::LabelPlace> lone = chart::placeLabels({{50, 50}}, {4}, {30}, 13, area);
  EXPECT_FALSE(lone[0].leader);
  EXPECT_NEAR(lone[0].box.x0, 57, 1e-9);
  EXPECT_NEAR((lone[0].box.y0 + lone[0].box.y1) / 2, 50, 1e-9);
}

TEST(BenchChart, ShortNamesKeepWhatDiffersFromTheDefault) {
  const std::string d = "perspective-float-8bit";
  EXPECT_EQ(chart::shortSettingName(d, d), "default");
  EXPECT_EQ(chart::shortSettingName("affine-float-8bit", d), "affine");
  EXPECT_EQ(chart::shortSettingName("perspective-float-nosnap", d), "nosnap");
  EXPECT_EQ(chart::shortSettingName("perspective-float-8bit-1thread", d), "1thread");
  EXPECT_EQ(chart::shortSettingName("affine-double-4bit", d), "affine double 4bit");
}

TEST(BenchChart, FormatComesFromTheName) {
  EXPECT_EQ(rc::app::chartFormatOf("a/b.svg"), rc::app::ChartFormat::kSvg);
  EXPECT_EQ(rc::app::chartFormatOf("B.SVG"), rc::app::ChartFormat::kSvg);
  EXPECT_EQ(rc::app::chartFormatOf("chart.png"), rc::app::ChartFormat::kPng);
  for (const char* bad : {"chart.bmp", "chart", "svg", ".svg.txt", "chart.pn"}) {
    try {
      rc::app::chartFormatOf(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const rc::Error& e) {
      EXPECT_EQ(e.code(), rc::ExitCode::kUsage) << bad;
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

// Two scenes of three settings each.
std::vector<BenchRow> craftedRows() {
  std::vector<BenchRow> rows;
  for (const char* scene : {"blob:tris=1000", "floor"}) {
    const struct {
      const char* setting;
      bool isDefault;
      double ms, p999, disagreement;
    } settings[] = {{"perspective-float-8bit", true, 3.0, 1.8e-7, 2.5e-5},
                    {"affine-float-8bit", false, 2.9, 2e-2, 2.5e-5},
                    {"perspective-double-8bit", false, 4.1, 0, 2.5e-5}};
    for (const auto& s : settings) {
      BenchRow r;
      r.scene = scene;
      r.setting = s.setting;
      r.isDefault = s.isDefault;
      r.triangles = 1002000;
      r.width = 1920, r.height = 1080, r.threads = 2, r.runs = 7;
      r.rasterMs = s.ms;
      r.baryP999 = s.p999;
      r.disagreementFraction = s.disagreement;
      r.referenceIsa = "avx512";
      r.referenceTraceMs = 21.7;
      r.referenceBuildMs = 0.45;
      rows.push_back(r);
    }
  }
  return rows;
}

// The number of times `needle` occurs in `text`.
using rc::testing::occurrences;

// The <circle> elements of an SVG: those with a tooltip, and those with an outline.
struct Circles {
  int titled = 0, ringed = 0;
};
Circles circles(const std::string& svg) {
  Circles c;
  for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) {
    const std::string tag = svg.substr(at, svg.find('>', at) - at + 1);
    c.ringed += tag.find("stroke=") != std::string::npos;
    c.titled += svg.compare(at + tag.size(), 7, "<title>") == 0;
  }
  return c;
}

TEST(BenchChart, ALongNameLosesItsMiddleOnCharacterBoundaries) {
  EXPECT_EQ(chart::elideMiddle("short.obj", 9), "short.obj");
  EXPECT_EQ(chart::elideMiddle("/a/very/long/path/to/mesh.obj", 15), "/a/v...mesh.obj");
  EXPECT_EQ(chart::elideMiddle("/a/very/long/path/to/mesh.obj", 15).size(), 15u);
  // U+00E9 is two bytes: a cut never splits it.
  EXPECT_EQ(chart::elideMiddle("\xC3\xA9\xC3\xA9\xC3\xA9-long-middle-\xC3\xA9\xC3\xA9\xC3\xA9", 12),
            "\xC3\xA9...\xC3\xA9\xC3\xA9\xC3\xA9");
}

// A scene named by a long path keeps its conditions on the chart: the name loses its middle.
TEST(BenchChart, ALongSceneNameLeavesTheConditionsWhole) {
  std::vector<BenchRow> rows = craftedRows();
  const std::string path = "/" + std::string(300, 'x') + "/" + std::string(300, 'y') + "/mesh.obj";
  for (BenchRow& row : rows) {
    if (row.scene == rows[0].scene) row.scene = path;
  }
  const std::string svg = rc::app::benchChartSvg(rows);
  EXPECT_EQ(svg.find(std::string(300, 'x')), std::string::npos);
  const std::size_t line = svg.find("y/mesh.obj: ");
  ASSERT_NE(line, std::string::npos) << "the name's end, then its conditions";
  EXPECT_NE(svg.find("...", svg.rfind(">", line)), std::string::npos);
  EXPECT_NE(svg.find("BVH build", line), std::string::npos);
}

// The machine's line under the title: one where it fits, else its hardware and its builds on
// two, the chart 14 pixels taller, and a CPU name too long even for that loses its middle.
TEST(BenchChart, TheMachineTakesASecondLineRatherThanRunningOffTheChart) {
  const auto height = [](const std::string& svg) {
    const std::size_t at = svg.find("height=\"");
    return std::stoi(svg.substr(at + 8));
  };
  const std::vector<BenchRow> rows = craftedRows();
  rc::app::BenchMachine machine{"AMD EPYC", 2, "avx512", "avx512", "GCC 12.2.0", "3.13.5", "0.1.0"};
  const std::string shortSvg = rc::app::benchChartSvg(rows, &machine);
  EXPECT_NE(shortSvg.find(">measured on AMD EPYC, 2 logical CPUs (kernels up to avx512, Embree avx512); GCC 12.2.0, "
                          "Embree 3.13.5, rastercheck 0.1.0<"), std::string::npos);
  machine.cpu = "AMD EPYC (family 26, model 2, stepping 1; L1d 48K, L2 1024K, L3 32768K)";
  const std::string twoLines = rc::app::benchChartSvg(rows, &machine);
  EXPECT_NE(twoLines.find(">measured on " + machine.cpu + ", 2 logical CPUs (kernels up to avx512, Embree avx512)<"),
            std::string::npos) << twoLines.substr(0, 2000);
  EXPECT_NE(twoLines.find(">built with GCC 12.2.0, Embree 3.13.5, rastercheck 0.1.0<"), std::string::npos);
  EXPECT_EQ(height(twoLines), height(shortSvg) + 14);
  EXPECT_EQ(height(rc::app::benchChartSvg(rows)), height(shortSvg));
  machine.cpu = std::string(400, 'c');
  const std::string elided = rc::app::benchChartSvg(rows, &machine);
  EXPECT_EQ(elided.find(std::string(200, 'c')), std::string::npos);
  EXPECT_NE(elided.find("...ccc"), std::string::npos);
  EXPECT_NE(elided.find(", 2 logical CPUs (kernels up to avx512, Embree avx512)<"), std::string::npos);
  EXPECT_NE(elided.find(">built with GCC 12.2.0, Embree 3.13.5, rastercheck 0.1.0<"), std::string::npos);
}

// The load's line under the machine's, and busyNote's words on one more where the machine was
// busy: each line 14 pixels more of chart.
TEST(BenchChart, TheLoadIsNamedUnderTheMachineAndABusyMachineSaysSo) {
  const auto height = [](const std::string& svg) { return std::stoi(svg.substr(svg.find("height=\"") + 8)); };
  const std::vector<BenchRow> rows = craftedRows();
  const rc::app::BenchMachine machine{"AMD EPYC", 2, "avx512", "avx512", "GCC 12.2.0", "3.13.5", "0.1.0"};
  const std::string bare = rc::app::benchChartSvg(rows, &machine);
  const rc::app::BenchLoad idle{0.004, 0.0};
  const std::string quiet = rc::app::benchChartSvg(rows, &machine, &idle);
  // (The apostrophes escaped, as all text of the SVG.)
  EXPECT_NE(quiet.find(">load during the run: other processes used 0.4% of the CPUs&#39; time, the hypervisor&#39;s "
                       "other guests 0.0% (steal)<"),
            std::string::npos);
  EXPECT_EQ(quiet.find("a busy machine"), std::string::npos);
  EXPECT_EQ(height(quiet), height(bare) + 14);
  EXPECT_LT(quiet.find(">measured on "), quiet.find(">load during the run: "));
  // 4% of others and 2% of steal: busy, though neither alone passes 5%.
  const rc::app::BenchLoad busy{0.04, 0.02};
  const std::string loud = rc::app::benchChartSvg(rows, &machine, &busy);
  EXPECT_NE(loud.find(">load during the run: other processes used 4.0% of the CPUs&#39; time, the hypervisor&#39;s "
                      "other guests 2.0% (steal)<"),
            std::string::npos);
  EXPECT_NE(loud.find(">a busy machine, so slower and noisier figures than an idle one gives<"), std::string::npos);
  EXPECT_EQ(height(loud), height(bare) + 28);
  // Without a machine (an old file, say) the load stands alone.
  const std::string alone = rc::app::benchChartSvg(rows, nullptr, &idle);
  EXPECT_EQ(alone.find(">measured on "), std::string::npos);
  EXPECT_NE(alone.find(">load during the run: "), std::string::npos);
  EXPECT_EQ(rc::app::busyNote(rc::app::BenchLoad{0.05, 0.0}), "");
  EXPECT_NE(rc::app::busyNote(rc::app::BenchLoad{0.0, 0.051}), "");
  // A scene whose own rows say other work made it busy says so on its line; an idle one does not.
  std::vector<BenchRow> scenes = craftedRows();
  for (BenchRow& row : scenes) row.load = row.scene == "floor" ? rc::app::BenchLoad{0.195, 0.01} : idle;
  const std::string perScene = rc::app::benchChartSvg(scenes, &machine, &idle);
  EXPECT_EQ(occurrences(perScene, "; busy: other work "), 1);
  const std::size_t at = perScene.find(">floor: ");
  ASSERT_NE(at, std::string::npos);
  const std::string floorLine = perScene.substr(at + 1, perScene.find('<', at) - at - 1);
  EXPECT_TRUE(floorLine.ends_with(" ms; busy: other work 20.5%")) << floorLine;
}

TEST(BenchChart, SvgShowsEveryRowInBothPanelsLabelledWithItsConditions) {
  const std::string svg = rc::app::benchChartSvg(craftedRows());
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  // A dot with a tooltip per row and panel; the legend's dots have none.
  const Circles dots = circles(svg);
  EXPECT_EQ(dots.titled, 12);
  // Fronts: bary error: affine (fastest), default, double (0) in each scene; disagreement: the
  // fastest alone, the others being as wrong and slower. A ring marks each, and one in the legend.
  EXPECT_EQ(dots.ringed, 2 * (3 + 1) + 1);
  for (const char* label : {">default<", ">affine<", ">double<", "1,002,000 triangles, 1920x1080, 2 threads, medians of 7 runs",
                            "pixels in disagreement", "barycentric error, p99.9", ">0<"}) {
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  }
  EXPECT_EQ(occurrences(svg, ">default<"), 4);
  // Markup in a scene's name is escaped.
  std::vector<BenchRow> odd = craftedRows();
  odd[0].scene = "a<b>&\"c\"";
  const std::string escaped = rc::app::benchChartSvg(odd);
  EXPECT_EQ(escaped.find("a<b>"), std::string::npos);
  EXPECT_NE(escaped.find("a&lt;b&gt;&amp;&quot;c&quot;"), std::string::npos);
}

TEST(BenchChart, PngIsTheSameLayoutDrawn) {
  const std::vector<BenchRow> rows = craftedRows();
  const rc::Rgb8Image image = rc::app::benchChartImage(rows);
  const std::string svg = rc::app::benchChartSvg(rows);
  EXPECT_EQ(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(image.width) +
                     "\" height=\"" + std::to_string(image.height) + "\""),
            0u);
  // The default's red dots (four in the panels, one in the legend) and dark text are drawn.
  int red = 0, dark = 0;
  for (std::size_t i = 0; i < image.pixels.size(); i += 3) {
    const int r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
    red += r > 200 && g < 60 && b < 60;
    dark += r < 60 && g < 60 && b < 60;
  }
  EXPECT_GT(red, 5 * 60) << "five dots of radius 6 have about 110 pixels each";
  EXPECT_GT(dark, 2000);
}

}  // namespace

// What bench writes, readBenchJson reads back; a row whose figures no chart can place (an error
// below zero, a time that is not positive) is refused, naming the file, the row and the field.
// (JSON has no infinity: nlohmann refuses 1e999 as it parses, and bench writes one as null.)
TEST(BenchJson, ReadsWhatBenchWroteAndRefusesFiguresNoChartCanPlace) {
  const rc::testing::TempDir temp;
  std::vector<BenchRow> rows = craftedRows();
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i].coverageFraction = 0.0625 * double(i);
  const rc::app::BenchMachine machine{"test cpu", 2, "avx2", "avx2", "GCC 12", "3.13.5", "0.1"};
  const std::string good = temp.write("good.json", rc::app::benchJson(rows, machine));
  const rc::app::BenchResults back = rc::app::readBenchJson(good);
  ASSERT_EQ(back.rows.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back.rows[i].setting, rows[i].setting);
    EXPECT_EQ(back.rows[i].rasterMs, rows[i].rasterMs);
    EXPECT_EQ(back.rows[i].baryP999, rows[i].baryP999);
    EXPECT_EQ(back.rows[i].disagreementFraction, rows[i].disagreementFraction);
    EXPECT_EQ(back.rows[i].coverageFraction, rows[i].coverageFraction);
    EXPECT_EQ(back.rows[i].overDefault, 0.0) << "none written";
  }
  // A file from before session 49 has no coverage_fraction: read as -1, which the report shows as "-".
  std::string older = rc::app::benchJson(rows, machine);
  for (std::size_t at; (at = older.find("\"coverage_fraction\": ")) != std::string::npos;) {
    older.erase(at, older.find_first_of(",\n}", at) + 1 - at);
  }
  const rc::app::BenchResults olderBack = rc::app::readBenchJson(temp.write("older.json", older));
  ASSERT_EQ(olderBack.rows.size(), rows.size()) << older;
  for (const BenchRow& r : olderBack.rows) EXPECT_EQ(r.coverageFraction, -1.0) << r.setting;
  // Each row's frame over the default's comes back where it was measured.
  std::vector<BenchRow> counted = rows;
  counted[1].overDefault = 1.75;
  counted[1].overDefaultMin = 1.5;
  counted[1].overDefaultMax = 2.125;
  const rc::app::BenchResults countedBack = rc::app::readBenchJson(temp.write("counted.json", rc::app::benchJson(counted, machine)));
  EXPECT_EQ(countedBack.rows[1].overDefault, 1.75);
  EXPECT_EQ(countedBack.rows[1].overDefaultMin, 1.5);
  EXPECT_EQ(countedBack.rows[1].overDefaultMax, 2.125);
  EXPECT_EQ(countedBack.rows[0].overDefault, 0.0);
  ASSERT_TRUE(back.machine.has_value());
  EXPECT_EQ(back.machine->cpu, "test cpu");
  EXPECT_FALSE(back.load.has_value()) << "bench could not read /proc/stat: no load";
  struct Case {
    const char* field;
    const char* value;  // JSON text
  };
  for (const Case c : {Case{"disagreement_fraction", "-0.001"}, Case{"coverage_fraction", "-0.001"}, Case{"bary_p999_error", "-1e-7"},
                       Case{"raster_ms", "0"}, Case{"raster_ms", "-3"}}) {
    std::string text = rc::app::benchJson(rows, machine);
    // Row 1's field, whatever the writer's spacing: replace the value after its second mention.
    const std::string key = std::string("\"") + c.field + "\": ";
    std::size_t at = text.find(key);
    at = text.find(key, at + 1);
    ASSERT_NE(at, std::string::npos) << c.field;
    const std::size_t end = text.find_first_of(",\n}", at + key.size());
    text.replace(at + key.size(), end - at - key.size(), c.value);
    const std::string bad = temp.write("bad.json", text);
    rc::testing::expectError([&] { rc::app::readBenchJson(bad); }, rc::ExitCode::kBadInput,
                             {bad + ": /rows/1/" + c.field + ": is "}, std::string(c.field) + " = " + c.value);
  }
  // JSON that is not a bench report at all: check's own report, another version, rows not a list.
  for (const char* text : {R"({"format_version": 1, "scenes": []})", R"({"format_version": 2, "rows": []})",
                           R"({"format_version": 1, "rows": {}})", R"([1, 2])"}) {
    const std::string other = temp.write("other.json", text);
    rc::testing::expectError([&] { rc::app::readBenchJson(other); }, rc::ExitCode::kBadInput,
                             {other + ": not a rastercheck bench report (format_version 1 with rows)"}, text);
  }
}

// The load bench measured comes back; a share outside 0 to 1, or one missing or not a number, is
// refused naming the file and the field.
TEST(BenchJson, ReadsTheLoadBackAndRefusesAShareOutsideZeroToOne) {
  const rc::testing::TempDir temp;
  const std::vector<BenchRow> rows = craftedRows();
  const rc::app::BenchMachine machine{"test cpu", 2, "avx2", "avx2", "GCC 12", "3.13.5", "0.1"};
  std::vector<BenchRow> loaded = rows;
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    if (i != 2) loaded[i].load = rc::app::BenchLoad{0.25 + 0.125 * double(i), 0.03125};  // row 2 without one
  }
  const std::string text = rc::app::benchJson(loaded, machine, rc::app::BenchLoad{0.125, 0.0625});
  const rc::app::BenchResults back = rc::app::readBenchJson(temp.write("good.json", text));
  ASSERT_TRUE(back.load.has_value());
  EXPECT_EQ(back.load->others, 0.125);
  EXPECT_EQ(back.load->steal, 0.0625);
  ASSERT_EQ(back.rows.size(), loaded.size());
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    ASSERT_EQ(back.rows[i].load.has_value(), i != 2) << i;
    if (i == 2) continue;
    EXPECT_EQ(back.rows[i].load->others, loaded[i].load->others) << i;
    EXPECT_EQ(back.rows[i].load->steal, 0.03125) << i;
  }
  struct Case {
    const char* from;
    const char* to;
    const char* where;
  };
  for (const Case c : {Case{"\"steal\": 0.0625", "\"steal\": 1.5", "/load/steal: is 1.5"},
                       Case{"\"other_processes\": 0.125", "\"other_processes\": -0.01", "/load/other_processes: is -0.01"},
                       Case{"\"other_processes\": 0.125", "\"other_processes\": \"12%\"", "/load/other_processes: missing"},
                       Case{"\"steal\": 0.0625", "\"stolen\": 0.0625", "/load/steal: missing"},
                       Case{"\"other_processes\": 0.375", "\"other_processes\": 2", "/rows/1/load/other_processes: is 2"}}) {
    std::string bad = text;
    const std::size_t at = bad.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    bad.replace(at, std::string(c.from).size(), c.to);
    const std::string path = temp.write("bad.json", bad);
    rc::testing::expectError([&] { rc::app::readBenchJson(path); }, rc::ExitCode::kBadInput, {path + ": " + c.where}, c.to);
  }
}
