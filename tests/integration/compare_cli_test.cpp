// `rastercheck compare` as a user meets it: exit codes, messages, codecs, thresholds, and an
// image from another renderer judged against the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <ImfCompression.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <nlohmann/json.hpp>

#include "core/exr_io.h"
#include "tests/integration/cli_run.h"
#include "tests/run_command.h"
#include "tests/test_files.h"

namespace {

using namespace rc::testing::cli;

TEST(Cli, CompareOfAFileWithItselfReportsZeroError) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  const std::string exr = (dir / "floor.exr").string();
  ASSERT_EQ(run("render floor --backend raster -o " + exr).exitCode, 0);
  const CliRun r = run("compare " + exr + " " + exr + " --json " + (dir / "self.json").string() +
                    " --heatmap " + (dir / "heat.exr").string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "self.json"));
  EXPECT_EQ(j["families"]["bary"]["max"], 0.0);
  EXPECT_EQ(j["families"]["depth"]["max"], 0.0);
  EXPECT_EQ(j["pixels"]["different_triangle"], 0);
  EXPECT_TRUE(fs::exists(dir / "heat.exr"));
}

// Every command that writes an EXR takes --exr-compression; each file says the codec it was
// written with, and every codec reads back as the same image (the same figures).
TEST(Cli, ExrCompressionIsTheOneAskedForAndEveryCodecComparesTheSame) {
  const rc::testing::TempDir temp;
  const fs::path& dir = temp.path();
  const auto codecOf = [](const fs::path& path) { return Imf::InputFile(path.c_str()).header().compression(); };
  const std::string ref = (dir / "ref.exr").string();
  ASSERT_EQ(run("render floor --backend reference -o " + ref).exitCode, 0);
  EXPECT_EQ(codecOf(ref), Imf::ZIP_COMPRESSION) << "the default";
  std::string baseline;
  for (const auto& [name, codec] : {std::pair{"zip", Imf::ZIP_COMPRESSION}, std::pair{"piz", Imf::PIZ_COMPRESSION},
                                    std::pair{"zips", Imf::ZIPS_COMPRESSION}, std::pair{"rle", Imf::RLE_COMPRESSION},
                                    std::pair{"none", Imf::NO_COMPRESSION}}) {
    SCOPED_TRACE(name);
    const fs::path raster = dir / (std::string(name) + ".exr"), heat = dir / (std::string(name) + ".heat.exr");
    const fs::path out = dir / name;
    ASSERT_EQ(run("render floor --exr-compression " + std::string(name) + " -o " + raster.string()).exitCode, 0);
    EXPECT_EQ(codecOf(raster), codec);
    const CliRun r = run("compare " + raster.string() + " " + ref + " --threads 1 --heatmap " + heat.string() +
                         " --exr-compression " + name);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(codecOf(heat), codec);
    if (baseline.empty()) baseline = r.output.substr(r.output.find("pixels"));
    EXPECT_EQ(r.output.substr(r.output.find("pixels")), baseline) << "the same figures whatever the codec";
    ASSERT_EQ(run("check floor -q --out " + out.string() + " --exr-compression " + name).exitCode, 0);
    for (const char* file : {"floor.raster.exr", "floor.reference.exr", "floor.heatmap.exr"}) {
      EXPECT_EQ(codecOf(out / file), codec) << file;
    }
  }
  const CliRun bad = run("render floor --exr-compression dwaa -o " + (dir / "lossy.exr").string());
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("zip|piz|zips|rle|none"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "lossy.exr"));
}

TEST(Cli, TruncatedExrIsExitThreeWithTheFileNamedAndNoOutput) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  const std::string exr = (dir / "cube.exr").string(), cut = (dir / "cut.exr").string();
  ASSERT_EQ(run("render cube -o " + exr).exitCode, 0);
  const std::uintmax_t size = fs::file_size(exr);
  fs::copy_file(exr, cut);
  fs::resize_file(cut, size / 2);
  const CliRun r = run("compare " + cut + " " + exr + " --json " + (dir / "r.json").string());
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find(cut), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "r.json"));
}

TEST(Cli, MismatchedSizesAndMissingChannelsAreExitThree) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string(), c = (dir / "c.exr").string();
  ASSERT_EQ(run("render cube -o " + a + " --size 64x48").exitCode, 0);
  ASSERT_EQ(run("render cube -o " + b + " --size 64x64").exitCode, 0);
  // Through the cube's camera, so that only its channels differ: it has attr.normal.
  ASSERT_EQ(run("render sphere -o " + c + " --size 64x48 --eye 2.6,2.2,3.4").exitCode, 0);
  const std::string d = (dir / "d.exr").string();
  ASSERT_EQ(run("render cube -o " + d + " --size 64x48 --eye 2.6,2.2,3.5 --backend reference").exitCode, 0);
  const CliRun sizes = run("compare " + a + " " + b);
  EXPECT_EQ(sizes.exitCode, 3) << sizes.output;
  EXPECT_NE(sizes.output.find("differs"), std::string::npos) << sizes.output;
  const CliRun channels = run("compare " + a + " " + c);
  EXPECT_EQ(channels.exitCode, 3) << channels.output;
  EXPECT_NE(channels.output.find("attr.normal"), std::string::npos) << channels.output;
  // The camera moved by 0.1: every pixel differs, which is the camera's doing, not a bound's.
  const CliRun cameras = run("compare " + a + " " + d + " --json " + (dir / "r.json").string());
  EXPECT_EQ(cameras.exitCode, 3) << cameras.output;
  EXPECT_NE(cameras.output.find("the images were rendered through different cameras"), std::string::npos) << cameras.output;
  EXPECT_FALSE(fs::exists(dir / "r.json"));
}

// compare --junit: one test case, named by the test image, with the reference as a property.
TEST(Cli, CompareWritesJUnitXmlWithOneCase) {
  const rc::testing::TempDir temp;
  const std::string raster = (temp.path() / "cube.raster.exr").string(), affine = (temp.path() / "cube.affine.exr").string(),
                    reference = (temp.path() / "cube.reference.exr").string();
  ASSERT_EQ(run("render cube --backend raster -o " + raster).exitCode, 0);
  ASSERT_EQ(run("render cube --backend raster --mode affine -o " + affine).exitCode, 0);
  ASSERT_EQ(run("render cube --backend reference -o " + reference).exitCode, 0);
  const auto junit = [&](const std::string& test, int expectedExit) {
    const fs::path xml = temp.path() / "compare.xml";
    const CliRun r = run("compare " + test + " " + reference + " --junit " + xml.string());
    EXPECT_EQ(r.exitCode, expectedExit) << r.output;
    return rc::testing::readFile(xml);
  };
  const std::string pass = junit(raster, 0);
  EXPECT_NE(pass.find("<testsuites name=\"rastercheck compare\" tests=\"1\" failures=\"0\""), std::string::npos) << pass;
  EXPECT_NE(pass.find("<property name=\"reference\" value=\"" + reference + "\"/>"), std::string::npos) << pass;
  EXPECT_NE(pass.find("<testcase classname=\"rastercheck.compare\" name=\"" + raster + "\""), std::string::npos) << pass;
  EXPECT_NE(pass.find("<system-out>640x480: bary max "), std::string::npos) << pass;
  EXPECT_EQ(pass.find("<failure"), std::string::npos) << pass;
  const std::string fail = junit(affine, 1);
  EXPECT_NE(fail.find("tests=\"1\" failures=\"1\""), std::string::npos) << fail;
  EXPECT_NE(fail.find("<failure type=\"accuracy gate\" message=\"bary: error reaches"), std::string::npos) << fail;
}

// docs/your-renderer.md, step by step, with rastercheck's rasterizer standing in for another
// renderer: an image that carries only what another renderer knows (no diagnostics, no
// preview) passes on the fixed thresholds; an affine one and one with its rows upside down fail.
TEST(Cli, AnotherRenderersImageIsJudgedAgainstTheReference) {
  const rc::testing::TempDir temp;
  const fs::path& dir = temp.path();
  const std::string scene = (dir / "sphere.glb").string(), ref = (dir / "sphere.reference.exr").string();
  ASSERT_EQ(run("export sphere -o " + scene).exitCode, 0);
  const CliRun described = run("scenes " + scene);
  EXPECT_NE(described.output.find("attributes: normal (3), uv (2)"), std::string::npos) << described.output;
  EXPECT_NE(described.output.find("camera: eye=(0,0.80000000000000004,2.7999999999999998) target=(0,0,0)"), std::string::npos)
      << described.output;
  ASSERT_EQ(run("render " + scene + " --backend reference -o " + ref).exitCode, 0);
  // What another renderer writes: the ids, barycentrics, depth and attributes, rows from the top.
  const auto theirs = [&](const std::string& options, bool flipRows) {
    const std::string raw = (dir / "raw.exr").string(), out = (dir / "yours.exr").string();
    EXPECT_EQ(run("render " + scene + " --no-diagnostics " + options + " -o " + raw).exitCode, 0);
    const rc::Framebuffer full = rc::readExr(raw);
    rc::Framebuffer kept(full.width(), full.height());
    const int w = full.width(), h = full.height();
    for (const rc::Channel& c : full.channels()) {
      if (c.name == "R" || c.name == "G" || c.name == "B") continue;
      EXPECT_TRUE(c.name.rfind("bound.", 0) != 0 && c.name != "edge.dist" && c.name != "depth.tie") << c.name;
      const auto row = [&](int y) { return std::size_t(flipRows ? h - 1 - y : y) * std::size_t(w); };
      if (c.type == rc::ChannelType::kUint) {
        std::uint32_t* to = kept.addUint(c.name);
        for (int y = 0; y < h; ++y) std::copy_n(&c.uints[row(y)], w, to + std::size_t(y) * w);
      } else {
        float* to = kept.addFloat(c.name);
        for (int y = 0; y < h; ++y) std::copy_n(&c.floats[row(y)], w, to + std::size_t(y) * w);
      }
    }
    rc::writeExr(kept, out);
    return run("compare " + out + " " + ref);
  };
  const CliRun good = theirs("", false);
  EXPECT_EQ(good.exitCode, 0) << good.output;
  EXPECT_NE(good.output.find("0.0002"), std::string::npos) << "the fixed barycentric limit gates\n" << good.output;
  const CliRun affine = theirs("--mode affine", false);
  EXPECT_EQ(affine.exitCode, 1) << affine.output;
  EXPECT_NE(affine.output.find("bary: max error"), std::string::npos) << affine.output;
  const CliRun flipped = theirs("", true);
  EXPECT_EQ(flipped.exitCode, 1) << flipped.output;
  EXPECT_NE(flipped.output.find("different triangle (depth ties left out) at"), std::string::npos) << flipped.output;
  EXPECT_NE(flipped.output.find("disagreements away from every edge of both images' ids and not a depth tie"),
            std::string::npos)
      << flipped.output;

  // An image with fewer attributes than the reference: refused with the way out, which works.
  const std::string uv = (dir / "uv.exr").string(), heat = (dir / "heat.exr").string();
  ASSERT_EQ(run("render " + scene + " --attributes uv -o " + uv).exitCode, 0);
  const CliRun refused = run("compare " + uv + " " + ref + " --heatmap " + heat);
  EXPECT_EQ(refused.exitCode, 3) << refused.output;
  EXPECT_NE(refused.output.find("channel attr.normal.x: missing (present in " + ref + "; --attributes compares only those named)"),
            std::string::npos)
      << refused.output;
  EXPECT_EQ(run("compare " + uv + " " + ref + " --attributes uv").exitCode, 0);
  const CliRun typo = run("compare " + uv + " " + ref + " --attributes nromal --heatmap " + heat);
  EXPECT_EQ(typo.exitCode, 2) << typo.output;
  EXPECT_NE(typo.output.find("(they carry normal, uv)"), std::string::npos) << typo.output;
  EXPECT_FALSE(fs::exists(heat));
}

// --max-attr as a user gives it: LIMIT for every attribute, NAME=LIMIT for one, repeated or
// comma-separated; a name the scene or the images do not carry is refused before any work.
TEST(Cli, MaxAttrGivesEveryAttributeOrOneByNameItsLimit) {
  const rc::testing::TempDir temp;
  const fs::path& dir = temp.path();
  const std::string test = (dir / "t.exr").string(), ref = (dir / "r.exr").string(), json = (dir / "c.json").string();
  ASSERT_EQ(run("render sphere --no-diagnostics -o " + test).exitCode, 0);
  ASSERT_EQ(run("render sphere --backend reference -o " + ref).exitCode, 0);
  const std::string pair = "compare " + test + " " + ref + " ";
  ASSERT_EQ(run(pair).exitCode, 0) << "the float rasterizer's attributes are within the default limit";

  const CliRun everyOne = run(pair + "--max-attr 1e-9");
  EXPECT_EQ(everyOne.exitCode, 1) << everyOne.output;
  for (const char* family : {"attr.normal", "attr.uv"}) {
    EXPECT_NE(everyOne.output.find(std::string(family) + ": max error "), std::string::npos) << everyOne.output;
  }
  EXPECT_NE(everyOne.output.find(" of range exceeds 1e-09"), std::string::npos) << "not 0.000000\n" << everyOne.output;

  const CliRun normalOnly = run(pair + "--max-attr normal=1e-9 --json " + json);
  EXPECT_EQ(normalOnly.exitCode, 1) << normalOnly.output;
  EXPECT_NE(normalOnly.output.find("attr.normal: max error "), std::string::npos) << normalOnly.output;
  EXPECT_EQ(normalOnly.output.find("attr.uv: max error "), std::string::npos) << normalOnly.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(j["thresholds"]["attribute_by_name"], (nlohmann::json{{"normal", 1e-9}}));
  EXPECT_EQ(j["families"]["attr.normal"]["threshold"], 1e-9);
  EXPECT_EQ(j["families"]["attr.uv"]["threshold"], 1e-4);

  EXPECT_EQ(run(pair + "--max-attr 1e-9,uv=1,normal=1").exitCode, 0);
  EXPECT_EQ(run(pair + "--max-attr 1e-9 --max-attr uv=1 --max-attr normal=1").exitCode, 0);
  EXPECT_EQ(run(pair + "--max-attr 1e-9,uv=1").exitCode, 1);

  const std::string heat = (dir / "heat.exr").string();
  const CliRun typo = run(pair + "--max-attr nromal=1 --heatmap " + heat);
  EXPECT_EQ(typo.exitCode, 2) << typo.output;
  EXPECT_NE(typo.output.find("--max-attr nromal: neither " + test + " nor " + ref + " carries it (they carry normal, uv)"),
            std::string::npos)
      << typo.output;
  EXPECT_FALSE(fs::exists(heat));

  // check refuses before it renders anything.
  const CliRun notCarried = run("check sphere floor --max-attr normal=1 --json " + json);
  EXPECT_EQ(notCarried.exitCode, 2) << notCarried.output;
  EXPECT_NE(notCarried.output.find("floor: --max-attr names 'normal', which the scene does not carry (it has: uv)"),
            std::string::npos)
      << notCarried.output;
  EXPECT_EQ(notCarried.output.find("PASS"), std::string::npos) << notCarried.output;
  const CliRun leftOut = run("check sphere --attributes uv --max-attr normal=1");
  EXPECT_EQ(leftOut.exitCode, 2) << leftOut.output;
  EXPECT_NE(leftOut.output.find("sphere: --max-attr names 'normal', which --attributes leaves out"), std::string::npos)
      << leftOut.output;
  const CliRun gated = run("check sphere cube --no-diagnostics --max-attr uv=1e-9 -q");
  EXPECT_EQ(gated.exitCode, 1) << gated.output;
  EXPECT_NE(gated.output.find("attr.uv: max error"), std::string::npos) << gated.output;
  EXPECT_EQ(gated.output.find("attr.normal: max error"), std::string::npos) << gated.output;
}


// A fixed limit the user gives that gates nothing is said on stderr: the images carry the bound
// channels, which gate instead, or no attribute is compared; a limit that gates says nothing.
TEST(Cli, ALimitThatGatesNothingIsNoted) {
  const rc::testing::TempDir temp;
  const fs::path& dir = temp.path();
  const std::string full = (dir / "full.exr").string(), bare = (dir / "bare.exr").string(),
                    ref = (dir / "r.exr").string();
  ASSERT_EQ(run("render sphere -o " + full).exitCode, 0);
  ASSERT_EQ(run("render sphere --no-diagnostics -o " + bare).exitCode, 0);
  ASSERT_EQ(run("render sphere --backend reference -o " + ref).exitCode, 0);
  const std::string note = "rastercheck: note: ";
  const CliRun bounded = run("compare " + full + " " + ref + " --max-bary 0 --max-coverage 1");
  EXPECT_EQ(bounded.exitCode, 0) << bounded.output;
  EXPECT_NE(bounded.output.find(note + "--max-bary, --max-coverage gated nothing: both images carry the bound channels"),
            std::string::npos)
      << bounded.output;
  const CliRun applied = run("compare " + bare + " " + ref + " --max-bary 1 --max-attr uv=1 --max-coverage 1");
  EXPECT_EQ(applied.exitCode, 0) << applied.output;
  EXPECT_EQ(applied.output.find(note), std::string::npos) << applied.output;
  const CliRun defaults = run("compare " + full + " " + ref);
  EXPECT_EQ(defaults.output.find(note), std::string::npos) << "nothing was given\n" << defaults.output;

  const CliRun check = run("check sphere cube --max-depth 1 -q");
  EXPECT_EQ(check.exitCode, 0) << check.output;
  EXPECT_NE(check.output.find(note + "--max-depth gated nothing"), std::string::npos) << check.output;
  const CliRun checkBare = run("check sphere cube --max-depth 1 -q --no-diagnostics");
  EXPECT_EQ(checkBare.exitCode, 0) << checkBare.output;
  EXPECT_EQ(checkBare.output.find(note), std::string::npos) << checkBare.output;

  // Images without attributes: --max-attr has nothing to gate.
  for (const std::string& path : {bare, ref}) {
    const rc::Framebuffer all = rc::readExr(path);
    rc::Framebuffer kept(all.width(), all.height());
    for (const rc::Channel& c : all.channels()) {
      if (c.name.rfind("attr.", 0) == 0 || c.name.rfind("bound.", 0) == 0 || c.name == "edge.dist") continue;
      if (c.type == rc::ChannelType::kUint) {
        std::copy(c.uints.begin(), c.uints.end(), kept.addUint(c.name));
      } else {
        std::copy(c.floats.begin(), c.floats.end(), kept.addFloat(c.name));
      }
    }
    rc::writeExr(kept, path);
  }
  const CliRun noAttribute = run("compare " + bare + " " + ref + " --max-attr 1e-4 --max-bary 1");
  EXPECT_EQ(noAttribute.exitCode, 0) << noAttribute.output;
  EXPECT_NE(noAttribute.output.find(note + "--max-attr gated nothing: no attribute was compared"), std::string::npos)
      << noAttribute.output;
  EXPECT_EQ(noAttribute.output.find("--max-bary"), std::string::npos) << noAttribute.output;
}


// --warn-*: printed, in the JSON, the JUnit output and the HTML report, and never a failure.
TEST(Cli, WarningLimitsArePrintedAndNeverFail) {
  const rc::testing::TempDir temp;
  const fs::path& dir = temp.path();
  const std::string full = (dir / "full.exr").string(), ref = (dir / "r.exr").string();
  ASSERT_EQ(run("render sphere -o " + full).exitCode, 0);
  ASSERT_EQ(run("render sphere --backend reference -o " + ref).exitCode, 0);
  const CliRun compared = run("compare " + full + " " + ref + " --warn-bary 0 --warn-attr 1,normal=0");
  EXPECT_EQ(compared.exitCode, 0) << compared.output;
  EXPECT_NE(compared.output.find("verdict: PASS\nwarning: bary: max error "), std::string::npos) << compared.output;
  EXPECT_NE(compared.output.find("warning: attr.normal: max error "), std::string::npos) << compared.output;
  EXPECT_EQ(compared.output.find("warning: attr.uv"), std::string::npos) << compared.output;
  EXPECT_EQ(run("compare " + full + " " + ref + " --warn-bary 1").output.find("warning:"), std::string::npos);
  // The sphere's two renders disagree on the triangle at a few edge pixels.
  const CliRun disagreeing = run("compare " + full + " " + ref + " --warn-disagreement 0");
  EXPECT_EQ(disagreeing.exitCode, 0) << disagreeing.output;
  EXPECT_NE(disagreeing.output.find("warning: different triangle at "), std::string::npos) << disagreeing.output;
  EXPECT_NE(disagreeing.output.find(" of covered pixels, warning limit 0\n"), std::string::npos) << disagreeing.output;
  EXPECT_EQ(run("compare " + full + " " + ref + " --warn-disagreement 0.5").output.find("warning:"), std::string::npos);

  const std::string junit = (dir / "j.xml").string(), report = (dir / "report").string();
  const CliRun checked = run("check sphere cube --warn-depth 0 -q --junit " + junit + " --report " + report);
  EXPECT_EQ(checked.exitCode, 0) << checked.output;
  EXPECT_NE(checked.output.find("    warning: depth: max error "), std::string::npos) << checked.output;
  EXPECT_NE(checked.output.find("2 scene(s): all pass; 2 with warnings\n"), std::string::npos) << checked.output;
  const std::string xml = rc::testing::readFile(junit), html = rc::testing::readFile((fs::path(report) / "index.html").string());
  EXPECT_EQ(xml.find("<failure"), std::string::npos) << xml;
  EXPECT_NE(xml.find("\nwarning: depth: max error "), std::string::npos) << xml;
  EXPECT_NE(html.find("<li>warning: depth: max error "), std::string::npos);
  EXPECT_NE(html.find("all 2 scenes pass the gate; 2 with warnings</p>"), std::string::npos);
  const CliRun typo = run("check sphere cube --warn-attr normal=1 -q");
  EXPECT_EQ(typo.exitCode, 2) << typo.output;
  EXPECT_NE(typo.output.find("cube: --warn-attr names 'normal', which the scene does not carry (it has: uv)"),
            std::string::npos)
      << typo.output;
}

// --baseline: a run held to an earlier run's report. The same run has nothing to say; a
// coarser snapping, which the gate passes, grows the disagreements twentyfold and is warned of.
TEST(Cli, BaselineWarnsOfFiguresThatGrew) {
  const rc::testing::TempDir temp;
  const std::string base = temp.file("base.json"), now = temp.file("now.json"), junit = temp.file("j.xml");
  ASSERT_EQ(run("check cube sphere -q --json " + base).exitCode, 0);
  const CliRun same = run("check cube sphere -q --baseline " + base + " --baseline-factor 1");
  EXPECT_EQ(same.exitCode, 0) << same.output;
  EXPECT_EQ(same.output.find("warning"), std::string::npos) << same.output;

  const CliRun coarse = run("check cube sphere floor -q --subpixel-bits 4 --baseline " + base + " --json " + now +
                            " --junit " + junit);
  EXPECT_EQ(coarse.exitCode, 0) << coarse.output;
  EXPECT_NE(coarse.output.find("    warning: different triangle at 0.0032 of covered pixels, 20.9x the baseline's 0.000153\n"),
            std::string::npos)
      << coarse.output;
  EXPECT_NE(coarse.output.find("    warning: not in the baseline " + base + ": not held to it\n"), std::string::npos)
      << coarse.output;
  EXPECT_NE(coarse.output.find("3 scene(s): all pass; 3 with warnings\n"), std::string::npos) << coarse.output;
  const nlohmann::json report = nlohmann::json::parse(rc::testing::readFile(now));
  EXPECT_EQ(report["verdict"], "pass");
  EXPECT_EQ(report["scenes"][1]["report"]["baseline"], (nlohmann::json{{"file", base}, {"factor", 2.0}}));
  EXPECT_GE(report["scenes"][1]["report"]["warnings"].size(), 1u);
  EXPECT_NE(rc::testing::readFile(junit).find("\nwarning: different triangle at "), std::string::npos);
  // --fail-on-warnings makes them the gate's reasons: exit 1, a JUnit failure per scene warned.
  const CliRun strict = run("check cube sphere -q --subpixel-bits 4 --fail-on-warnings --baseline " + base + " --junit " + junit);
  EXPECT_EQ(strict.exitCode, 1) << strict.output;
  EXPECT_NE(strict.output.find("    - different triangle at 0.0032 of covered pixels, 20.9x the baseline's 0.000153\n"),
            std::string::npos)
      << strict.output;
  EXPECT_EQ(rc::testing::occurrences(rc::testing::readFile(junit), "<failure "), 2);
  const std::string folder = temp.file("report");
  EXPECT_EQ(run("check cube -q --subpixel-bits 4 --fail-on-warnings --baseline " + base + " --report " + folder).exitCode, 1);
  const std::string html = rc::testing::readFile(fs::path(folder) / "index.html");
  EXPECT_NE(html.find("FAIL</span> the scene fails the gate</p>"), std::string::npos) << html.substr(0, 2000);
  EXPECT_NE(html.find("one-side-only coverage at 7.77e-05 of covered pixels, where the baseline&#39;s was 0"), std::string::npos);
  EXPECT_EQ(run("check cube sphere -q --fail-on-warnings --baseline " + base).exitCode, 0);
  const CliRun idle = run("check cube -q --fail-on-warnings");
  EXPECT_EQ(idle.exitCode, 0);
  EXPECT_NE(idle.output.find("note: --fail-on-warnings has nothing to fail on"), std::string::npos) << idle.output;
  // A scene given twice is held to its first and second entries in turn.
  const std::string twice = temp.file("twice.json");
  ASSERT_EQ(run("check cube cube -q --json " + twice).exitCode, 0);
  const CliRun again = run("check cube cube -q --baseline-factor 1 --baseline " + twice);
  EXPECT_EQ(again.exitCode, 0) << again.output;
  EXPECT_EQ(again.output.find("warning"), std::string::npos) << again.output;
  // In turn, not each to the first: a baseline whose first cube was drawn with 4 subpixel bits
  // and its second with 8 warns a 4-bit run of its second cube alone.
  const std::string coarseCube = temp.file("coarse.json"), now2 = temp.file("now2.json");
  ASSERT_EQ(run("check cube -q --subpixel-bits 4 --json " + coarseCube).exitCode, 0);
  nlohmann::json mixed = nlohmann::json::parse(rc::testing::readFile(twice));
  mixed["scenes"][0] = nlohmann::json::parse(rc::testing::readFile(coarseCube))["scenes"][0];
  const CliRun inTurn =
      run("check cube cube -q --subpixel-bits 4 --baseline " + temp.write("mixed.json", mixed.dump()) + " --json " + now2);
  EXPECT_EQ(inTurn.exitCode, 0) << inTurn.output;
  EXPECT_NE(inTurn.output.find("2 scene(s): all pass; 1 with warnings\n"), std::string::npos) << inTurn.output;
  const nlohmann::json heldInTurn = nlohmann::json::parse(rc::testing::readFile(now2));
  EXPECT_TRUE(heldInTurn["scenes"][0]["report"]["warnings"].empty()) << heldInTurn["scenes"][0]["report"]["warnings"];
  EXPECT_NE(heldInTurn["scenes"][1]["report"]["warnings"].dump().find("different triangle at "), std::string::npos)
      << heldInTurn["scenes"][1]["report"]["warnings"];
  // A scene file whose triangle count changed since the baseline is not held to its figures.
  const std::string obj = temp.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), objBase = temp.file("obj.json");
  ASSERT_EQ(run("check " + obj + " -q --json " + objBase).exitCode, 0);
  temp.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  const CliRun grown = run("check " + obj + " -q --baseline-factor 1 --baseline " + objBase);
  EXPECT_EQ(grown.exitCode, 0) << grown.output;
  EXPECT_NE(grown.output.find("    warning: the baseline's scene had 1 triangles, this one 2: not held to it\n"),
            std::string::npos)
      << grown.output;
  EXPECT_EQ(rc::testing::occurrences(grown.output, "warning: "), 1) << grown.output;
  // Nor is a scene seen through another camera than the baseline's.
  const CliRun moved = run("check cube -q --baseline-factor 1 --eye 2.6,2.2,3.5 --baseline " + base);
  EXPECT_EQ(moved.exitCode, 0) << moved.output;
  EXPECT_NE(moved.output.find("    warning: the baseline's images were rendered through the camera 'eye=(2.6"),
            std::string::npos)
      << moved.output;
  EXPECT_EQ(rc::testing::occurrences(moved.output, "warning: "), 1) << moved.output;
  // A factor above the growth keeps it quiet.
  const CliRun loose = run("check cube sphere -q --subpixel-bits 4 --baseline " + base + " --baseline-factor 100");
  EXPECT_EQ(loose.output.find("warning"), std::string::npos) << loose.output;

  // compare holds one comparison to a compare report, and refuses check's.
  const std::string raster = temp.file("s.exr"), ref = temp.file("r.exr"), one = temp.file("one.json");
  ASSERT_EQ(run("render sphere -o " + raster).exitCode, 0);
  ASSERT_EQ(run("render sphere --backend reference -o " + ref).exitCode, 0);
  ASSERT_EQ(run("compare " + raster + " " + ref + " --json " + one).exitCode, 0);
  const CliRun held = run("compare " + raster + " " + ref + " --baseline " + one + " --baseline-factor 1");
  EXPECT_EQ(held.exitCode, 0) << held.output;
  EXPECT_EQ(held.output.find("warning"), std::string::npos) << held.output;
  const CliRun wrong = run("compare " + raster + " " + ref + " --baseline " + base);
  EXPECT_EQ(wrong.exitCode, 3) << wrong.output;
  EXPECT_NE(wrong.output.find(base + ": is a report of rastercheck check --json; compare --baseline takes one of compare --json"),
            std::string::npos)
      << wrong.output;
  EXPECT_EQ(run("check cube --baseline-factor 3").exitCode, 2);
  EXPECT_EQ(run("check cube --baseline " + base + " --baseline-factor 0.5").exitCode, 2);
  EXPECT_EQ(run("check cube --baseline " + base + " --json " + base).exitCode, 2);  // would replace its input
}

}  // namespace
