// bench's chart: the Pareto front, label placement, the SVG and the PNG drawn from crafted rows,
// and the JSON it is drawn from read back (the sweep and its figures in bench_sweep_test.cpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/bench.h"
#include "app/bench_files.h"
#include "app/bench_chart.h"
#include "core/error.h"
#include "tests/test_files.h"

namespace {

using rc::app::BenchRow;
namespace chart = rc::app::chart;

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
