// compare's decisions at their limits (CompareLimits), and the heatmap's explanations of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "compare/colormap.h"
#include "compare/compare.h"
#include "compare/report.h"
#include "core/channels.h"
#include "core/error.h"
#include "scenes/camera.h"
#include "tests/compare/synthetic_images.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using namespace testing;  // tests/compare/synthetic_images.h

// compare's decisions at their limits, on synthetic images with diagnostics: each error bound,
// the edge band, the depth tie and the clip tie pass at exactly their limit and fail one float
// step beyond it (docs/numerics.md, "A lenient gate"). The values are powers of two and small
// multiples of them, so that every sum and ratio compare forms is exact. Without these, compare
// could be made more lenient (a bound doubled, a tie ten times wider, the gate at twice the
// bound) and no other test would notice: the renders the other tests compare are well inside
// the limits, and tests/mutants.txt holds these tests to eighteen such mutants.
constexpr double kBaryBoundTest = 0x1p-20, kBaryBoundRef = 0x1p-21;    // sum 3 * 2^-21
constexpr double kDepthBoundTest = 0x1p-20, kDepthBoundRef = 0x1p-21;  // sum 3 * 2^-21
constexpr double kBandTest = 0x1p-9, kBandRef = 0x1p-12;               // band 9 * 2^-12
constexpr double kTieTest = 0x1p-20, kResolutionRef = 0x1p-21;         // tie 3 * 2^-21
constexpr float kFar = 10.0f;  // edge.dist of a pixel far from every edge

// A header number as the rasterizer writes one: every digit, so that compare reads it back exactly.
std::string exactly(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// image() with the diagnostics of one path: the rasterizer's (`test`: depth.tie per pixel) or
// the reference's (its depth resolution in the header).
Framebuffer diagnosed(bool test) {
  Framebuffer fb = image();
  fb.addFloat(channels::kBaryBound, float(test ? kBaryBoundTest : kBaryBoundRef));
  fb.addFloat(channels::kDepthBound, float(test ? kDepthBoundTest : kDepthBoundRef));
  fb.addFloat(channels::kEdgeDistance, kFar);
  fb.attributes[channels::header::kEdgeBand] = exactly(test ? kBandTest : kBandRef);
  if (test) {
    fb.addFloat(channels::kDepthTie, float(kTieTest));
  } else {
    fb.attributes[channels::header::kDepthResolution] = exactly(kResolutionRef);
  }
  return fb;
}

// A pixel one path drew nothing at: id none, values and diagnostics 0, as both renderers write.
void empty(Framebuffer& fb, int x, int y) {
  idAt(fb, x, y) = channels::kNoTriangle;
  for (const Channel& c : fb.channels()) {
    if (c.type == ChannelType::kFloat) fb.find(c.name)->floats[std::size_t(y) * kW + std::size_t(x)] = 0.0f;
  }
}

CompareReport compared(const Framebuffer& test, const Framebuffer& ref) {
  return compareImages(test, "t.exr", ref, "r.exr", Thresholds{}, nullptr);
}

std::string reasons(const CompareReport& r) {
  std::string all;
  for (const std::string& reason : r.reasons) all += reason + "; ";
  return all;
}

TEST(CompareLimits, TheHeadersAndChannelsHereAreReadAsDiagnostics) {
  const CompareReport r = compared(diagnosed(true), diagnosed(false));
  EXPECT_TRUE(r.pass) << reasons(r);
  EXPECT_TRUE(r.explained);
  EXPECT_EQ(r.edgeBand, kBandTest + kBandRef);
  for (const FamilyReport& f : r.families) EXPECT_TRUE(f.bounded) << f.name;
}

// Each barycentric component, at (3, 1): the bound is 3 * 2^-21, 48 float steps of 0.25 and 24
// of 0.5. At the bound the ratio is exactly 1 and passes; one step more fails.
TEST(CompareLimits, EachBarycentricPassesAtItsBoundAndFailsOneStepBeyond) {
  for (int k = 0; k < 3; ++k) {
    const double step = k == 2 ? 0x1p-24 : 0x1p-25;
    const double steps = 3 * 0x1p-21 / step;
    for (const double n : {steps, steps + 1}) {
      Framebuffer test = diagnosed(true);
      at(test, channels::kBary[k], 3, 1) += float(n * step);
      const CompareReport r = compared(test, diagnosed(false));
      const FamilyReport& bary = family(r, "bary");
      EXPECT_EQ(bary.gated, n / steps) << "component " << k << ", " << n << " steps";
      EXPECT_EQ(r.pass, n == steps) << "component " << k << ", " << n << " steps: " << reasons(r);
      if (n > steps) {
        EXPECT_NE(reasons(r).find("bary: error reaches"), std::string::npos) << reasons(r);
      }
    }
  }
}

// Depth is relative: the bound 3 * 2^-21 of 4 is 12 float steps (2^-21 each) there.
TEST(CompareLimits, DepthPassesAtItsBoundAndFailsOneStepBeyond) {
  for (const int n : {12, 13}) {
    Framebuffer test = diagnosed(true);
    at(test, channels::kDepth, 5, 2) = float(4.0 + n * 0x1p-21);
    const CompareReport r = compared(test, diagnosed(false));
    EXPECT_EQ(family(r, "depth").gated, n / 12.0) << n;
    EXPECT_EQ(r.pass, n == 12) << n << " steps: " << reasons(r);
  }
}

// An attribute's bound is 3 (b_test + b_ref) range + 2^-21 (|a| + range): at uv.x = 2 in a
// range of 9, 3 * 3 * 2^-21 * 9 + 2^-21 * 11 = 92 * 2^-21, 184 float steps of 2^-22.
TEST(CompareLimits, AnAttributePassesAtItsBoundAndFailsOneStepBeyond) {
  for (const int n : {184, 185}) {
    Framebuffer test = diagnosed(true);
    at(test, channels::attributeChannel("uv", 0).c_str(), 2, 3) = float(2.0 + n * 0x1p-22);
    const CompareReport r = compared(test, diagnosed(false));
    EXPECT_EQ(family(r, "attr.uv").range, 9.0);
    EXPECT_EQ(family(r, "attr.uv").gated, n / 184.0) << n;
    EXPECT_EQ(r.pass, n == 184) << n << " steps: " << reasons(r);
  }
}

// Where the reference gives the hit triangle's spread of the attribute (spread.uv), the bound
// takes it in place of the image's range when it is wider: a triangle whose values reach far
// beyond what the image shows (a close-up, a small image) errs by its own spread times the
// barycentric error. A spread of 90 at (2, 3) makes the bound 3 * 3 * 2^-21 * 90 + 2^-21 *
// 92 = 902 * 2^-21, 1804 steps of 2^-22; a spread below the range changes nothing.
TEST(CompareLimits, AnAttributesBoundTakesTheTrianglesSpreadWhereItExceedsTheRange) {
  for (const float spread : {90.0f, 1.0f}) {
    const int steps = spread > 9.0f ? 1804 : 184;
    for (const int n : {steps, steps + 1}) {
      Framebuffer test = diagnosed(true), ref = diagnosed(false);
      ref.addFloat(channels::spreadChannel("uv"), spread);
      at(test, channels::attributeChannel("uv", 0).c_str(), 2, 3) = float(2.0 + n * 0x1p-22);
      const CompareReport r = compared(test, ref);
      EXPECT_EQ(family(r, "attr.uv").range, 9.0);
      EXPECT_EQ(family(r, "attr.uv").gated, double(n) / steps) << spread << ", " << n;
      EXPECT_EQ(r.pass, n == steps) << spread << ", " << n << " steps: " << reasons(r);
    }
  }
  // The test image's own spread channel, or one of another type, is not read as the reference's.
  Framebuffer test = diagnosed(true), ref = diagnosed(false);
  test.addFloat(channels::spreadChannel("uv"), 90.0f);
  at(test, channels::attributeChannel("uv", 0).c_str(), 2, 3) = float(2.0 + 185 * 0x1p-22);
  EXPECT_FALSE(compared(test, ref).pass);
  Framebuffer wrongType = diagnosed(false);
  wrongType.addUint(channels::spreadChannel("uv"), 90);
  rc::testing::expectError([&] { compared(test, wrongType); }, ExitCode::kBadInput,
                           {"r.exr: channel spread.uv", "is UINT"}, "a UINT spread");
}

// A pixel where the paths disagree on the triangle, 1 apart in depth (no tie), is explained
// when either path's edge.dist is within the sum of the headers' bands, and only then.
TEST(CompareLimits, ADisagreementIsInTheEdgeBandUpToTheSumOfBothBandsFromEitherPath) {
  const float band = float(kBandTest + kBandRef);
  const float beyond = std::nextafter(band, 1.0f);
  for (const bool fromTest : {true, false}) {
    for (const float distance : {band, beyond}) {
      Framebuffer test = diagnosed(true), ref = diagnosed(false);
      idAt(test, 6, 0) = 2;
      at(test, channels::kDepth, 6, 0) = 5.0f;
      at(fromTest ? test : ref, channels::kEdgeDistance, 6, 0) = distance;
      const CompareReport r = compared(test, ref);
      const bool inBand = distance == band;
      EXPECT_EQ(r.explanationCounts[int(Explanation::kEdgeBand)], inBand ? 1u : 0u) << fromTest;
      EXPECT_EQ(r.explanationCounts[int(Explanation::kUnexplained)], inBand ? 0u : 1u) << fromTest;
      EXPECT_EQ(r.pass, inBand) << (fromTest ? "test" : "reference") << " edge.dist " << distance << ": " << reasons(r);
      if (!inBand) {
        EXPECT_NE(reasons(r).find("1 disagreements neither in the edge band nor a depth tie, first at (6,0)"),
                  std::string::npos)
            << reasons(r);
      }
    }
  }
}

// The heatmap: explanation.id names why each disagreement is allowed (or that it is not) and
// marks every agreeing pixel kNothingToExplain; R, G and B colour the quantity --heatmap-shows
// names, from its own plane on its own scale, and the header records which.
TEST(CompareHeatmap, ExplanationsMarkOnlyDisagreementsAndTheColoursShowTheChosenQuantity) {
  Framebuffer test = diagnosed(true), ref = diagnosed(false);
  idAt(test, 6, 0) = 2;  // another triangle at an edge: explained
  at(test, channels::kDepth, 6, 0) = 5.0f;
  at(test, channels::kEdgeDistance, 6, 0) = float(kBandTest);
  idAt(test, 7, 0) = 2;  // another triangle far from every edge and 1 deeper: unexplained
  at(test, channels::kDepth, 7, 0) = 5.0f;
  at(test, channels::kBary[0], 3, 1) += float(0x1p-22);  // 4 ulps of 2^-24, a sixth of the bound
  const std::size_t shown = std::size_t(1) * kW + 3;
  std::vector<float> colours;
  for (const auto& [quantity, key, value] : {std::tuple{HeatmapQuantity::kError, "error", 0x1p-22},
                                             std::tuple{HeatmapQuantity::kUlps, "ulps", 4.0},
                                             std::tuple{HeatmapQuantity::kBoundRatio, "bound", 1.0 / 6.0}}) {
    Thresholds t;
    t.heatmap = quantity;
    Framebuffer heatmap;
    compareImages(test, "t.exr", ref, "r.exr", t, &heatmap);
    const auto& explanation = heatmap.find("explanation.id")->uints;
    EXPECT_EQ(explanation[6], std::uint32_t(Explanation::kEdgeBand)) << key;
    EXPECT_EQ(explanation[7], std::uint32_t(Explanation::kUnexplained)) << key;
    for (std::size_t i = 0; i < explanation.size(); ++i) {
      if (i != 6 && i != 7) {
        EXPECT_EQ(explanation[i], kNothingToExplain) << key << ", pixel " << i;
      }
    }
    EXPECT_EQ(heatmap.attributes.at("rastercheck.heatmapQuantity"), key);
    EXPECT_EQ(heatmap.find("error.bary")->floats[shown], float(0x1p-22));
    EXPECT_EQ(heatmap.find("ulps.bary")->floats[shown], 4.0f);
    EXPECT_NEAR(heatmap.find("ratio.bary")->floats[shown], 1.0 / 6.0, 1e-7);
    const Rgb expected = linearFromSrgb(heatColour(value, heatScaleByKey(key)));
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(heatmap.find(std::string(1, "RGB"[k]))->floats[shown], expected[k], 1e-6) << key << ", channel " << k;
      colours.push_back(heatmap.find(std::string(1, "RGB"[k]))->floats[shown]);
    }
  }
  EXPECT_NE(colours[0], colours[3]);  // error and ulps put the same pixel at different places on their scales
  EXPECT_NE(colours[3], colours[6]);
  // Without the diagnostics there is no bound: "bound" falls back to the error, and says so.
  Thresholds t;
  t.heatmap = HeatmapQuantity::kBoundRatio;
  Framebuffer heatmap;
  compareImages(image(), "t.exr", image(), "r.exr", t, &heatmap);
  EXPECT_EQ(heatmap.attributes.at("rastercheck.heatmapQuantity"), "error");
  EXPECT_EQ(heatmap.find("ratio.bary"), nullptr);
  const auto& explanation = heatmap.find("explanation.id")->uints;  // without them, what the ids show
  EXPECT_TRUE(std::all_of(explanation.begin(), explanation.end(), [](std::uint32_t e) { return e == kNothingToExplain; }));
}

// A path that drew nothing at a pixel writes 0 there for its edge distance: that is no
// distance to an edge, and must not explain the other path's pixel.
TEST(CompareLimits, AnEmptyPixelsEdgeDistanceExplainsNothing) {
  for (const bool testDrew : {true, false}) {
    Framebuffer test = diagnosed(true), ref = diagnosed(false);
    empty(testDrew ? ref : test, 1, 1);
    const CompareReport r = compared(test, ref);
    EXPECT_EQ(r.explanationCounts[int(Explanation::kUnexplained)], 1u) << testDrew;
    EXPECT_FALSE(r.pass) << testDrew;
  }
}

// Two surfaces whose depths differ by at most 2 (tie_test + resolution_ref) times the larger
// are a depth tie: at 4 that is 6 * 2^-21 * (4 + d), 24 float steps and not 25.
TEST(CompareLimits, ADisagreementIsADepthTieUpToTwiceBothPathsResolutions) {
  for (const int n : {24, 25}) {
    Framebuffer test = diagnosed(true);
    idAt(test, 4, 2) = 2;
    at(test, channels::kDepth, 4, 2) = float(4.0 + n * 0x1p-21);
    const CompareReport r = compared(test, diagnosed(false));
    EXPECT_EQ(r.explanationCounts[int(Explanation::kDepthTie)], n == 24 ? 1u : 0u) << n;
    EXPECT_EQ(r.pass, n == 24) << n << " steps: " << reasons(r);
  }
}

// A pixel only one path drew, off every edge, is a clip tie when its depth lies within
// 2 tie z of a clipping plane in either image's camera line, and only then. Where the test
// drew, tie = its depth.tie + the reference's resolution (3 * 2^-21): 24 steps of 2^-21 at 4.
// Where only the reference drew, the test's depth.tie there is 0: 8 steps.
TEST(CompareLimits, APixelOnlyOnePathDrewIsAClipTieUpToTwiceTheResolutionsFromEitherPlane) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  struct Case {
    double zNear, zFar;
    bool inTest, testDrew;
    int limit;
  };
  for (const Case c : {Case{4.0, kInf, true, true, 24}, Case{0.5, 4.0, true, true, 24}, Case{4.0, kInf, false, true, 24},
                       Case{4.0, kInf, true, false, 8}, Case{0.5, 4.0, false, false, 8}}) {
    // The camera line as the renderers write it (Camera::describe, which compare parses).
    CameraSpec spec = lookAt({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 60.0, c.zNear, kW, kH);
    spec.zFar = c.zFar;
    const std::string planes = "near=" + exactly(c.zNear) + " far=" + exactly(c.zFar);
    for (const int n : {c.limit, c.limit + 1}) {
      Framebuffer test = diagnosed(true), ref = diagnosed(false);
      (c.inTest ? test : ref).attributes[channels::header::kCamera] = Camera(spec, "limits").describe();
      empty(c.testDrew ? ref : test, 7, 8);
      at(c.testDrew ? test : ref, channels::kDepth, 7, 8) = float(4.0 + n * 0x1p-21);
      const CompareReport r = compared(test, ref);
      const std::string what = planes + (c.inTest ? " in the test's header" : " in the reference's") +
                               (c.testDrew ? ", test drew" : ", reference drew") + ", " + std::to_string(n) + " steps";
      EXPECT_EQ(r.explanationCounts[int(Explanation::kDepthTie)], n == c.limit ? 1u : 0u) << what;
      EXPECT_EQ(r.pass, n == c.limit) << what << ": " << reasons(r);
    }
  }
}

// Without diagnostics (a renderer of your own, --no-diagnostics) compare falls back to fixed
// limits: each passes at exactly its value and fails just beyond it. Barycentrics and relative
// depth at 2^-12 (a float step of 0.25 is 2^-25, of 4 is 2^-21); an attribute at 2^-12 of its
// range (9: the step at uv.y = 8 is 2^-20); each fraction at 2 of the 100 covered pixels.
TEST(CompareLimits, WithoutDiagnosticsEachFixedLimitPassesAtItsValueAndFailsBeyond) {
  Thresholds limits;
  limits.bary = limits.depth = limits.attribute = 0x1p-12;
  limits.disagreement = limits.coverage = 0.02;
  struct Case {
    const char* what;
    std::function<void(Framebuffer&, bool beyond)> change;
  };
  const Case cases[] = {
      {"bary.b2 (the last)",
       [](Framebuffer& t, bool beyond) { at(t, channels::kBary[2], 1, 1) = 0.5f + 0x1p-12f + (beyond ? 0x1p-24f : 0.0f); }},
      {"depth", [](Framebuffer& t, bool beyond) { at(t, channels::kDepth, 2, 2) = 4.0f + 0x1p-10f + (beyond ? 0x1p-21f : 0.0f); }},
      {"attr.uv.y (the last)",
       [](Framebuffer& t, bool beyond) {
         at(t, channels::attributeChannel("uv", 1), 3, 8) = 8.0f + 9.0f * 0x1p-12f + (beyond ? 0x1p-20f : 0.0f);
       }},
      {"different triangle",
       [](Framebuffer& t, bool beyond) {
         for (int x = 0; x < (beyond ? 3 : 2); ++x) {
           idAt(t, x, 5) = 2;
           at(t, channels::kDepth, x, 5) = 5.0f;  // 1 deeper: no tie (the depth limit is 2^-12 here)
         }
       }},
      {"one side only",
       [](Framebuffer& t, bool beyond) {
         for (int x = 0; x < (beyond ? 3 : 2); ++x) idAt(t, x, 6) = channels::kNoTriangle;
       }},
  };
  for (const Case& c : cases) {
    for (const bool beyond : {false, true}) {
      Framebuffer test = image();
      c.change(test, beyond);
      const CompareReport r = compareImages(test, "t.exr", image(), "r.exr", limits, nullptr);
      EXPECT_FALSE(r.explained);
      EXPECT_EQ(r.pass, !beyond) << c.what << (beyond ? " beyond" : " at") << " its limit: " << reasons(r);
      EXPECT_EQ(r.reasons.size(), beyond ? 1u : 0u) << c.what << ": " << reasons(r);
    }
  }
}

// Without diagnostics, a disagreement must also lie at an edge of either image's ids (a
// neighbour of the eight with another id, or the image's border) or be a depth tie within the
// depth limit: a right renderer's pixel of another triangle lies within snapping's reach of an
// edge, so next to a pixel of another id in one of the images. A 3x3 block of another triangle
// (the fractions let through) has 8 pixels at such an edge and 1 inside, which fails unless its
// depth ties within the limit (the same steps as the fixed limits' test above); a block
// against the border has no pixel inside. Depth ties, where either answer is right, are left
// out of the fractions the fixed limits gate.
TEST(CompareLimits, WithoutDiagnosticsADisagreementLiesAtAnEdgeOfTheIdsOrTiesInDepth) {
  Thresholds limits;
  limits.depth = 0x1p-12;
  limits.disagreement = limits.coverage = 1.0;
  const auto block = [](int x0, std::uint32_t id, float depth) {
    Framebuffer test = image();
    for (int y = 3; y < 6; ++y) {
      for (int x = std::max(x0, 0); x < x0 + 3; ++x) {
        idAt(test, x, y) = id;
        at(test, channels::kDepth, x, y) = depth;
      }
    }
    return test;
  };
  struct Case {
    const char* what;
    Framebuffer test;
    std::size_t disagreeing, inside, ties;
  };
  const Case cases[] = {
      {"another triangle 1 deeper", block(3, 2, 5.0f), 9, 1, 0},
      {"another triangle at the depth limit", block(3, 2, 4.0f + 0x1p-10f), 9, 0, 9},
      {"another triangle just beyond it", block(3, 2, 4.0f + 0x1p-10f + 0x1p-21f), 9, 1, 0},
      {"nothing drawn", block(3, channels::kNoTriangle, 0.0f), 9, 1, 0},
      {"another triangle against the border, two columns of it", block(-1, 2, 5.0f), 6, 0, 0},
  };
  for (const Case& c : cases) {
    Framebuffer heatmap;
    const CompareReport r = compareImages(c.test, "t.exr", image(), "r.exr", limits, &heatmap);
    EXPECT_FALSE(r.explained) << c.what;
    EXPECT_EQ(r.explanationCounts[int(Explanation::kIdEdge)], c.disagreeing - c.inside - c.ties) << c.what;
    EXPECT_EQ(r.explanationCounts[int(Explanation::kDepthTie)], c.ties) << c.what;
    EXPECT_EQ(r.explanationCounts[int(Explanation::kUnexplained)], c.inside) << c.what;
    EXPECT_EQ(r.explanationCounts[int(Explanation::kEdgeBand)], 0u) << c.what;
    EXPECT_EQ(r.pass, c.inside == 0) << c.what << ": " << reasons(r);
    const std::uint32_t centre = heatmap.find("explanation.id")->uints[std::size_t(4) * kW + 4];
    const std::uint32_t corner = heatmap.find("explanation.id")->uints[std::size_t(3) * kW + 3];
    if (c.disagreeing == 9) {
      EXPECT_EQ(centre, std::uint32_t(c.inside ? Explanation::kUnexplained : Explanation::kDepthTie)) << c.what;
      EXPECT_EQ(corner, std::uint32_t(c.ties ? Explanation::kDepthTie : Explanation::kIdEdge)) << c.what;
      EXPECT_EQ(heatmap.find("R")->floats[std::size_t(4) * kW + 4], c.inside ? linearFromSrgb(kColourUnexplained)[0] : 0.0f)
          << c.what;
    }
    if (c.inside) {
      EXPECT_EQ(r.reasons, std::vector<std::string>{"1 disagreements away from every edge of both images' ids and not a "
                                                    "depth tie, first at (4,4)"})
          << c.what;
      const bool oneSide = r.classCounts[int(PixelClass::kReferenceOnly)] > 0;
      EXPECT_EQ(reportToJson(r)["disagreements"],
                (nlohmann::json{{"by", "ids"},
                                {"depth_tie", 0},
                                {"unexplained", 1},
                                {"id_edge", 8},
                                {"first_unexplained", {{"x", 4}, {"y", 4}}},
                                {"untied_disagreement_fraction", oneSide ? 0.0 : 0.09},
                                {"untied_coverage_fraction", oneSide ? 0.09 : 0.0}}))
          << c.what;
      EXPECT_NE(reportToTable(r).find("disagreements: 8 at an edge of the ids, 0 depth ties (within the depth limit), "
                                      "1 unexplained\n"),
                std::string::npos)
          << reportToTable(r);
    }
  }
  limits.disagreement = 0.0;
  const CompareReport tied = compareImages(block(3, 2, 4.0f + 0x1p-10f), "t.exr", image(), "r.exr", limits, nullptr);
  EXPECT_TRUE(tied.pass) << reasons(tied);
  EXPECT_EQ(reportToJson(tied)["disagreement_fraction"], 0.09);
  EXPECT_EQ(reportToJson(tied)["disagreements"]["untied_disagreement_fraction"], 0.0);
  const CompareReport deeper = compareImages(block(3, 2, 5.0f), "t.exr", image(), "r.exr", limits, nullptr);
  EXPECT_NE(reasons(deeper).find("different triangle (depth ties left out) at 0.09 of covered pixels, limit 0;"),
            std::string::npos)
      << reasons(deeper);
}

}  // namespace
}  // namespace rc
