// compare on synthetic images whose differences are known exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "compare/baseline.h"
#include "compare/compare.h"
#include "compare/heatmap_png.h"
#include "compare/report.h"
#include "core/channels.h"
#include "core/error.h"
#include "rasterizer/rasterizer.h"
#include "raytracer_ref/reference.h"
#include "scenes/camera.h"
#include "scenes/registry.h"
#include "tests/compare/synthetic_images.h"
#include "tests/made_up_report.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using namespace testing;  // tests/compare/synthetic_images.h

TEST(Compare, IdenticalImagesHaveZeroErrorAndPass) {
  const CompareReport r = compareImages(image(), "a.exr", image(), "b.exr", Thresholds{}, nullptr);
  EXPECT_TRUE(r.pass);
  EXPECT_EQ(r.classCounts[int(PixelClass::kSameTriangle)], std::size_t(kW * kH));
  for (const FamilyReport& f : r.families) {
    EXPECT_EQ(f.stats.max, 0.0) << f.name;
    EXPECT_EQ(f.stats.count, std::size_t(kW * kH)) << f.name;
  }
  EXPECT_EQ(r.families.size(), 3u);  // bary, depth, attr.uv
}

// Two empty images agree everywhere, but the gate saw nothing: that fails unless allowed.
// One covered pixel is enough to compare.
TEST(Compare, APairThatCoversNoPixelComparesNothingAndFailsUnlessAllowed) {
  Framebuffer empty = image();
  for (std::uint32_t& id : empty.find(channels::kTriangleId)->uints) id = channels::kNoTriangle;
  const CompareReport r = compareImages(empty, "t.exr", empty, "r.exr", Thresholds{}, nullptr);
  EXPECT_EQ(r.coveredEither, 0u);
  EXPECT_FALSE(r.pass);
  ASSERT_EQ(r.reasons.size(), 1u);
  EXPECT_EQ(r.reasons[0], "neither image covers a pixel, so nothing was compared (--allow-empty lets such a pair pass)");
  Thresholds allowing;
  allowing.allowEmpty = true;
  EXPECT_TRUE(compareImages(empty, "t.exr", empty, "r.exr", allowing, nullptr).pass);
  Framebuffer one = empty;
  idAt(one, 4, 4) = 1;
  const CompareReport single = compareImages(one, "t.exr", one, "r.exr", Thresholds{}, nullptr);
  EXPECT_EQ(single.coveredEither, 1u);
  EXPECT_TRUE(single.pass);
}

TEST(Compare, OneKnownDifferenceGivesKnownStatistics) {
  Framebuffer test = image();
  at(test, channels::kBary[0], 3, 4) = 0.25f + 0x1p-10f;  // exact in float
  at(test, channels::kDepth, 6, 7) = 4.0f + 0x1p-10f;     // relative error 2^-12
  at(test, channels::attributeChannel("uv", 1), 2, 2) = 2.0f + 0.5f;
  const CompareReport r = compareImages(test, "t.exr", image(), "r.exr", Thresholds{}, nullptr);
  const FamilyStats& bary = family(r, "bary").stats;
  EXPECT_EQ(bary.max, 0x1p-10);
  EXPECT_EQ(bary.worst.x, 3);
  EXPECT_EQ(bary.worst.y, 4);
  EXPECT_EQ(bary.worst.test, 0.25 + 0x1p-10);
  EXPECT_EQ(bary.worst.reference, 0.25);
  EXPECT_DOUBLE_EQ(bary.mean, 0x1p-10 / 100);
  EXPECT_DOUBLE_EQ(bary.rms, 0x1p-10 / 10);
  EXPECT_EQ(bary.p50, 0.0);
  EXPECT_EQ(bary.p99, 0.0);     // nearest rank 99 of 100 is still zero
  EXPECT_EQ(bary.p999, 0x1p-10);  // rank 100
  EXPECT_EQ(family(r, "depth").stats.max, 0x1p-12);
  const FamilyReport& uv = family(r, "attr.uv");
  EXPECT_EQ(uv.stats.max, 0.5);
  EXPECT_EQ(uv.range, 9.0);  // uv spans 0..9 in the reference
  EXPECT_DOUBLE_EQ(uv.gated, 0.5 / 9.0);
  EXPECT_FALSE(r.pass);
  EXPECT_EQ(r.reasons.size(), 3u);  // bary, depth, attr.uv
}

TEST(Compare, PixelClassesAreCounted) {
  Framebuffer test = image(), ref = image();
  idAt(test, 0, 0) = 2;                        // different triangle
  idAt(test, 1, 0) = channels::kNoTriangle;    // reference only
  idAt(ref, 2, 0) = channels::kNoTriangle;     // test only
  idAt(test, 3, 0) = idAt(ref, 3, 0) = channels::kNoTriangle;  // both empty
  const CompareReport r = compareImages(test, "t", ref, "r", Thresholds{}, nullptr);
  EXPECT_EQ(r.classCounts[int(PixelClass::kDifferentTriangle)], 1u);
  EXPECT_EQ(r.classCounts[int(PixelClass::kReferenceOnly)], 1u);
  EXPECT_EQ(r.classCounts[int(PixelClass::kTestOnly)], 1u);
  EXPECT_EQ(r.classCounts[int(PixelClass::kBothEmpty)], 1u);
  EXPECT_EQ(r.classCounts[int(PixelClass::kSameTriangle)], 96u);
  EXPECT_DOUBLE_EQ(r.disagreementFraction, 1.0 / 99.0);
  EXPECT_DOUBLE_EQ(r.coverageFraction, 2.0 / 99.0);
  EXPECT_FALSE(r.pass);  // both fractions exceed the defaults
}

TEST(Compare, NanAndInfNeverPassEvenWithHugeThresholds) {
  Thresholds lax{1e30, 1e30, 1e30, 1.0, 1.0};
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    for (bool inReference : {false, true}) {
      Framebuffer test = image(), ref = image();
      at(inReference ? ref : test, channels::kBary[1], 5, 5) = bad;
      const CompareReport r = compareImages(test, "t", ref, "r", lax, nullptr);
      const FamilyStats& s = family(r, "bary").stats;
      EXPECT_EQ(s.nanCount + s.infCount, 1u);
      EXPECT_FALSE(r.pass) << "a " << bad << " in " << (inReference ? "reference" : "test") << " passed";
    }
  }
}

int incompatibility(const Framebuffer& test, const Framebuffer& ref, std::string* message,
                    const Thresholds& thresholds = Thresholds{}) {
  try {
    compareImages(test, "test.exr", ref, "ref.exr", thresholds, nullptr);
  } catch (const Error& e) {
    *message = e.what();
    return int(e.code());
  }
  return 0;
}

TEST(Compare, IncompatibleImagesAreRefusedNamingFileAndChannel) {
  std::string message;
  Framebuffer small(kW, kH + 1);
  EXPECT_EQ(incompatibility(image(), small, &message), int(ExitCode::kBadInput));
  EXPECT_NE(message.find("differs"), std::string::npos) << message;

  Framebuffer noUv(kW, kH);
  noUv.addUint(channels::kTriangleId, 1);
  for (const char* b : channels::kBary) noUv.addFloat(b);
  noUv.addFloat(channels::kDepth);
  EXPECT_EQ(incompatibility(image(), noUv, &message), int(ExitCode::kBadInput));
  EXPECT_NE(message.find("ref.exr: channel attr.uv.x"), std::string::npos) << message;

  // An attribute channel without a name (found by fuzz_exr_pair: attr.x made a family "attr",
  // which the per-attribute limits then cut past its end).
  for (const char* nameless : {"attr.x", "attr..x", "attr."}) {
    Framebuffer odd = image();
    odd.addFloat(nameless);
    EXPECT_EQ(incompatibility(image(), odd, &message), int(ExitCode::kBadInput)) << nameless;
    EXPECT_EQ(message, std::string("ref.exr: channel ") + nameless +
                           ": names no attribute (attribute channels are attr.NAME.x, .y, .z, .w)");
  }

  Framebuffer floatIds(kW, kH);
  floatIds.addFloat(channels::kTriangleId);
  EXPECT_EQ(incompatibility(floatIds, image(), &message), int(ExitCode::kBadInput));
  EXPECT_NE(message.find("test.exr: channel tri.id"), std::string::npos) << message;

  // Renders through two cameras (both record theirs): refused, not failed bound by bound. An
  // image without the line (another renderer's) is taken at its word.
  Framebuffer here = image(), there = image();
  here.attributes[channels::header::kCamera] = "eye=(0,0,5) size=8x6";
  there.attributes[channels::header::kCamera] = "eye=(0,0,6) size=8x6";
  EXPECT_EQ(incompatibility(here, there, &message), int(ExitCode::kBadInput));
  EXPECT_EQ(message, "test.exr: rastercheck.camera: 'eye=(0,0,5) size=8x6' is not ref.exr's 'eye=(0,0,6) size=8x6': "
                     "the images were rendered through different cameras");
  EXPECT_EQ(incompatibility(here, here, &message), 0);
  EXPECT_EQ(incompatibility(here, image(), &message), 0);
}

// --attributes: only the attribute families named are compared, each required in both; an
// attribute one image lacks is refused with a hint, and a name neither carries is a usage error.
TEST(Compare, AttributesOptionComparesOnlyTheFamiliesNamed) {
  Framebuffer withNormal = image();
  for (int k = 0; k < 3; ++k) withNormal.addFloat(channels::attributeChannel("normal", k), 0.5f);
  std::string message;
  EXPECT_EQ(incompatibility(image(), withNormal, &message), int(ExitCode::kBadInput));
  EXPECT_NE(message.find("test.exr: channel attr.normal.x: missing (present in ref.exr; --attributes compares only those named)"),
            std::string::npos)
      << message;

  Thresholds uvOnly;
  uvOnly.attributes = {"uv"};
  const CompareReport r = compareImages(image(), "test.exr", withNormal, "ref.exr", uvOnly, nullptr);
  EXPECT_TRUE(r.pass);
  ASSERT_EQ(r.families.size(), 3u);
  EXPECT_EQ(r.families[2].name, "attr.uv");
  EXPECT_EQ(reportToJson(r)["thresholds"]["attributes"], nlohmann::json::array({"uv"}));
  EXPECT_EQ(reportToJson(r)["left_out"], nlohmann::json::array({"attr.normal"}));
  EXPECT_NE(reportToTable(r).find("left out (--attributes): attr.normal\n"), std::string::npos) << reportToTable(r);
  EXPECT_EQ(reportToJson(compareImages(image(), "t", image(), "r", Thresholds{}, nullptr))["thresholds"]["attributes"],
            nlohmann::json::array());

  Thresholds normalOnly;
  normalOnly.attributes = {"normal"};
  EXPECT_EQ(incompatibility(image(), withNormal, &message, normalOnly), int(ExitCode::kBadInput));
  EXPECT_NE(message.find("test.exr: channel attr.normal.x: missing (present in ref.exr)"), std::string::npos) << message;

  Thresholds typo;
  typo.attributes = {"nromal"};
  EXPECT_EQ(incompatibility(image(), withNormal, &message, typo), int(ExitCode::kUsage));
  EXPECT_NE(message.find("--attributes nromal: neither test.exr nor ref.exr carries it (they carry normal, uv)"),
            std::string::npos)
      << message;
}

// --max-attr: one limit for every attribute, and NAME=LIMIT for one; a name that gates nothing
// (neither image carries it, or --attributes leaves it out) is a usage error. A reason prints
// as many digits as tell the error from its limit.
TEST(Compare, EachAttributeMayHaveItsOwnLimit) {
  const auto withColor = [] {
    Framebuffer fb = image();
    float* c = fb.addFloat(channels::attributeChannel("color", 0));
    for (int i = 0; i < kW * kH; ++i) c[i] = float(i % kW) * 0.25f;  // range 2.25
    return fb;
  };
  Framebuffer test = withColor();
  at(test, channels::attributeChannel("uv", 1), 2, 2) = 2.5f;                    // 0.5 of 9: 0.0556
  at(test, channels::attributeChannel("color", 0), 4, 1) = 4 * 0.25f + 0.25f;  // 0.25 of 2.25: 0.111
  const Framebuffer ref = withColor();
  const auto gate = [&](const Thresholds& t) { return compareImages(test, "test.exr", ref, "ref.exr", t, nullptr); };

  const CompareReport byDefault = gate(Thresholds{});
  EXPECT_EQ(byDefault.reasons, (std::vector<std::string>{"attr.color: max error 0.111 of range exceeds 0.0001",
                                                         "attr.uv: max error 0.0556 of range exceeds 0.0001"}));
  Thresholds uvLoose;
  uvLoose.attributeByName = {{"uv", 0.06}};
  const CompareReport loose = gate(uvLoose);
  EXPECT_EQ(family(loose, "attr.uv").threshold, 0.06);
  EXPECT_EQ(family(loose, "attr.color").threshold, 1e-4);
  EXPECT_EQ(loose.reasons, (std::vector<std::string>{"attr.color: max error 0.111 of range exceeds 0.0001"}));
  EXPECT_EQ(reportToJson(loose)["thresholds"]["attribute_by_name"], (nlohmann::json{{"uv", 0.06}}));
  EXPECT_EQ(reportToJson(loose)["families"]["attr.uv"]["threshold"], 0.06);

  Thresholds uvTight;
  uvTight.attribute = 0.2;
  uvTight.attributeByName = {{"uv", 0.05}};
  EXPECT_EQ(gate(uvTight).reasons, (std::vector<std::string>{"attr.uv: max error 0.0556 of range exceeds 0.05"}));
  uvTight.attributeByName["uv"] = 0.06;
  EXPECT_TRUE(gate(uvTight).pass);
  EXPECT_EQ(reportToJson(gate(Thresholds{}))["thresholds"]["attribute_by_name"], nlohmann::json::object());

  // A limit just below the error still reads as below it.
  Thresholds justBelow;
  justBelow.attributeByName = {{"color", std::nextafter(0.25 / 2.25, 0.0)}, {"uv", 1.0}};
  const std::vector<std::string> reasons = gate(justBelow).reasons;
  ASSERT_EQ(reasons.size(), 1u);
  EXPECT_EQ(reasons[0], "attr.color: max error 0.1111111111111111 of range exceeds 0.11111111111111109");

  std::string message;
  Thresholds typo;
  typo.attributeByName = {{"colour", 1.0}};
  EXPECT_EQ(incompatibility(test, ref, &message, typo), int(ExitCode::kUsage));
  EXPECT_EQ(message, "--max-attr colour: neither test.exr nor ref.exr carries it (they carry color, uv)");
  Thresholds leftOut;
  leftOut.attributes = {"color"};
  leftOut.attributeByName = {{"uv", 1.0}};
  EXPECT_EQ(incompatibility(test, ref, &message, leftOut), int(ExitCode::kUsage));
  EXPECT_EQ(message, "--max-attr uv: --attributes leaves it out, so it is not compared");
}

// --warn-*: a value beyond a warning limit is a warning, in the report and its JSON, and never
// fails the gate; a value at the limit is within it; unset limits warn of nothing.
TEST(Compare, WarningLimitsWarnWithoutFailing) {
  Framebuffer test = image();
  at(test, channels::kBary[0], 3, 4) = 0.25f + 0x1p-10f;
  at(test, channels::kDepth, 6, 7) = 4.0f + 0x1p-10f;  // relative 2^-12
  at(test, channels::attributeChannel("uv", 1), 2, 2) = 2.5f;  // 0.5 of 9
  idAt(test, 0, 0) = 2;  // one different triangle of 100 covered pixels
  Thresholds t{1.0, 1.0, 1.0, 1.0, 1.0};
  const auto warned = [&] { return compareImages(test, "t.exr", image(), "r.exr", t, nullptr); };
  EXPECT_TRUE(warned().warnings.empty());
  EXPECT_EQ(reportToJson(warned())["thresholds"]["warn"]["bary"], nullptr);

  t.warn.bary = 0x1p-11;
  t.warn.depth = 0x1p-12;  // exactly the error: within
  t.warn.attribute = 0.05;
  t.warn.disagreement = 0.005;
  t.warn.coverage = 0.0;
  const CompareReport r = warned();
  EXPECT_TRUE(r.pass);
  EXPECT_TRUE(r.reasons.empty());
  EXPECT_EQ(r.warnings, (std::vector<std::string>{"bary: max error 0.000977 exceeds the warning limit 0.000488",
                                                  "attr.uv: max error 0.0556 of range exceeds the warning limit 0.05",
                                                  "different triangle at 0.01 of covered pixels, warning limit 0.005"}));
  const nlohmann::json j = reportToJson(r);
  EXPECT_EQ(j["verdict"], "pass");
  EXPECT_EQ(j["warnings"].size(), 3u);
  EXPECT_EQ(j["thresholds"]["warn"]["depth"], 0x1p-12);
  EXPECT_NE(reportToTable(r).find("verdict: PASS\nwarning: bary: max error 0.000977"), std::string::npos) << reportToTable(r);

  t.warn.attributeByName = {{"uv", 0.06}};
  EXPECT_EQ(warned().warnings.size(), 2u);
  t.warn.attributeByName = {{"uvw", 0.06}};
  std::string message;
  EXPECT_EQ(incompatibility(test, image(), &message, t), int(ExitCode::kUsage));
  EXPECT_EQ(message, "--warn-attr uvw: neither test.exr nor ref.exr carries it (they carry uv)");

  // A failing gate keeps its warnings apart from its reasons.
  t.warn.attributeByName.clear();
  t.bary = 0.0;
  const CompareReport failed = warned();
  EXPECT_FALSE(failed.pass);
  EXPECT_EQ(failed.reasons, (std::vector<std::string>{"bary: max error 0.000977 exceeds 0"}));
  EXPECT_EQ(failed.warnings.size(), 3u);

  // --fail-on-warnings: each warning is a reason instead, after the gate's own.
  t.warn.fail = true;
  const CompareReport strict = warned();
  EXPECT_FALSE(strict.pass);
  EXPECT_EQ(strict.reasons.size(), 4u);
  EXPECT_EQ(strict.reasons[1], "bary: max error 0.000977 exceeds the warning limit 0.000488");
  EXPECT_TRUE(strict.warnings.empty());
  EXPECT_EQ(reportToJson(strict)["thresholds"]["warn"]["fail"], true);
  t.bary = 1.0;
  EXPECT_EQ(warned().reasons.size(), 3u);
  EXPECT_FALSE(warned().pass);
  t.warn = {};
  t.warn.fail = true;
  EXPECT_TRUE(warned().pass);  // nothing to warn of
}

// --baseline: a report's figures read back from its JSON hold the same report to itself with
// no warning at a factor of 1, on a real pair gated against the bounds (ratios included).
TEST(Baseline, AReportHeldToItsOwnJsonHasNoWarnings) {
  const Scene scene = makeBuiltinScene("sphere");
  const CompareReport r = compareImages(rasterize(scene, RasterOptions{}), "t", renderReference(scene, ReferenceOptions{}),
                                        "r", Thresholds{}, nullptr);
  ASSERT_TRUE(family(r, "bary").bounded);
  // Round-trips through text, as a CI keeps it.
  const BaselineFigures b = baselineFigures(nlohmann::json::parse(reportToJson(r).dump()), "base.json: ");
  EXPECT_EQ(b.families.size(), r.families.size());
  EXPECT_EQ(b.families.at("bary").max, family(r, "bary").stats.max);
  EXPECT_EQ(b.families.at("attr.uv").p999, family(r, "attr.uv").stats.p999 / family(r, "attr.uv").range);
  EXPECT_EQ(b.families.at("depth").boundRatio, family(r, "depth").ratio.max);
  EXPECT_EQ(b.disagreement, r.disagreementFraction);
  EXPECT_GT(b.disagreement, 0.0);
  EXPECT_TRUE(baselineWarnings(r, b, 1.0).empty());
  // One figure lowered in the baseline: that one warns, and only it.
  BaselineFigures lower = b;
  lower.families["bary"].max /= 1.5;
  const std::vector<std::string> warned = baselineWarnings(r, lower, 1.0);
  ASSERT_EQ(warned.size(), 1u);
  EXPECT_EQ(warned[0].rfind("bary: max error ", 0), 0u) << warned[0];
  EXPECT_NE(warned[0].find(", 1.5x the baseline's "), std::string::npos) << warned[0];
  EXPECT_TRUE(baselineWarnings(r, lower, 1.5).empty());
  // The bounded families are held to their error / bound as well.
  BaselineFigures tighter = b;
  tighter.families["depth"].boundRatio = *b.families.at("depth").boundRatio / 2;
  const std::vector<std::string> ratio = baselineWarnings(r, tighter, 1.5);
  ASSERT_EQ(ratio.size(), 1u);
  EXPECT_EQ(ratio[0].rfind("depth: max error / bound ", 0), 0u) << ratio[0];
}

TEST(Baseline, FiguresThatGrewBeyondTheFactorAreWarnings) {
  Framebuffer before = image(), now = image();
  at(before, channels::kBary[0], 3, 4) = 0.25f + 0x1p-12f;
  at(now, channels::kBary[0], 3, 4) = 0.25f + 0x1p-10f;  // 4x
  at(now, channels::attributeChannel("uv", 1), 2, 2) = 2.5f;  // 0.5 of 9; before: 0
  idAt(now, 0, 0) = idAt(now, 1, 0) = idAt(now, 2, 0) = 2;  // 0.03 of the covered pixels; before: none
  const Thresholds t{1.0, 1.0, 1.0, 1.0, 1.0};
  const CompareReport r = compareImages(now, "t.exr", image(), "r.exr", t, nullptr);
  const BaselineFigures b =
      baselineFigures(reportToJson(compareImages(before, "t.exr", image(), "r.exr", t, nullptr)), "b.json: ");
  EXPECT_EQ(baselineWarnings(r, b, 2.0),
            (std::vector<std::string>{"bary: max error 0.000977, 4x the baseline's 0.000244",
                                      "bary: p99.9 error 0.000977, 4x the baseline's 0.000244",
                                      "attr.uv: max error 0.0556 of range, where the baseline's was 0",
                                      "attr.uv: p99.9 error 0.0556 of range, where the baseline's was 0",
                                      "different triangle at 0.03 of covered pixels, where the baseline's was 0"}));
  // Exactly the factor is within it; a figure the baseline had at 0 is held as one covered pixel
  // (3 pixels now: within 3 times it) or an error of 2^-24.
  EXPECT_EQ(baselineWarnings(r, b, 4.0),
            (std::vector<std::string>{"attr.uv: max error 0.0556 of range, where the baseline's was 0",
                                      "attr.uv: p99.9 error 0.0556 of range, where the baseline's was 0"}));
  EXPECT_EQ(baselineWarnings(r, b, 3.0).size(), 4u);

  // A figure the baseline had as NaN holds nothing; a family it lacks, or another image size, is
  // said once.
  BaselineFigures odd = b;
  odd.families["bary"].max = odd.families["bary"].p999 = std::numeric_limits<double>::quiet_NaN();
  odd.families.erase("attr.uv");
  EXPECT_EQ(baselineWarnings(r, odd, 2.0),
            (std::vector<std::string>{"attr.uv: not in the baseline, not held to it",
                                      "different triangle at 0.03 of covered pixels, where the baseline's was 0"}));
  odd.width = 12;
  EXPECT_EQ(baselineWarnings(r, odd, 2.0),
            (std::vector<std::string>{"the baseline's images are 12x10, these 10x10: not held to it"}));
  // Nor is a baseline whose images were rendered through another camera: its figures are of
  // other pixels. A report of images that record no camera is held to any baseline.
  Framebuffer seen = now, seenRef = image();
  seen.attributes[channels::header::kCamera] = seenRef.attributes[channels::header::kCamera] = "eye=(0,0,5)";
  const CompareReport throughCamera = compareImages(seen, "t.exr", seenRef, "r.exr", t, nullptr);
  EXPECT_EQ(throughCamera.camera, "eye=(0,0,5)");
  BaselineFigures elsewhere = b;
  elsewhere.camera = "eye=(0,0,6)";
  EXPECT_EQ(baselineWarnings(throughCamera, elsewhere, 2.0),
            (std::vector<std::string>{"the baseline's images were rendered through the camera 'eye=(0,0,6)', these "
                                      "through 'eye=(0,0,5)': not held to it"}));
  EXPECT_EQ(baselineWarnings(r, elsewhere, 2.0), baselineWarnings(r, b, 2.0));
  elsewhere.camera = "eye=(0,0,5)";
  EXPECT_EQ(baselineWarnings(throughCamera, elsewhere, 2.0), baselineWarnings(r, b, 2.0));

  // Held to it, the report carries the warnings after its own and names the baseline.
  Thresholds warnAlso = t;
  warnAlso.warn.bary = 0.0;
  CompareReport held = compareImages(now, "t.exr", image(), "r.exr", warnAlso, nullptr);
  holdReportToBaseline(held, b, {"b.json", 3.5});
  ASSERT_EQ(held.warnings.size(), 5u);
  EXPECT_EQ(held.warnings[0], "bary: max error 0.000977 exceeds the warning limit 0");
  const nlohmann::json j = reportToJson(held);
  EXPECT_EQ(j["baseline"], (nlohmann::json{{"file", "b.json"}, {"factor", 3.5}}));
  EXPECT_EQ(j["warnings"].size(), 5u);
  EXPECT_EQ(reportToJson(r)["baseline"], nullptr);
  // With --fail-on-warnings the baseline's warnings fail the gate as well.
  warnAlso.warn.fail = true;
  CompareReport strict = compareImages(now, "t.exr", image(), "r.exr", warnAlso, nullptr);
  EXPECT_EQ(strict.reasons.size(), 1u);
  holdReportToBaseline(strict, b, {"b.json", 3.5});
  EXPECT_FALSE(strict.pass);
  EXPECT_EQ(strict.reasons.size(), 5u);
  EXPECT_TRUE(strict.warnings.empty());
}

TEST(Baseline, AnythingButAReportOfTheCommandIsRefusedNamingTheField) {
  const rc::testing::TempDir dir;
  const nlohmann::json report = reportToJson(compareImages(image(), "t.exr", image(), "r.exr", Thresholds{}, nullptr));
  const nlohmann::json check = {{"format_version", 1}, {"scenes", {{{"scene", "cube"}, {"triangles", 12}, {"report", report}}}}};
  const std::string compareFile = dir.write("c.json", report.dump()), checkFile = dir.write("k.json", check.dump());
  EXPECT_EQ(readBaseline(compareFile, false).at("").size(), 1u);
  EXPECT_EQ(*readBaseline(checkFile, true).at("cube").at(0).triangles, 12u);

  const auto refused = [&](const nlohmann::json& doc, bool perScene, const std::string& message) {
    const std::string file = dir.write("bad.json", doc.dump());
    rc::testing::expectError([&] { readBaseline(file, perScene); }, ExitCode::kBadInput, {file + ": " + message}, message);
  };
  refused(check, false, "is a report of rastercheck check --json; compare --baseline takes one of compare --json");
  refused(report, true, "is a report of rastercheck compare --json; check --baseline takes one of check --json");
  refused(nlohmann::json::array(), false, "not a rastercheck report");
  nlohmann::json j = report;
  j["format_version"] = 2;
  refused(j, false, "not a rastercheck report");
  j = report;
  j["families"]["bary"]["max"] = -1;
  refused(j, false, "/families/bary/max: is -1; a figure is a number >= 0");
  j = report;
  j["families"]["attr.uv"]["p999"] = "big";
  refused(j, false, "/families/attr.uv/p999: is \"big\"");
  j = report;
  j.erase("coverage_fraction");
  refused(j, false, "/coverage_fraction: missing");
  j = report;
  j["camera"] = "eye=(1,2,3)";  // read back as written; null or absent: none
  EXPECT_EQ(readBaseline(dir.write("camera.json", j.dump()), false).at("").at(0).camera, "eye=(1,2,3)");
  EXPECT_EQ(readBaseline(compareFile, false).at("").at(0).camera, "");
  j.erase("camera");
  EXPECT_EQ(readBaseline(dir.write("camera.json", j.dump()), false).at("").at(0).camera, "");
  j["camera"] = 3;
  refused(j, false, "/camera: is 3, not a string or null");
  j = report;
  j["width"] = 0.5;
  refused(j, false, "/width: is 0.5; an image side is a whole number of pixels");
  j = report;
  j["families"]["depth"]["bound_ratio"] = {{"p999", 1}};
  refused(j, false, "/families/depth/bound_ratio/max: missing");
  j = check;
  j["scenes"].push_back(j["scenes"][0]);  // `check cube cube`: both kept, in order
  j["scenes"][1]["triangles"] = 13;
  EXPECT_EQ(*readBaseline(dir.write("twice.json", j.dump()), true).at("cube").at(1).triangles, 13u);
  j = check;
  j["scenes"][0]["triangles"] = -3;
  refused(j, true, "/scenes/0/triangles: is -3, not a count");
  j = check;
  j["scenes"][0]["report"]["families"] = 7;
  refused(j, true, "/scenes/0/report/families: is number, not an object");
  rc::testing::expectError([&] { readBaseline(dir.write("half.json", "{\"format"), false); }, ExitCode::kBadInput,
                           {"half.json: invalid JSON"}, "truncated");
  rc::testing::expectError([&] { readBaseline(dir.file("none.json"), false); }, ExitCode::kIo,
                           {"none.json: cannot read baseline report"}, "missing");
}

TEST(Compare, HeatmapHasErrorAndClassChannels) {
  Framebuffer test = image();
  at(test, channels::kBary[0], 3, 4) = 0.3f;
  idAt(test, 0, 0) = 7;
  Framebuffer heatmap;
  compareImages(test, "t", image(), "r", Thresholds{}, &heatmap);
  ASSERT_NE(heatmap.find("error.bary"), nullptr);
  ASSERT_NE(heatmap.find("error.attr.uv"), nullptr);
  ASSERT_NE(heatmap.find("R"), nullptr);
  EXPECT_NEAR(heatmap.find("error.bary")->floats[4 * kW + 3], 0.05, 1e-6);
  EXPECT_EQ(heatmap.find("class.id")->uints[0], std::uint32_t(PixelClass::kDifferentTriangle));
  EXPECT_EQ(heatmap.find("class.id")->uints[1], std::uint32_t(PixelClass::kSameTriangle));
}

TEST(HeatmapPicture, KeepsTheMapAndAddsALegendWithTheReservedColours) {
  Framebuffer test = image();
  idAt(test, 0, 0) = 7;  // a different-triangle pixel: green
  Framebuffer heatmap;
  compareImages(test, "t", image(), "r", Thresholds{}, &heatmap);
  const Rgb8Image picture = heatmapImage(heatmap);
  EXPECT_GE(picture.width, 760);  // wide enough for the legend
  EXPECT_GT(picture.height, kH + 60);
  const std::uint8_t* p = &picture.pixels[0];
  EXPECT_EQ(p[0], 0);
  EXPECT_EQ(p[1], 255);  // the different-triangle pixel at (0, 0) is pure green
  EXPECT_EQ(p[2], 0);
  std::size_t greenInLegend = 0;
  for (int y = kH; y < picture.height; ++y) {
    for (int x = 0; x < picture.width; ++x) {
      const std::uint8_t* q = &picture.pixels[(std::size_t(y) * picture.width + x) * 3];
      greenInLegend += q[0] == 0 && q[1] == 255 && q[2] == 0;
    }
  }
  EXPECT_GT(greenInLegend, 100u) << "the legend's swatch for different-triangle pixels";
}

TEST(Compare, JsonReportCarriesVerdictCountsAndFamilies) {
  Framebuffer test = image();
  at(test, channels::kBary[0], 3, 4) = std::numeric_limits<float>::quiet_NaN();
  const nlohmann::json j =
      reportToJson(compareImages(test, "t", image(), "r", Thresholds{}, nullptr));
  EXPECT_EQ(j["verdict"], "fail");
  EXPECT_EQ(j["pixels"]["same_triangle"], 100);
  EXPECT_EQ(j["families"]["bary"]["nan"], 1);
  for (const char* key : {"max", "mean", "rms", "p99", "p999"}) {
    EXPECT_TRUE(j["families"]["depth"].contains(key)) << key;
  }
}

// Each figure of a report in its own column of the table and under its own name in the JSON, on
// made-up figures that are all distinct. Until session 39 a table that printed the maximum as
// the p99.9 (of the errors or of their ratio to the bound) or the depth ties as unexplained, and
// JSON that wrote the p99.9 as the p99, the mean as the rms or the ulps' maximum as their p99.9,
// passed every test.
TEST(Report, TableShowsEachFigureInItsColumn) {
  EXPECT_EQ(reportToTable(testing::madeUpReport(false)),
            "pixels 8x4: 29 covered by either; same triangle 19, different 5 (0.125), test only 3, reference only 2\n"
            "disagreements: 11 in the edge band (0.0055 px), 13 depth ties, 17 unexplained\n"
            "family               max      mean     p99.9  max ulps max/bound   n+i     limit p99.9/bnd  "
            "largest error at: test / ref\n"
            "bary             0.00125   0.00025   0.00065      42.5      0.75     3     bound     0.625  "
            "(6,1) 0.25 / 0.375\n"
            "attr.uv            0.002    0.0003    0.0007      52.5         -     0 0.004*2.5         -  "
            "(2,3) 1.5 / 1.5\n"
            "verdict: FAIL\n"
            "  - bary: max error 0.5 over its bound\n"
            "  - depth: 2 NaN <pixels>\n");
}

TEST(Report, JsonCarriesEachFigureUnderItsName) {
  const nlohmann::json j = reportToJson(testing::madeUpReport(false));
  EXPECT_EQ(j["verdict"], "fail");
  EXPECT_EQ(j["pixels"], (nlohmann::json{{"both_empty", 3}, {"same_triangle", 19}, {"different_triangle", 5},
                                         {"test_only", 3}, {"reference_only", 2}, {"covered_either", 29}}));
  EXPECT_EQ(j["disagreement_fraction"], 0.125);
  EXPECT_EQ(j["coverage_fraction"], 0.0625);
  EXPECT_EQ(j["disagreements"],
            (nlohmann::json{{"by", "diagnostics"}, {"edge_band", 11}, {"depth_tie", 13}, {"unexplained", 17},
                            {"edge_band_pixels", 0.0055}}));
  EXPECT_EQ(j["families"]["bary"],
            (nlohmann::json{{"unit", "absolute"},
                            {"count", 24},
                            {"nan", 1},
                            {"inf", 2},
                            {"max", 0.00125},
                            {"mean", 0.00025},
                            {"rms", 0.00035},
                            {"p50", 4.5e-05},
                            {"p99", 0.00055},
                            {"p999", 0.00065},
                            {"threshold", 1.0},
                            {"gated", 0.75},
                            {"bounded", true},
                            {"ulps", {{"max", 42.5}, {"p999", 37.5}}},
                            {"bound_ratio", {{"max", 0.75}, {"p999", 0.625}, {"worst", {{"x", 5}, {"y", 2}}}}},
                            {"worst", {{"x", 6}, {"y", 1}, {"test", 0.25}, {"reference", 0.375}}}}));
  EXPECT_EQ(j["families"]["attr.uv"],
            (nlohmann::json{{"unit", "absolute"},
                            {"count", 27},
                            {"nan", 0},
                            {"inf", 0},
                            {"max", 0.002},
                            {"mean", 0.0003},
                            {"rms", 0.0004},
                            {"p50", 5e-05},
                            {"p99", 0.0006},
                            {"p999", 0.0007},
                            {"threshold", 0.004},
                            {"gated", 0.0008},
                            {"range", 2.5},
                            {"bounded", false},
                            {"ulps", {{"max", 52.5}, {"p999", 47.5}}},
                            {"worst", {{"x", 2}, {"y", 3}, {"test", 1.5}, {"reference", 1.498}}}}));
}

// The families are measured in parallel, each in pixel order: every figure and every heatmap
// bit is the same on 1, 2 or 5 threads, on a real pair with non-finite pixels in two families.
TEST(Compare, FiguresAndHeatmapDoNotDependOnTheThreadCount) {
  const Scene scene = makeBuiltinScene("sphere");
  RasterOptions options;
  options.threads = 1;
  Framebuffer raster = rasterize(scene, options);
  const Framebuffer reference = renderReference(scene, ReferenceOptions{});
  const std::uint32_t* ids = raster.find(channels::kTriangleId)->uints.data();
  int poisoned = 0;
  for (std::size_t i = 0; i < raster.pixelCount() && poisoned < 2; i += 997) {
    if (ids[i] == channels::kNoTriangle) continue;
    raster.find(poisoned == 0 ? channels::kBary[1] : channels::attributeChannel("uv", 0))->floats[i] =
        std::numeric_limits<float>::quiet_NaN();
    ++poisoned;
  }
  ASSERT_EQ(poisoned, 2);
  Framebuffer one;
  const CompareReport first = compareImages(raster, "t", reference, "r", Thresholds{}, &one, 1);
  ASSERT_GE(first.families.size(), 4u);  // bary, depth, and the sphere's normal and uv
  EXPECT_EQ(family(first, "bary").stats.nanCount, 1u);
  EXPECT_EQ(family(first, "attr.uv").stats.nanCount, 1u);
  for (const int threads : {2, 5, 0}) {
    SCOPED_TRACE(threads);
    Framebuffer heatmap;
    const CompareReport r = compareImages(raster, "t", reference, "r", Thresholds{}, &heatmap, threads);
    EXPECT_EQ(reportToJson(r).dump(), reportToJson(first).dump());
    ASSERT_EQ(heatmap.channels().size(), one.channels().size());
    for (const Channel& c : one.channels()) {
      const Channel* d = heatmap.find(c.name);
      ASSERT_TRUE(d) << c.name;
      EXPECT_EQ(0, std::memcmp(c.type == ChannelType::kUint ? static_cast<const void*>(c.uints.data()) : c.floats.data(),
                               d->type == ChannelType::kUint ? static_cast<const void*>(d->uints.data()) : d->floats.data(),
                               4 * one.pixelCount()))
          << c.name;
    }
  }
}

TEST(Percentile, UsesNearestRank) {
  std::vector<float> values;
  for (int i = 1000; i >= 1; --i) values.push_back(float(i));
  EXPECT_EQ(percentile(values, 0.999), 999.0);
  EXPECT_EQ(percentile(values, 0.99), 990.0);
  EXPECT_EQ(percentile(values, 0.5), 500.0);
  EXPECT_EQ(percentile(values, 1.0), 1000.0);
}

// Both ways of selecting (a partition per rank for fewer than 65,536 values, a radix select
// from there) give what sorting gives: on random errors spread over many exponents, on values
// crowded into one bin of the top 16 bits, with ties, zeros, negatives and infinities.
TEST(Percentile, MatchesTheValueAtTheNearestRankOfASortedCopy) {
  std::uint64_t state = 88172645463325252ull;
  const auto next = [&state] {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return state;
  };
  const auto uniform = [&] { return double(next() >> 11) * 0x1p-53; };
  for (int set = 0; set < 40; ++set) {
    std::vector<float> values(std::size_t(set < 20 ? 1 + next() % 5000 : 65536 + next() % 100000));
    for (float& v : values) {
      switch (set % 5) {
        case 0: v = float(std::exp(-40.0 * uniform())); break;  // errors from 1 down to 4e-18
        case 1: v = 1.0f + float(uniform()) * 0x1p-10f; break;    // one bin of the top 16 bits
        case 2: v = float(next() % 7) * 0.25f; break;             // ties and zeros
        case 3: v = float(uniform() - 0.5) * 1e3f; break;         // negatives
        default: v = next() % 10 == 0 ? std::numeric_limits<float>::infinity() : float(uniform()); break;
      }
    }
    std::vector<float> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    const std::vector<double> ps = {0.0, 1e-9, 0.5, 0.9, 0.99, 0.999, 0.9999, 1.0, uniform()};
    const std::vector<double> got = percentiles(values, ps);
    for (std::size_t j = 0; j < ps.size(); ++j) {
      const std::size_t rank = std::clamp<std::size_t>(std::size_t(std::ceil(ps[j] * double(values.size()))), 1, values.size());
      EXPECT_EQ(got[j], double(sorted[rank - 1])) << "set " << set << ", p " << ps[j] << ", n " << values.size();
      EXPECT_EQ(percentile(values, ps[j]), got[j]);
    }
  }
  EXPECT_EQ(percentiles({}, {0.5, 0.99}), (std::vector<double>{0.0, 0.0}));
  // p outside [0, 1] (or NaN) is taken as the nearest end.
  const std::vector<float> three = {3.0f, 1.0f, 2.0f};
  EXPECT_EQ(percentiles(three, {-0.5, 7.0, std::nan("")}), (std::vector<double>{1.0, 3.0, 1.0}));
}

}  // namespace
}  // namespace rc
