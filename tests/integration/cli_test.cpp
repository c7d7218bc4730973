// The CLI as a user meets it: exit codes, messages, and files written or not written (bench in
// bench_cli_test.cpp, compare in compare_cli_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>
#include <nlohmann/json.hpp>

#include "app/html_report.h"
#include "core/channels.h"
#include "core/exr_io.h"
#include "rasterizer/coverage_audit.h"
#include "scenes/registry.h"
#include "tests/integration/cli_run.h"
#include "tests/run_command.h"
#include "tests/test_files.h"

namespace {

using namespace rc::testing::cli;

TEST(Cli, HelpAndScenesExitZero) {
  EXPECT_EQ(run("--help").exitCode, 0);
  EXPECT_EQ(run("check --help").exitCode, 0);
  const CliRun scenes = run("scenes");
  EXPECT_EQ(scenes.exitCode, 0);
  for (const char* name : {"floor", "cube", "sphere", "blob"}) {
    EXPECT_NE(scenes.output.find(name), std::string::npos) << name;
  }
}

TEST(Cli, ScenesDescribesTheScenesGivenAsTheyWouldBeRendered) {
  const rc::testing::TempDir dir;
  const std::string obj = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n");
  const CliRun r = run("scenes cube " + obj + " --size 320x200");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const std::string& line : {std::string("cube\n"), std::string("12 triangles, 24 vertices, a closed solid"),
                                  std::string("attributes: uv (2)"), obj + "\n  mesh with a framing camera\n  2 triangles, 4 vertices\n",
                                  std::string("size=320x200")}) {
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  }
  const std::string data = rc::testing::sharedData();
  if (!data.empty()) {  // the Khronos sample places a perspective and an orthographic camera
    const CliRun cameras = run("scenes " + data + "/gltf/Cameras.gltf");
    EXPECT_EQ(cameras.exitCode, 0) << cameras.output;
    EXPECT_NE(cameras.output.find("through its cameras[0] (it places 0, 1 (orthographic))"), std::string::npos) << cameras.output;
    EXPECT_EQ(run("scenes " + data + "/gltf/Cameras.gltf --camera 1").exitCode, 3);
  }
  EXPECT_EQ(run("scenes cube --camera 0").exitCode, 2);
  const CliRun missing = run("scenes cube " + (dir.path() / "missing.obj").string());
  EXPECT_EQ(missing.exitCode, 4) << missing.output;
  EXPECT_EQ(missing.output.find("cube\n"), std::string::npos) << "nothing is printed before every scene has loaded";
}

TEST(Cli, CheckWritesRendersHeatmapsAndJsonAndPasses) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  const CliRun r = run("check floor cube --out " + (dir / "out").string() + " --json " + (dir / "r.json").string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  for (const char* file : {"floor.raster.exr", "floor.reference.exr", "floor.heatmap.exr", "cube.heatmap.exr"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  }
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "r.json"));
  EXPECT_EQ(j["verdict"], "pass");
  EXPECT_EQ(j["scenes"].size(), 2u);
}

// One scene that fails the gate fails the whole check, wherever it stands among scenes that
// pass. In affine mode floor fails (its checker bends) and depthpairs passes: its quads face
// the eye, so w is constant over each triangle and affine weights are the perspective ones.
TEST(Cli, OneFailingSceneFailsTheWholeCheckWhereverItStands) {
  const rc::testing::TempDir temp;
  const std::string json = temp.file("r.json"), junit = temp.file("j.xml");
  for (const auto& [scenes, failing] : {std::pair{"floor depthpairs", 0}, std::pair{"depthpairs floor", 1}}) {
    const CliRun r = run(std::string("check ") + scenes + " -q --mode affine --json " + json + " --junit " + junit);
    EXPECT_EQ(r.exitCode, 1) << scenes << "\n" << r.output;
    EXPECT_NE(r.output.find("2 scene(s): GATE FAILED\n"), std::string::npos) << scenes << "\n" << r.output;
    const nlohmann::json report = nlohmann::json::parse(rc::testing::readFile(json));
    EXPECT_EQ(report["verdict"], "fail") << scenes;
    ASSERT_EQ(report["scenes"].size(), 2u);
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(report["scenes"][i]["report"]["verdict"], i == failing ? "fail" : "pass") << scenes << ", scene " << i;
    }
    const std::string xml = rc::testing::readFile(junit);
    EXPECT_NE(xml.find(" tests=\"2\" failures=\"1\""), std::string::npos) << scenes << "\n" << xml;
  }
}

// check's table prints each scene's own figures, as its JSON has them. Until session 39 a table
// that printed the barycentric maximum as the p99.9, the depth p99.9 as the maximum, or the
// one-side-only fraction as the disagreement passed every test. In affine mode the sphere's
// figures tell those columns apart.
TEST(Cli, CheckTablePrintsEachScenesFiguresFromItsReport) {
  const rc::testing::TempDir temp;
  const std::string json = temp.file("r.json");
  const CliRun r = run("check cube sphere -q --mode affine --json " + json);
  ASSERT_EQ(r.exitCode, 1) << r.output;
  const nlohmann::json report = nlohmann::json::parse(rc::testing::readFile(json));
  ASSERT_EQ(report["scenes"].size(), 2u);
  for (const nlohmann::json& scene : report["scenes"]) {
    const std::string name = scene["scene"];
    const std::size_t at = r.output.find("\n" + name + " ");
    ASSERT_NE(at, std::string::npos) << name << "\n" << r.output;
    const std::vector<std::string> cells = cellsOfLine(r.output, at + 1);
    ASSERT_EQ(cells.size(), 10u) << r.output;
    const nlohmann::json& families = scene["report"]["families"];
    const std::vector<std::string> expected = {
        name,
        std::to_string(scene["triangles"].get<std::size_t>()),
        std::to_string(scene["report"]["width"].get<int>()) + "x" + std::to_string(scene["report"]["height"].get<int>()),
        scene["report"]["verdict"] == "pass" ? "PASS" : "FAIL",
        printed(families["bary"]["max"]),
        printed(families["bary"]["p999"]),
        printed(families["depth"]["max"]),
        printed(scene["report"]["disagreement_fraction"]),
        printed(scene["raster_ms"], "%.1f"),
        printed(scene["reference_ms"], "%.1f")};
    EXPECT_EQ(cells, expected) << r.output;
    if (name == "sphere") {
      EXPECT_NE(printed(families["bary"]["max"]), printed(families["bary"]["p999"]));
      EXPECT_NE(printed(families["depth"]["max"]), printed(families["depth"]["p999"]));
      EXPECT_NE(printed(scene["report"]["disagreement_fraction"]), printed(scene["report"]["coverage_fraction"]));
    }
  }
}

// Looking straight down the scene's up direction needs another up: the error says which
// options made the camera, and --up gives it.
TEST(Cli, ACameraLookingAlongTheUpDirectionTakesUp) {
  const CliRun down = run("check cube -q --eye 0,5,0 --target 0,0,0");
  EXPECT_EQ(down.exitCode, 3) << down.output;
  EXPECT_NE(down.output.find("--up"), std::string::npos) << down.output;
  EXPECT_NE(down.output.find("parallel to the view direction"), std::string::npos) << down.output;
  const CliRun withUp = run("check cube -q --eye 0,5,0 --target 0,0,0 --up 0,0,-1");
  EXPECT_EQ(withUp.exitCode, 0) << withUp.output;
  EXPECT_EQ(run("check cube -q --up 1,2").exitCode, 2);
}

TEST(Cli, AffineCheckExitsOne) {
  const CliRun r = run("check floor --mode affine");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("FAIL"), std::string::npos);
}

// A broken fill rule moves no pixel beyond the edge band, so the comparison with the reference
// passes it; the coverage audit fails it, names the first pixel, and writes its counts to the
// JSON report. The right rule passes with the centres it decided counted.
TEST(Cli, WrongFillRulesFailTheGateThroughTheCoverageAudit) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const std::string json = (temp.path() / "r.json").string();
  const CliRun right = run("check edges fans -q --json " + json);
  ASSERT_EQ(right.exitCode, 0) << right.output;
  const nlohmann::json passed = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(passed["settings"].get<std::string>().find("fill rule"), std::string::npos) << passed["settings"];
  for (const auto& scene : passed["scenes"]) {
    EXPECT_EQ(scene["fill_rule"], "top-left");
    const auto& audit = scene["coverage_audit"];
    EXPECT_GT(audit["on_edge"].get<int>(), 10) << audit;
    EXPECT_EQ(audit["not_owned"], 0) << audit;
    EXPECT_EQ(audit["lost"], 0) << audit;
    EXPECT_TRUE(audit["first_not_owned"].is_null()) << audit;
  }
  for (const auto& [rule, count, kind] : {std::tuple{"inclusive", "not_owned", "first_not_owned"},
                                          std::tuple{"exclusive", "lost", "first_lost"}}) {
    const CliRun wrong = run(std::string("check edges fans -q --fill-rule ") + rule + " --json " + json);
    EXPECT_EQ(wrong.exitCode, 1) << wrong.output;
    EXPECT_NE(wrong.output.find("- coverage audit: "), std::string::npos) << wrong.output;
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(report["verdict"], "fail");
    EXPECT_NE(report["settings"].get<std::string>().find(std::string(rule) + " fill rule (wrong on purpose)"), std::string::npos)
        << report["settings"];
    for (const auto& scene : report["scenes"]) {
      EXPECT_EQ(scene["fill_rule"], rule);
      const auto& audit = scene["coverage_audit"];
      EXPECT_GT(audit[count].get<int>(), 0) << rule << ": " << audit;
      EXPECT_GE(audit[kind]["x"].get<int>(), 0) << rule << ": " << audit;
      EXPECT_EQ(scene["report"]["verdict"], "fail") << rule;
      EXPECT_NE(scene["report"]["reasons"].dump().find("coverage audit"), std::string::npos) << rule;
    }
  }
  // The rule is recorded, and bench, which times the right one, refuses the others.
  const std::string out = (temp.path() / "e.exr").string();
  ASSERT_EQ(run("render edges --fill-rule exclusive -o " + out).exitCode, 0);
  EXPECT_EQ(rc::readExr(out).attributes.at("rastercheck.fillRule"), "exclusive");
  const CliRun bench = run("bench edges --fill-rule inclusive");
  EXPECT_EQ(bench.exitCode, 2) << bench.output;
  EXPECT_NE(bench.output.find("--fill-rule inclusive"), std::string::npos) << bench.output;
}

// check's JSON carries the audit's own figures, each under its name: those of the same audit run
// here on the same frame. Until session 39 an edge band limit written from the band itself, or
// every covered pixel counted as diagnosed, passed every test.
TEST(Cli, CheckJsonCarriesTheCoverageAuditsOwnFigures) {
  const rc::testing::TempDir temp;
  const std::string json = temp.file("r.json");
  const rc::Scene scene = rc::makeBuiltinScene("cube");
  for (const bool diagnostics : {true, false}) {
    const CliRun r = run(std::string("check cube -q --json ") + json + (diagnostics ? "" : " --no-diagnostics"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json audit = nlohmann::json::parse(rc::testing::readFile(json))["scenes"][0]["coverage_audit"];
    rc::RasterOptions options;
    options.diagnostics = diagnostics;
    const rc::CoverageAudit own = rc::auditCoverage(scene, options, rc::rasterize(scene, options));
    EXPECT_EQ(audit["covered"], own.covered);
    EXPECT_EQ(audit["on_edge"], own.onEdge);
    EXPECT_EQ(audit["diagnosed"], own.diagnosed);
    EXPECT_EQ(audit["edge_band"], own.edgeBand);
    EXPECT_EQ(audit["edge_band_limit"], own.edgeBandLimit);
    // Figures that tell the fields apart.
    EXPECT_GT(own.covered, 0u);
    EXPECT_EQ(own.diagnosed, diagnostics ? own.covered : 0u);
    EXPECT_LT(own.edgeBand, own.edgeBandLimit);
  }
}

// check's JSON carries the header's count of pixels a float frame resolved in double: those of
// the same frame rendered here (slivers: its needles; cube: none), null for a double frame.
TEST(Cli, CheckJsonCountsThePixelsAFloatFrameResolvedInDouble) {
  const rc::testing::TempDir temp;
  const std::string json = temp.file("r.json");
  const CliRun r = run("check slivers cube -q --json " + json);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json scenes = nlohmann::json::parse(rc::testing::readFile(json))["scenes"];
  for (const nlohmann::json& row : scenes) {
    const rc::Scene scene = rc::makeBuiltinScene(row["scene"].get<std::string>());
    rc::RasterOptions options;
    options.threads = 2;
    const std::string own = rc::rasterize(scene, options).attributes.at(rc::channels::header::kPromotedPixels);
    EXPECT_EQ(row["promoted_pixels"].get<std::uint64_t>(), std::stoull(own)) << row["scene"];
  }
  EXPECT_GT(scenes[0]["promoted_pixels"].get<std::uint64_t>(), 100u);
  EXPECT_EQ(scenes[1]["promoted_pixels"].get<std::uint64_t>(), 0u);
  const CliRun twice = run("check slivers -q --precision double --json " + json);
  ASSERT_EQ(twice.exitCode, 0) << twice.output;
  EXPECT_TRUE(nlohmann::json::parse(rc::testing::readFile(json))["scenes"][0]["promoted_pixels"].is_null());
}

TEST(Cli, MissingInputIsExitFour) {
  const CliRun r = run("compare /nonexistent/a.exr /nonexistent/b.exr");
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/a.exr"), std::string::npos);
}

TEST(Cli, UsageErrorsAreExitTwo) {
  for (const char* args : {"", "frobnicate", "check --no-such-flag", "check --max-bary nan",
                           "check --max-bary -1", "check --threads -1", "check --mode sideways",
                           "check no-such-scene", "check blob:tris=abc", "render floor",
                           "check --size 0x10", "check --cull front", "check --subpixel-bits 17",
                           "check --subpixel-bits 0", "check --subpixel-bits nones", "check --subpixel-bits 8.5",
                           "check --fill-rule bottom-right"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.exitCode, 2) << "rastercheck " << args << "\n" << r.output;
  }
}

// The header says what the frame did: the sphere is a closed solid, so auto culls its back
// faces unless asked not to, or unless the eye is inside it.
TEST(Cli, CullSettingIsRecordedAsWhatTheFrameDid) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  const std::string out = (dir / "s.exr").string();
  for (const auto& [args, cull] : std::vector<std::pair<std::string, std::string>>{
           {"", "back"}, {" --cull none", "none"}, {" --cull auto --eye 0,0,0 --target 0,0,-1", "none"}}) {
    const CliRun r = run("render sphere -o " + out + args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(rc::readExr(out).attributes.at("rastercheck.cull"), cull) << args;
  }
}

// Issue 4's settings, each chosen on the command line and recorded in the raster EXR's header:
// the defaults, then every one changed at once.
TEST(Cli, EveryRasterSettingIsRecordedInTheHeader) {
  const rc::testing::TempDir temp;
  const std::string out = temp.file("s.exr");
  using Header = std::map<std::string, std::string>;
  const Header defaults = {{"rastercheck.mode", "perspective"},      {"rastercheck.precision", "float"},
                           {"rastercheck.subpixelBits", "8"},        {"rastercheck.depthMapping", "inverse-w"},
                           {"rastercheck.fillRule", "top-left"},     {"rastercheck.cull", "back"},
                           {"rastercheck.renderer", "raster"},       {"rastercheck.scene", "cube"}};
  const Header changed = {{"rastercheck.mode", "affine"},            {"rastercheck.precision", "double"},
                          {"rastercheck.subpixelBits", "4"},         {"rastercheck.depthMapping", "standard"},
                          {"rastercheck.fillRule", "exclusive"},     {"rastercheck.cull", "none"},
                          {"rastercheck.kernelIsa", "sse2"},         {"rastercheck.scene", "cube"}};
  for (const auto& [args, expected] : std::vector<std::pair<std::string, Header>>{
           {"", defaults},
           {" --mode affine --precision double --subpixel-bits 4 --depth-mapping standard --fill-rule exclusive"
            " --cull none --raster-isa sse2",
            changed}}) {
    const CliRun r = run("render cube -o " + out + args);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const rc::Framebuffer fb = rc::readExr(out);
    for (const auto& [key, value] : expected) {
      ASSERT_TRUE(fb.attributes.count(key)) << key << args;
      EXPECT_EQ(fb.attributes.at(key), value) << key << args;
    }
  }
}

// --subpixel-bits none: coverage of the unsnapped triangles, recorded in the header with the
// edge band it leaves (the double raster positions' own error, far below a 16-bit grid's), and
// gated as any other setting: the affine mode still fails.
TEST(Cli, SubpixelBitsNoneIsRecordedAndGated) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const std::string out = (temp.path() / "s.exr").string();
  const CliRun r = run("render sphere --subpixel-bits None -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const rc::Framebuffer fb = rc::readExr(out);
  EXPECT_EQ(fb.attributes.at("rastercheck.subpixelBits"), "none");
  const double band = std::stod(fb.attributes.at("rastercheck.edgeBand"));
  EXPECT_GT(band, 0.0);
  EXPECT_LT(band, 1e-3 * 0.7072 * std::ldexp(1.0, -16));
  EXPECT_EQ(run("check cube slivers nearplane --subpixel-bits none -q").exitCode, 0);
  EXPECT_EQ(run("check cube slivers nearplane --subpixel-bits none --mode affine -q").exitCode, 1);
}

TEST(Cli, MeshFilesTakeCameraOverridesAndAttributeSelection) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  std::ofstream(dir / "tri.obj") << "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
  const std::string obj = (dir / "tri.obj").string();
  const CliRun ok = run("check " + obj + " --eye 0,0,4 --target 0,0,0 --fov 40 --size 64x48 --out " + (dir / "out").string());
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "tri.raster.exr"));
  const CliRun missingAttribute = run("check " + obj + " --attributes normal");
  EXPECT_EQ(missingAttribute.exitCode, 2) << missingAttribute.output;
  EXPECT_NE(missingAttribute.output.find("normal"), std::string::npos);
  EXPECT_EQ(run("check " + obj + " --eye 0,0").exitCode, 2);
  const CliRun absent = run("check " + (dir / "absent.obj").string());
  EXPECT_EQ(absent.exitCode, 4) << absent.output;
  std::ofstream(dir / "bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  const CliRun bad = run("check " + (dir / "bad.obj").string() + " --out " + (dir / "badout").string());
  EXPECT_EQ(bad.exitCode, 3) << bad.output;
  EXPECT_NE(bad.output.find("bad.obj:4"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "badout" / "bad.raster.exr"));
}

TEST(Cli, ProgressIsPlainLinesOffATerminalABarOnOneAndNothingWhenQuiet) {
  const CliRun plain = run("check cube sphere");  // stderr is a pipe here
  EXPECT_NE(plain.output.find("rastercheck: [1/4] loading cube"), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("rastercheck: [4/4] sphere"), std::string::npos) << plain.output;
  const CliRun quiet = run("check cube sphere --quiet");
  EXPECT_EQ(quiet.output.find("rastercheck: ["), std::string::npos) << quiet.output;
  EXPECT_EQ(quiet.exitCode, 0);
  // On a terminal (a pseudo-terminal from util-linux's script): a bar redrawn in place.
  if (std::system("command -v script > /dev/null 2>&1") != 0) GTEST_SKIP() << "util-linux script is absent: no terminal test";
  if (std::system("script -qec true /dev/null > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "no pseudo-terminal can be created here (/dev/pts): the terminal bar was not tested";
  }
  const std::string tty =
      rc::testing::runCommand("script -qec '" + rc::testing::rastercheckExe() + " check cube sphere' /dev/null").output;
  EXPECT_NE(tty.find("\r\033[K["), std::string::npos) << "no bar redrawn in place";
  EXPECT_EQ(tty.find("rastercheck: [1/4]"), std::string::npos) << "plain lines on a terminal";
}

// A scene named by a long path widens the scene column instead of pushing its row's figures out
// of line with the header (check and bench).
TEST(Cli, TablesStayAlignedForLongSceneNames) {
  const rc::testing::TempDir temp;
  const fs::path obj = temp.path() / "a-mesh-whose-path-is-longer-than-the-column.obj";
  std::ofstream(obj) << "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
  for (const std::string& command : {std::string("check"), std::string("bench --runs 1 -q")}) {
    const CliRun r = run(command + " " + obj.string() + " cube");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::istringstream lines(r.output);
    std::string header;
    std::vector<std::string> rows;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("scene ", 0) == 0) header = line;
      if (line.rfind(obj.string() + " ", 0) == 0 || line.rfind("cube ", 0) == 0) rows.push_back(line);
    }
    ASSERT_FALSE(header.empty()) << r.output;
    ASSERT_GE(rows.size(), 2u) << r.output;
    // The second column ends at the same place in every line: its header right-aligned over
    // the triangle counts (check), or left-aligned over the settings (bench).
    const bool check = command == "check";
    const std::size_t column = check ? header.find("triangles") + std::string("triangles").size() : header.find("setting");
    for (const std::string& row : rows) {
      if (check) {
        EXPECT_NE(row[column - 1], ' ') << row << "\n" << header;
        EXPECT_EQ(row[column], ' ') << row << "\n" << header;
      } else {
        EXPECT_EQ(row[column - 1], ' ') << row << "\n" << header;
        EXPECT_TRUE(row.compare(column, 11, "perspective") == 0 || row.compare(column, 6, "affine") == 0)
            << row << "\n" << header;
      }
    }
  }
}

// A camera that misses the mesh renders two empty images that agree everywhere: the gate
// fails, saying nothing was compared, unless --allow-empty lets it pass.
TEST(Cli, ACheckThatSeesNothingFailsUnlessAllowed) {
  const CliRun missed = run("check cube --eye 0,0,5 --target 0,0,10");
  EXPECT_EQ(missed.exitCode, 1) << missed.output;
  EXPECT_NE(missed.output.find("neither image covers a pixel, so nothing was compared"), std::string::npos)
      << missed.output;
  const rc::testing::TempDir temp;
  const std::string json = (temp.path() / "c.json").string();
  const CliRun allowed = run("check cube --eye 0,0,5 --target 0,0,10 --allow-empty --json " + json);
  EXPECT_EQ(allowed.exitCode, 0) << allowed.output;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(report["scenes"][0]["report"]["thresholds"]["allow_empty"], true);
  EXPECT_EQ(report["scenes"][0]["report"]["pixels"]["covered_either"], 0);
}

// A Linux file name may be any bytes; JSON, SVG and HTML must be UTF-8. A scene file whose
// name is not gets U+FFFD for its bad bytes there, instead of an internal error at the end.
TEST(Cli, ASceneNamedInBytesThatAreNotUtf8IsReportedWithReplacementCharacters) {
  const rc::testing::TempDir temp;
  const fs::path obj = temp.path() / "bad\xFFname.obj";
  std::ofstream(obj) << "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
  const std::string json = (temp.path() / "c.json").string(), bench = (temp.path() / "b.json").string(),
                    svg = (temp.path() / "b.svg").string(), report = (temp.path() / "report").string();
  const CliRun check = run("check '" + obj.string() + "' -q --json " + json + " --report " + report);
  ASSERT_EQ(check.exitCode, 0) << check.output;
  const CliRun benched = run("bench '" + obj.string() + "' --runs 1 -q --json " + bench + " --chart " + svg);
  ASSERT_EQ(benched.exitCode, 0) << benched.output;
  const std::string expected = (temp.path() / "bad\xEF\xBF\xBDname.obj").string();
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(json))["scenes"][0]["scene"], expected);
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(bench))["rows"][0]["scene"], expected);
  for (const std::string& file : {svg, report + "/index.html"}) {
    const std::string text = rc::testing::readFile(file);
    EXPECT_NE(text.find("bad\xEF\xBF\xBDname.obj"), std::string::npos) << file;
    EXPECT_EQ(text.find('\xFF'), std::string::npos) << file;
  }
}

// check --junit: a test case per scene for CI's test reports, a failure with the gate's reasons
// where the scene failed, names escaped.
TEST(Cli, CheckWritesJUnitXmlWithACasePerScene) {
  const rc::testing::TempDir temp;
  const auto text = [](const fs::path& path) { return rc::testing::readFile(path); };
  const auto count = rc::testing::occurrences;
  const fs::path obj = temp.path() / "a&b<c>.obj";
  std::ofstream(obj) << "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
  const fs::path failing = temp.path() / "failing.xml", passing = temp.path() / "passing.xml";
  const fs::path json = temp.path() / "failing.json";
  const CliRun affine = run("check cube floor --mode affine -q --junit " + failing.string() + " --json " + json.string());
  EXPECT_EQ(affine.exitCode, 1) << affine.output;
  const std::string f = text(failing);
  // Each case's failure lists every reason, and its output gives the scene's own figures, as the
  // JSON has them (until session 39 the first reason alone, or the maximum as the p99.9, passed).
  const nlohmann::json scenes = nlohmann::json::parse(text(json))["scenes"];
  ASSERT_EQ(scenes.size(), 2u);
  for (const nlohmann::json& scene : scenes) {
    const nlohmann::json& r = scene["report"];
    std::string reasons;
    for (const std::string reason : r["reasons"]) reasons += reason + "\n";
    EXPECT_GE(r["reasons"].size(), 2u);
    EXPECT_NE(f.find("\">" + rc::app::escapeMarkup(reasons) + "</failure>"), std::string::npos) << reasons << "\n" << f;
    const std::string summary = std::to_string(scene["triangles"].get<std::size_t>()) + " triangles, " +
                                std::to_string(r["width"].get<int>()) + "x" + std::to_string(r["height"].get<int>()) +
                                ": bary max " + printed(r["families"]["bary"]["max"]) + ", p99.9 " +
                                printed(r["families"]["bary"]["p999"]) + "; depth max " +
                                printed(r["families"]["depth"]["max"]) + "; disagreement " +
                                printed(r["disagreement_fraction"]) + "; raster ";
    EXPECT_NE(f.find("<system-out>" + summary), std::string::npos) << summary << "\n" << f;
  }
  EXPECT_EQ(f.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"rastercheck check\" tests=\"2\" failures=\"2\"", 0), 0u) << f;
  EXPECT_EQ(count(f, "<testcase "), 2);
  EXPECT_EQ(count(f, "<failure "), 2);
  EXPECT_NE(f.find("<testcase classname=\"rastercheck.check\" name=\"cube\""), std::string::npos) << f;
  EXPECT_NE(f.find("message=\"bary: error reaches"), std::string::npos) << f;
  EXPECT_NE(f.find("property name=\"settings\" value=\"rasterizer: affine"), std::string::npos) << f;
  EXPECT_TRUE(f.ends_with("  </testsuite>\n</testsuites>\n")) << f;
  const CliRun fine = run("check cube '" + obj.string() + "' -q --junit " + passing.string());
  EXPECT_EQ(fine.exitCode, 0) << fine.output;
  const std::string p = text(passing);
  EXPECT_NE(p.find("tests=\"2\" failures=\"0\""), std::string::npos) << p;
  EXPECT_EQ(count(p, "<failure"), 0);
  EXPECT_NE(p.find("a&amp;b&lt;c&gt;.obj"), std::string::npos) << p;
  EXPECT_EQ(p.find("a&b<c>"), std::string::npos) << p;
  EXPECT_EQ(count(p, "<system-out>"), 2);
  // An XML report by any other name is refused before anything runs.
  EXPECT_EQ(run("check cube --junit " + (temp.path() / "r.json").string()).exitCode, 2);
}

// export: the hard cases as glTF files, which check reads back (with their exact cameras, so
// the same figures) and another reader, gltfpack, accepts; bad requests are refused before any
// file or folder appears.
TEST(Cli, ExportWritesScenesAsGltfThatCheckAndOtherToolsRead) {
  const rc::testing::TempDir temp;
  const std::string dir = (temp.path() / "exported").string();
  const CliRun exported = run("export hard --out " + dir + " --format glb");
  ASSERT_EQ(exported.exitCode, 0) << exported.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), std::ptrdiff_t(rc::hardCaseSpecs().size()));
  EXPECT_NE(exported.output.find("attributes: 48 triangles, 4 attributes, 160x120 -> " + dir + "/attributes.glb"), std::string::npos)
      << exported.output;
  const std::string single = (temp.path() / "floor.gltf").string();
  ASSERT_EQ(run("export floor -o " + single).exitCode, 0);
  EXPECT_EQ(rc::testing::readFile(dir + "/edges.glb").substr(0, 4), "glTF");

  // The same figures as the built-in scenes: the same mesh under the same camera.
  const CliRun builtin = run("check edges attributes floor -q");
  const CliRun files = run("check " + dir + "/edges.glb " + dir + "/attributes.glb " + single + " -q");
  ASSERT_EQ(files.exitCode, 0) << files.output;
  for (const char* name : {"edges", "attributes", "floor"}) {
    const std::size_t a = builtin.output.find(std::string("\n") + name + " "), b = files.output.find(std::string("/") + name + ".gl");
    ASSERT_NE(a, std::string::npos) << builtin.output;
    ASSERT_NE(b, std::string::npos) << files.output;
    // triangles, size, verdict and the four error figures (the two times differ)
    auto columns = [](const std::string& text, std::size_t at) {
      std::istringstream line(text.substr(at, text.find('\n', at + 1) - at));
      std::string scene, word, kept;
      line >> scene;
      for (int i = 0; i < 7 && line >> word; ++i) kept += word + " ";
      return kept;
    };
    EXPECT_EQ(columns(files.output, b), columns(builtin.output, a + 1)) << name;
  }
  if (rc::testing::runCommand("gltfpack -h").output.find("gltfpack") != std::string::npos) {
    const rc::testing::CommandResult packed =
        rc::testing::runCommand("gltfpack -noq -i " + dir + "/attributes.glb -o " + (temp.path() / "re.glb").string());
    EXPECT_EQ(packed.exitCode, 0) << packed.output;
  }

  const std::string fresh = (temp.path() / "fresh").string();
  for (const auto& [args, message] :
       {std::pair{"export cube floor -o " + fresh + "/x.gltf", std::string("-o writes one scene, but 2 are given")},
        {"export cube -o " + fresh + "/x.obj", "name a .gltf or .glb file"},
        {"export cube", "give -o FILE (one scene) or --out DIR"},
        {"export cube nosuch --out " + fresh, "nosuch"}}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(fresh)) << args;
  }
}

}  // namespace
