// The HTML report as a person meets it: self-contained, and in headless Chromium it loads with
// no console errors and shows its images.
#include <gtest/gtest.h>
#include <png.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/html_report.h"
#include "compare/report.h"
#include "tests/made_up_report.h"
#include "tests/run_command.h"
#include "tests/test_files.h"

namespace {

namespace fs = std::filesystem;

std::pair<int, std::string> shell(const std::string& command) {
  const rc::testing::CommandResult r = rc::testing::runCommand(command);
  return {r.exitCode, r.output};
}

std::string chromium() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (fs::exists(path)) return path;
  }
  return "";
}

// Opens `url` headless, saves a screenshot, returns Chromium's console lines.
std::string openInChromium(const std::string& url, const std::string& screenshot, const std::string& profile) {
  const auto [code, output] = shell(
      "timeout 120 " + chromium() +
      " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking"
      " --disable-component-update --disable-sync --user-data-dir=" + profile +
      " --enable-logging=stderr --v=0 --window-size=1400,1600 --screenshot=" + screenshot + " " + url);
  EXPECT_EQ(code, 0) << output;
  std::string console;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.find(":CONSOLE") != std::string::npos) console += line + "\n";
  }
  return console;
}

// A report of floor and cube, with bench results for cube shown as a chart.
std::string makeReport(const rc::testing::TempDir& dir) {
  const std::string out = dir.file("report"), bench = dir.file("bench.json");
  const auto [benchCode, benchOutput] = shell(rc::testing::rastercheckExe() + " bench cube --runs 1 -q --json " + bench);
  EXPECT_EQ(benchCode, 0) << benchOutput;
  const auto [code, output] =
      shell(rc::testing::rastercheckExe() + " check floor cube -q --report " + out + " --bench-json " + bench);
  EXPECT_EQ(code, 0) << output;
  return out;
}

TEST(HtmlReport, IsSelfContainedAndEveryImageItNamesExists) {
  rc::testing::TempDir dir;
  const std::string out = makeReport(dir);
  std::ifstream in(fs::path(out) / "index.html");
  const std::string html((std::istreambuf_iterator<char>(in)), {});
  ASSERT_FALSE(html.empty());
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_NE(html.find("all 2 scenes pass the gate"), std::string::npos);
  // Each scene shows its coverage audit.
  std::size_t audits = 0;
  for (std::size_t at = html.find("<p>coverage audit: "); at != std::string::npos; at = html.find("<p>coverage audit: ", at + 1)) ++audits;
  EXPECT_EQ(audits, 2u);
  // Every src="..." attribute. (A plain search: <regex> drew a dozen -Wmaybe-uninitialized
  // warnings from inside libstdc++ in GCC 12's sanitizer build.)
  int images = 0;
  const std::string open = "src=\"";
  for (std::size_t at = html.find(open); at != std::string::npos; at = html.find(open, at)) {
    at += open.size();
    const std::size_t end = html.find('"', at);
    ASSERT_NE(end, std::string::npos) << "unterminated src attribute";
    const std::string name = html.substr(at, end - at);
    EXPECT_TRUE(fs::exists(fs::path(out) / name)) << name;
    ++images;
    at = end;
  }
  EXPECT_EQ(images, 7);  // raster, reference and heatmap per scene, and the bench chart
  EXPECT_NE(html.find("Speed against error"), std::string::npos);
  // The bench section names the machine the figures came from, as the bench JSON has it.
  const nlohmann::json bench = nlohmann::json::parse(std::ifstream(fs::path(out).parent_path() / "bench.json"));
  const std::string cpu = bench["machine"]["cpu"];
  EXPECT_NE(html.find("Measured on: " + cpu + ", "), std::string::npos);
  // The bench rows carry their memory floor, read back from the JSON (older reports show "-").
  EXPECT_NE(html.find("<th>floor ms</th>"), std::string::npos);
  // The chart is drawn across the page and opens at full size.
  EXPECT_NE(html.find("<a href=\"bench.svg\"><img src=\"bench.svg\""), std::string::npos);
  // And the least and greatest of the rounds' own speed-ups (one run: both that round's).
  EXPECT_NE(html.find("<th>per round</th>"), std::string::npos);
  const nlohmann::json& first = bench["rows"][0];
  EXPECT_NE(html.find("<td>" + rc::formatNumber(first["speedup_min"].get<double>()) + " to " +
                      rc::formatNumber(first["speedup_max"].get<double>()) + "</td>"),
            std::string::npos);
  // Each row's frame over the default's, read back from the JSON: "-" in the default's own row,
  // and no other cell is left without its figure.
  EXPECT_NE(html.find("<th>raster ms</th><th>x default</th>"), std::string::npos);
  std::size_t dashes = 0;
  for (std::size_t at = html.find("</td><td>-</td><td>"); at != std::string::npos; at = html.find("</td><td>-</td><td>", at + 1)) {
    ++dashes;
  }
  EXPECT_EQ(dashes, 1u) << "the default's x default alone";
  for (const auto& row : bench["rows"]) {
    if (row["default"].get<bool>()) continue;
    EXPECT_NE(html.find("<td>" + rc::formatNumber(row["raster_ms"].get<double>()) + "</td><td>" +
                        rc::formatNumber(row["raster_over_default"].get<double>()) + " (" +
                        rc::formatNumber(row["raster_over_default_min"].get<double>()) + " to " +
                        rc::formatNumber(row["raster_over_default_max"].get<double>()) + ")</td>"),
              std::string::npos)
        << row["setting"];
  }
  // And how busy other work kept the machine, as bench measured it.
  ASSERT_EQ(bench.contains("load"), bool(std::ifstream("/proc/stat"))) << "a load wherever bench can read /proc/stat";
  if (bench.contains("load")) {
    const rc::app::BenchLoad load{bench["load"]["other_processes"], bench["load"]["steal"]};
    EXPECT_NE(html.find("<p class=\"settings\">Load during the run: " + rc::app::escapeMarkup(rc::app::describe(load))),
              std::string::npos);
  }
}

rc::app::ReportScene madeUpScene(const std::string& name, bool pass) {
  rc::app::ReportScene s;
  s.name = s.stem = name;
  s.triangles = 12;
  s.report = rc::testing::madeUpReport(pass);
  return s;
}

// Every scene's own verdict, reasons and figures, each in its place, and the summary over all
// of them whatever their order. Until session 39 a report that gave every scene a PASS badge,
// counted the failures from the last scene alone, showed no unexplained disagreements or the
// mean in the max column passed every test.
TEST(HtmlReport, ShowsEachScenesVerdictReasonsAndFiguresInTheirPlaces) {
  rc::testing::TempDir dir;
  for (const char* folder : {"report", "one", "two"}) fs::create_directories(dir.file(folder));
  for (const bool failFirst : {true, false}) {
    std::vector<rc::app::ReportScene> scenes = {madeUpScene("fails", false), madeUpScene("passes", true)};
    if (!failFirst) std::swap(scenes[0], scenes[1]);
    rc::app::writeHtmlReport(dir.file("report"), scenes, "settings");
    const std::string html = rc::testing::readFile(fs::path(dir.file("report")) / "index.html");
    EXPECT_NE(html.find("<span class=\"fail\">FAIL</span> 1 of 2 scenes fail the gate</p>"), std::string::npos) << html;
    const std::size_t second = html.find("<section class=\"scene\">", html.find("<section class=\"scene\">") + 1);
    ASSERT_NE(second, std::string::npos);
    const std::string failing = failFirst ? html.substr(0, second) : html.substr(second);
    const std::string passing = failFirst ? html.substr(second) : html.substr(0, second);
    EXPECT_NE(failing.find("<h2>fails <span class=\"fail\">FAIL</span></h2>"), std::string::npos) << failing;
    EXPECT_NE(passing.find("<h2>passes <span class=\"pass\">PASS</span></h2>"), std::string::npos) << passing;
    EXPECT_NE(failing.find("<ul>\n<li>bary: max error 0.5 over its bound</li>\n<li>depth: 2 NaN &lt;pixels&gt;</li>\n</ul>"),
              std::string::npos)
        << failing;
    EXPECT_EQ(failing.find("Every family is within its threshold"), std::string::npos);
    EXPECT_NE(passing.find("Every family is within its threshold"), std::string::npos);
    for (const std::string& section : {failing, passing}) {
      EXPECT_NE(section.find("<p>12 triangles, 8x4;"), std::string::npos) << section;
      EXPECT_NE(section.find("<tr><td>29 covered</td><td>19</td><td>5</td><td>3</td><td>2</td><td>0.125</td>"
                             "<td>0.0625</td></tr>"),
                std::string::npos)
          << section;
      EXPECT_NE(section.find("<p>Disagreements: 11 in the edge band (0.0055 px), 13 depth ties, 17 unexplained"),
                std::string::npos)
          << section;
      EXPECT_NE(section.find("<tr><td>bary</td><td>0.00125</td><td>0.00025</td><td>0.00035</td><td>4.5e-05</td>"
                             "<td>0.00055</td><td>0.00065</td><td>3</td><td>0.75 of bound</td><td>1</td>"
                             "<td>(6,1) 0.25 / 0.375</td></tr>"),
                std::string::npos)
          << section;
      EXPECT_NE(section.find("<tr><td>attr.uv</td><td>0.002</td><td>0.0003</td><td>0.0004</td><td>5e-05</td>"
                             "<td>0.0006</td><td>0.0007</td><td>0</td><td>0.0008 of range</td><td>0.004</td>"
                             "<td>(2,3) 1.5 / 1.5</td></tr>"),
                std::string::npos)
          << section;
    }
  }
  // One scene alone, and two that pass.
  rc::app::writeHtmlReport(dir.file("one"), {madeUpScene("fails", false)}, "settings");
  EXPECT_NE(rc::testing::readFile(fs::path(dir.file("one")) / "index.html")
                .find("<span class=\"fail\">FAIL</span> the scene fails the gate</p>"),
            std::string::npos);
  rc::app::writeHtmlReport(dir.file("two"), {madeUpScene("a", true), madeUpScene("b", true)}, "settings");
  EXPECT_NE(rc::testing::readFile(fs::path(dir.file("two")) / "index.html")
                .find("<span class=\"pass\">PASS</span> all 2 scenes pass the gate</p>"),
            std::string::npos);
}

// A bench row of the cube's default setting, as made up for the report's tests.
rc::app::BenchRow madeUpDefaultBenchRow() {
  rc::app::BenchRow row;
  row.scene = "cube";
  row.setting = "perspective-float-8bit";
  row.isDefault = true;
  row.triangles = 12;
  row.width = 64, row.height = 48, row.threads = 2;
  row.rasterMs = 0.5, row.referenceTraceMs = 2, row.speedup = 4;
  return row;
}

// Each bench row's frame over its scene's default's: the medians' ratio and each round's least
// and greatest, in that order; "-" in the default's own row. Its disagreement and one-side
// fractions follow ("-" for the second in a file from before session 49, which lacks it).
TEST(HtmlReport, ShowsEachBenchRowsFrameOverTheDefaults) {
  rc::testing::TempDir dir;
  rc::app::BenchRow def = madeUpDefaultBenchRow();
  def.overDefault = def.overDefaultMin = def.overDefaultMax = 1;
  def.disagreementFraction = 0.25, def.coverageFraction = 0.125;
  rc::app::BenchRow oneThread = def;
  oneThread.coverageFraction = -1;
  oneThread.setting = "perspective-float-8bit-1thread";
  oneThread.isDefault = false;
  oneThread.threads = 1;
  oneThread.rasterMs = 0.875, oneThread.speedup = 2;
  oneThread.overDefault = 1.75, oneThread.overDefaultMin = 1.5, oneThread.overDefaultMax = 2.25;
  const std::string out = dir.file("report");
  fs::create_directories(out);
  rc::app::writeHtmlReport(out, {madeUpScene("a", true)}, "settings",
                           rc::app::BenchResults{{def, oneThread}, std::nullopt, std::nullopt});
  const std::string html = rc::testing::readFile(fs::path(out) / "index.html");
  EXPECT_NE(html.find("<td>perspective-float-8bit (default)</td><td>2</td><td>0.5</td><td>-</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<td>perspective-float-8bit-1thread</td><td>1</td><td>0.875</td><td>1.75 (1.5 to 2.25)</td>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("<td>0.25</td><td>0.125</td><td>-</td></tr>"), std::string::npos) << html;  // other work: unmeasured
  EXPECT_NE(html.find("<td>0.25</td><td>-</td><td>-</td></tr>"), std::string::npos) << html;
}

// Bench results taken on a busy machine say so in the report, in words that stand out; an idle
// machine's load is shown without them.
TEST(HtmlReport, SaysWhenTheBenchFiguresCameFromABusyMachine) {
  rc::testing::TempDir dir;
  rc::app::BenchRow row = madeUpDefaultBenchRow();
  for (const bool busy : {true, false}) {
    const std::string out = dir.file(busy ? "busy" : "idle");
    fs::create_directories(out);
    const rc::app::BenchLoad load{busy ? 0.379 : 0.004, 0.0};
    // The row's own load (its scene's), other processes' and steal's shares together.
    row.load = rc::app::BenchLoad{busy ? 0.30 : 0.002, busy ? 0.05 : 0.001};
    rc::app::writeHtmlReport(out, {madeUpScene("a", true)}, "settings", rc::app::BenchResults{{row}, std::nullopt, load});
    const std::string html = rc::testing::readFile(fs::path(out) / "index.html");
    const std::string line = "<p class=\"settings\">Load during the run: other processes used " +
                             std::string(busy ? "37.9" : "0.4") + "% of the CPUs&#39; time, the hypervisor&#39;s other guests 0.0% (steal)";
    EXPECT_NE(html.find(line + (busy ? ": <strong>a busy machine, so slower and noisier figures than an idle one "
                                       "gives</strong></p>"
                                     : "</p>")),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("<th>disagreement</th><th>one side only</th><th>other work</th></tr>"), std::string::npos);
    EXPECT_NE(html.find(busy ? "</td><td><strong>35.0%</strong></td></tr>" : "</td><td>0.3%</td></tr>"), std::string::npos)
        << html;
  }
}

TEST(HtmlReport, LoadsInChromiumWithoutConsoleErrorsAndShowsItsImages) {
  if (chromium().empty()) GTEST_SKIP() << "Chromium is absent (Debian package chromium): the report was not opened in a browser";
  rc::testing::TempDir dir;
  const std::string out = makeReport(dir);
  const std::string shot = dir.file("report.png");
  const std::string console = openInChromium("file://" + fs::absolute(out).string() + "/index.html", shot, dir.file("profile"));
  EXPECT_EQ(console, "") << "console messages while loading the report";
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&image, shot.c_str())) << "no screenshot";
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  ASSERT_TRUE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr));
  // The page background is near white; the floor's sky and the heatmaps are near black. A page
  // whose images failed to load has almost no dark pixels.
  std::size_t dark = 0;
  for (std::size_t i = 0; i < pixels.size(); i += 3) dark += pixels[i] < 40 && pixels[i + 1] < 40 && pixels[i + 2] < 40;
  EXPECT_GT(double(dark) / double(pixels.size() / 3), 0.05) << "the screenshot shows no images";
}

TEST(HtmlReport, ConsoleErrorDetectionCatchesADeliberateError) {
  if (chromium().empty()) GTEST_SKIP() << "Chromium is absent (Debian package chromium)";
  rc::testing::TempDir dir;
  const std::string page = dir.write("bad.html", "<html><body><script>undefinedFunction();</script></body></html>");
  const std::string console = openInChromium("file://" + page, dir.file("bad.png"), dir.file("profile"));
  EXPECT_NE(console.find("undefinedFunction"), std::string::npos) << "the check above could not fail";
}

}  // namespace
