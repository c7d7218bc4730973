// The coverage audit (rasterizer/coverage_audit.h): silent on the rasterizer's own frames in
// every setting, and it finds a wrong fill rule, pixels changed by hand, and diagnostics more
// lenient than the frame's geometry allows.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "core/channels.h"
#include "rasterizer/coverage_audit.h"
#include "scenes/registry.h"
#include "scenes/scene_loader.h"
#include "tests/test_scenes.h"

namespace rc {
namespace {

struct Setting {
  const char* name;
  RasterOptions options;
};

std::vector<Setting> settings() {
  std::vector<Setting> all;
  for (int bits : {8, 4, 16, 0}) {
    RasterOptions o;
    o.subpixelBits = bits;
    all.push_back({bits == 0 ? "no snapping" : "subpixel bits", o});
  }
  RasterOptions twice;
  twice.precision = Precision::kDouble;
  all.push_back({"double", twice});
  twice.subpixelBits = 0;  // the audit's double records on the exact, unsnapped triangles
  all.push_back({"double, no snapping", twice});
  RasterOptions affine;
  affine.interpolation = Interpolation::kAffine;
  affine.culling = Culling::kNone;
  affine.depthMapping = DepthMapping::kStandard;
  all.push_back({"affine, no culling, standard depth", affine});
  return all;
}

std::size_t coveredCount(const Framebuffer& frame) {
  std::size_t n = 0;
  for (std::uint32_t id : frame.find(channels::kTriangleId)->uints) n += id != channels::kNoTriangle;
  return n;
}

TEST(CoverageAudit, FindsNothingInTheRasterizersOwnFrames) {
  for (const char* spec : {"fans", "edges", "subpixel", "grazing", "nearplane", "zfight", "closed", "huge", "blob:tris=2000"}) {
    for (const Setting& s : settings()) {
      const Scene scene = makeBuiltinScene(spec);
      const Framebuffer frame = rasterize(scene, s.options);
      const CoverageAudit audit = auditCoverage(scene, s.options, frame);
      const std::string where = std::string(spec) + ", " + s.name + " " + std::to_string(s.options.subpixelBits);
      EXPECT_EQ(audit.violations(), 0u) << where << ": first not owned at " << audit.firstNotOwned.x << ","
                                        << audit.firstNotOwned.y << ", first lost at " << audit.firstLost.x << ","
                                        << audit.firstLost.y;
      EXPECT_EQ(audit.covered, coveredCount(frame)) << where;
      EXPECT_EQ(audit.diagnosed, audit.covered) << where << ": every covered pixel's diagnostics checked";
      EXPECT_GT(audit.edgeBand, 0.0) << where;
      EXPECT_LE(audit.edgeBand, audit.edgeBandLimit) << where;
      EXPECT_EQ(audit.offGrid, 0u) << where;
      EXPECT_GT(audit.covered, 0u) << where;
    }
  }
}

// The scenes built to put pixel centres on shared edges do, so the fill rule decides pixels there.
TEST(CoverageAudit, CountsTheCentresTheFillRuleDecides) {
  for (const char* spec : {"fans", "edges", "subpixel"}) {
    const Scene scene = makeBuiltinScene(spec);
    const RasterOptions options;
    const CoverageAudit audit = auditCoverage(scene, options, rasterize(scene, options));
    EXPECT_GE(audit.onEdge, 10u) << spec;
    EXPECT_LT(audit.onEdge, audit.covered) << spec;
  }
}

TEST(CoverageAudit, FindsEveryWrongFillRule) {
  for (const char* spec : {"fans", "edges"}) {
    const Scene scene = makeBuiltinScene(spec);
    for (int bits : {8, 4}) {
      RasterOptions options;
      options.subpixelBits = bits;
      const std::size_t onEdge = auditCoverage(scene, options, rasterize(scene, options)).onEdge;

      // Inclusive: both triangles of a shared edge cover the centres on it, and the depth test
      // keeps one; where it keeps the one the top-left rule does not give them to, a pixel is
      // written by a triangle that does not own it. (Nothing is lost: the owner covers it too.)
      options.fillRule = FillRule::kInclusive;
      Framebuffer frame = rasterize(scene, options);
      EXPECT_EQ(frame.attributes.at("rastercheck.fillRule"), "inclusive");
      CoverageAudit audit = auditCoverage(scene, options, frame);
      EXPECT_GT(audit.notOwned, 0u) << spec << " at " << bits << " bits";
      EXPECT_LE(audit.notOwned, onEdge) << spec;
      EXPECT_EQ(audit.lost, 0u) << spec;
      const CoverageAudit::Pixel& p = audit.firstNotOwned;
      ASSERT_GE(p.x, 0);
      EXPECT_EQ(p.written, frame.find(channels::kTriangleId)->uints[std::size_t(p.y) * std::size_t(frame.width()) + std::size_t(p.x)]);

      // Exclusive: neither does; each such centre is left empty or to what lies behind.
      options.fillRule = FillRule::kExclusive;
      frame = rasterize(scene, options);
      audit = auditCoverage(scene, options, frame);
      EXPECT_EQ(audit.notOwned, 0u) << spec;
      EXPECT_EQ(audit.lost, onEdge) << spec << " at " << bits << " bits";
    }
  }
}

TEST(CoverageAudit, HoldsEachCornerToTheGridPointNearestItsRasterPosition) {
  const int bits = 8;
  const glm::dvec2 raster[3] = {{10.25, 3.5}, {-7.0 / 3.0, 0.0}, {100.0 + 0.5 / 256.0, 2.0 - 1.0 / 512.0}};
  // Rounded to nearest (the tie at 100 + 0.5 / 256 either way).
  const std::int32_t x[3] = {2624, -597, 25601}, y[3] = {896, 0, 512};
  EXPECT_EQ(cornersOffGrid(x, y, raster, bits), 0);
  const std::int32_t xTie[3] = {2624, -597, 25600};
  EXPECT_EQ(cornersOffGrid(xTie, y, raster, bits), 0);
  // Rounded down (the floor of -597.33 is -598), and one step off in y.
  const std::int32_t xDown[3] = {2624, -598, 25601}, yOff[3] = {897, 0, 510};
  EXPECT_EQ(cornersOffGrid(xDown, y, raster, bits), 1);
  EXPECT_EQ(cornersOffGrid(x, yOff, raster, bits), 2);
  EXPECT_EQ(cornersOffGrid(xDown, yOff, raster, bits), 3);
}

// Three triangles: 0 in front, 1 behind it over the same pixels, 2 off in a corner.
Scene layeredScene() {
  return testing::makeTriangleScene({{-1.5f, -1.5f, 0.0f}, {1.5f, -1.5f, 0.0f}, {0.0f, 1.5f, 0.0f},
                                     {-1.5f, -1.5f, -1.0f}, {1.5f, -1.5f, -1.0f}, {0.0f, 1.5f, -1.0f},
                                     {-2.0f, 1.4f, 0.0f}, {-1.8f, 1.4f, 0.0f}, {-1.9f, 1.6f, 0.0f}});
}

TEST(CoverageAudit, FindsPixelsChangedByHand) {
  const Scene scene = layeredScene();
  const RasterOptions options;
  const Framebuffer correct = rasterize(scene, options);
  ASSERT_EQ(auditCoverage(scene, options, correct).violations(), 0u);
  const int x = correct.width() / 2, y = correct.height() / 2;
  const std::size_t at = std::size_t(y) * std::size_t(correct.width()) + std::size_t(x);
  ASSERT_EQ(correct.find(channels::kTriangleId)->uints[at], 0u);

  struct Case {
    std::uint32_t id;
    std::size_t notOwned, lost;
  };
  // The farther triangle, nothing, and a triangle that does not cover the pixel.
  for (const Case& c : {Case{1, 0, 1}, Case{channels::kNoTriangle, 0, 1}, Case{2, 1, 0}}) {
    Framebuffer changed = rasterize(scene, options);
    changed.find(channels::kTriangleId)->uints[at] = c.id;
    const CoverageAudit audit = auditCoverage(scene, options, changed);
    EXPECT_EQ(audit.notOwned, c.notOwned) << "tri.id " << c.id;
    EXPECT_EQ(audit.lost, c.lost) << "tri.id " << c.id;
    const CoverageAudit::Pixel& p = c.lost ? audit.firstLost : audit.firstNotOwned;
    EXPECT_EQ(p.x, x);
    EXPECT_EQ(p.y, y);
    EXPECT_EQ(p.written, c.id);
    if (c.lost) {
      EXPECT_EQ(p.owner, 0u) << "the nearer owner";
    }
  }
}

// Two parallel triangles over the same pixels, the second farther by d, at w = 3: their 1/w
// keys differ by about d / 9, and each key's error bound is 5 u / 3 (float: u = 2^-24). A pixel
// written with the farther one is lost when the difference exceeds both bounds (d > 30 u), and
// within them a tie the depth test may decide either way. At half and one and a half times
// that: so the audit holds the depth test to its keys' error bounds, not to twice them.
TEST(CoverageAudit, HoldsTheDepthTestToBothKeysErrorBounds) {
  for (const double times : {0.5, 1.5}) {
    const float d = float(times * 30.0 * 0x1p-24);
    const Scene scene = testing::makeTriangleScene({{-1.5f, -1.5f, 0.0f}, {1.5f, -1.5f, 0.0f}, {0.0f, 1.5f, 0.0f},
                                                    {-1.5f, -1.5f, -d}, {1.5f, -1.5f, -d}, {0.0f, 1.5f, -d}});
    const RasterOptions options;
    Framebuffer frame = rasterize(scene, options);
    ASSERT_EQ(auditCoverage(scene, options, frame).violations(), 0u) << times;
    auto& ids = frame.find(channels::kTriangleId)->uints;
    const std::size_t at = std::size_t(frame.height() / 2) * std::size_t(frame.width()) + std::size_t(frame.width() / 2);
    ASSERT_EQ(ids[at], 0u) << "the nearer triangle, or the lower index in a tie";
    ids[at] = 1;
    const CoverageAudit audit = auditCoverage(scene, options, frame);
    EXPECT_EQ(audit.lost, times > 1.0 ? 1u : 0u) << "farther by " << times << " times both keys' bounds";
    EXPECT_EQ(audit.notOwned, 0u) << times;
  }
}

// The gate explains a disagreement by the edge.dist and depth.tie the rasterizer writes, and
// passes any error within its bound.bary and bound.depth; the audit holds all four to the
// set-up that owns the pixel. Shorter edge distances, wider depth ties and wider bounds than
// the set-up gives are found; the other way round (a stricter gate) is not a violation.
TEST(CoverageAudit, FindsDiagnosticsMoreLenientThanTheGeometry) {
  for (const char* spec : {"blob:tris=2000", "nearplane"}) {  // whole triangles; clipped ones
    const Scene scene = makeBuiltinScene(spec);
    const RasterOptions options;
    const Framebuffer correct = rasterize(scene, options);
    ASSERT_EQ(auditCoverage(scene, options, correct).violations(), 0u) << spec;
    const auto& ids = correct.find(channels::kTriangleId)->uints;
    const auto& edge = correct.find(channels::kEdgeDistance)->floats;
    const auto& tie = correct.find(channels::kDepthTie)->floats;
    // A pixel well inside its triangle, the first in row order.
    std::size_t at = 0;
    while (at < ids.size() && (ids[at] == channels::kNoTriangle || !(edge[at] > 0.4f))) ++at;
    ASSERT_LT(at, ids.size()) << spec;
    const int x = int(at % std::size_t(correct.width())), y = int(at / std::size_t(correct.width()));

    // One diagnostic at that pixel scaled by `factor`: found once, at the pixel, with the value
    // the frame had (to the rounding of the audit's double evaluation).
    struct Case {
      const char* channel;
      float factor;
      std::size_t CoverageAudit::*count;
      CoverageAudit::Diagnostic CoverageAudit::*first;
      double tolerance;  // of the audited value, relative to the frame's
    };
    for (const Case& c : {Case{channels::kEdgeDistance, 0.5f, &CoverageAudit::edgeDistanceShort,
                               &CoverageAudit::firstEdgeDistanceShort, 1e-5},
                          Case{channels::kEdgeDistance, 0.99f, &CoverageAudit::edgeDistanceShort,
                               &CoverageAudit::firstEdgeDistanceShort, 1e-5},
                          Case{channels::kDepthTie, 1.01f, &CoverageAudit::depthTieWide, &CoverageAudit::firstDepthTieWide, 1e-6},
                          Case{channels::kDepthTie, 1.0001f, &CoverageAudit::depthTieWide,
                               &CoverageAudit::firstDepthTieWide, 1e-6},
                          Case{channels::kBaryBound, 1.001f, &CoverageAudit::boundWide, &CoverageAudit::firstBoundWide, 0.0},
                          Case{channels::kDepthBound, 1.001f, &CoverageAudit::boundWide, &CoverageAudit::firstBoundWide,
                               0.0}}) {
      Framebuffer changed = correct;
      float& value = changed.find(c.channel)->floats[at];
      const double was = value;
      value *= c.factor;
      const CoverageAudit audit = auditCoverage(scene, options, changed);
      EXPECT_EQ(audit.*c.count, 1u) << spec << ", " << c.channel << " x " << c.factor;
      EXPECT_EQ(audit.violations(), 1u) << spec;
      const CoverageAudit::Diagnostic& first = audit.*c.first;
      EXPECT_EQ(first.x, x);
      EXPECT_EQ(first.y, y);
      EXPECT_EQ(first.triangle, ids[at]);
      EXPECT_EQ(first.written, double(value));
      EXPECT_NEAR(first.audited, was, c.tolerance * was) << spec << ", " << c.channel;
    }
    // Stricter diagnostics: a longer edge distance, a narrower tie, tighter bounds.
    Framebuffer stricter = correct;
    stricter.find(channels::kEdgeDistance)->floats[at] = edge[at] * 2.0f;
    stricter.find(channels::kDepthTie)->floats[at] = tie[at] * 0.5f;
    stricter.find(channels::kBaryBound)->floats[at] *= 0.5f;
    stricter.find(channels::kDepthBound)->floats[at] *= 0.5f;
    EXPECT_EQ(auditCoverage(scene, options, stricter).violations(), 0u) << spec;
  }
}

// The header's edge band against the ceiling worked out from the scene and the camera: at
// snapping's own sqrt(2)/2 grid steps where the transform's error is negligible, so that a band
// from one bit fewer (twice as wide) or an unreadable one fails.
TEST(CoverageAudit, HoldsTheHeadersEdgeBandToSnappingAndTheTransform) {
  for (const char* spec : {"blob:tris=2000", "nearplane", "huge"}) {
    const Scene scene = makeBuiltinScene(spec);
    for (int bits : {8, 4, 0}) {
      RasterOptions options;
      options.subpixelBits = bits;
      const Framebuffer correct = rasterize(scene, options);
      const double band = std::stod(correct.attributes.at(channels::header::kEdgeBand));
      EXPECT_EQ(auditCoverage(scene, options, correct).edgeBand, band) << spec;
      char twice[32];
      std::snprintf(twice, sizeof twice, "%.17g", 2.0 * edgeBandCeiling(scene, options));
      for (const char* text : {static_cast<const char*>(twice), "nan", "wide", "-0.5", "0.002 px"}) {
        Framebuffer changed = correct;
        changed.attributes[channels::header::kEdgeBand] = text;
        const CoverageAudit audit = auditCoverage(scene, options, changed);
        EXPECT_TRUE(audit.edgeBandWide()) << spec << " at " << bits << " bits, band " << text;
        EXPECT_EQ(audit.violations(), 1u) << spec;
      }
    }
    // Where the transform's error is negligible, the ceiling is snapping's steps.
    if (std::string(spec) == "blob:tris=2000") {
      const double ceiling = edgeBandCeiling(scene, RasterOptions{});
      EXPECT_NEAR(ceiling, 0.7072 / 256, 1e-6);
      EXPECT_GT(0.7072 / 128, 1.9 * ceiling) << "a band from one bit fewer fails";
    }
  }
}

// At the default 8 bits the ceiling is the band of every scene of `check default hard` within a
// thousandth, so a band only 1% wider fails each. Until session 39 it took the transform's shift
// at its worst for anything drawn (w at the near plane, |ndc| at the guard band), which let a
// band 20 times wide pass on `huge` and 127 times on `faroffset:offset=1e7`.
TEST(CoverageAudit, TheEdgeBandCeilingIsTheBandWithinAThousandthAtEightBits) {
  const RasterOptions options;
  for (const std::string& spec : expandSceneGroups({"default", "hard"})) {
    const Scene scene = makeBuiltinScene(spec);
    const double band = std::stod(rasterize(scene, options).attributes.at(channels::header::kEdgeBand));
    const double ceiling = edgeBandCeiling(scene, options);
    EXPECT_LE(band, ceiling) << spec;
    EXPECT_LE(ceiling, 1.0011 * band) << spec;
  }
}

// Found by checking `huge` through random cameras: a triangle whose w runs from 5e7 to -4e7 is
// clipped at a near plane of 0.1, and the clipper's double arithmetic puts the new vertex at
// w = 0.1 - 6e-9, whose shift the rasterizer's band rightly counts. The ceiling took every drawn
// w to be at least near, and fell short of the band by 6e-8 of it at each of these cameras.
TEST(CoverageAudit, TheEdgeBandCeilingCountsTheClippersRounding) {
  struct View {
    int width, height;
    glm::dvec3 eye, target;
    double fov;
    int bits;
    DepthMapping depth;
  };
  for (const View& v : {View{3, 200, {-1.18054801, 0.864845846, -0.329162645}, {-0.0583327191, 0.111128943, -0.289344795},
                             20.0, 1, DepthMapping::kStandard},
                        View{320, 240, {-0.0873906629, 3.81659204, 7.03036187}, {0.260026635, 0.293284277, -0.270779353},
                             179.0, 16, DepthMapping::kInverseW},
                        View{97, 61, {-0.578194208, -2.84971698, 0.738108775}, {-0.21491482, -0.245677508, -0.112513624},
                             179.0, 2, DepthMapping::kStandard}}) {
    SceneOverrides view;
    view.width = v.width, view.height = v.height;
    view.eye = v.eye, view.target = v.target, view.fovYDegrees = v.fov;
    const Scene scene = loadScene("huge", view);
    RasterOptions options;
    options.subpixelBits = v.bits;
    options.depthMapping = v.depth;
    const Framebuffer frame = rasterize(scene, options);
    const CoverageAudit audit = auditCoverage(scene, options, frame);
    EXPECT_EQ(audit.violations(), 0u) << v.bits << " bits: band " << audit.edgeBand << ", at most " << audit.edgeBandLimit;
    // Still within a ten-thousandth of the band: one bit fewer, or a band 1% wider, fails.
    EXPECT_LE(audit.edgeBandLimit, 1.0001 * audit.edgeBand) << v.bits << " bits";
  }
}

// compare explains a pixel one path drew at the near or far plane by the planes in either
// image's camera line; the frame's must be the scene's.
TEST(CoverageAudit, HoldsTheHeadersCameraLineToTheScene) {
  const Scene scene = makeBuiltinScene("nearplane");
  const RasterOptions options;
  Framebuffer frame = rasterize(scene, options);
  EXPECT_FALSE(auditCoverage(scene, options, frame).cameraMismatch);
  const std::string line = frame.attributes.at(channels::header::kCamera);
  const std::size_t near = line.find(" near=");
  ASSERT_NE(near, std::string::npos) << line;
  frame.attributes[channels::header::kCamera] = line.substr(0, near) + " near=0.5" + line.substr(line.find(' ', near + 1));
  CoverageAudit audit = auditCoverage(scene, options, frame);
  EXPECT_TRUE(audit.cameraMismatch) << frame.attributes.at(channels::header::kCamera);
  EXPECT_EQ(audit.violations(), 1u);
  frame.attributes.erase(channels::header::kCamera);
  EXPECT_TRUE(auditCoverage(scene, options, frame).cameraMismatch) << "no camera line";
}

TEST(CoverageAudit, LeavesAFrameWithoutDiagnosticsUndiagnosed) {
  const Scene scene = makeBuiltinScene("edges");
  RasterOptions options;
  options.diagnostics = false;
  const Framebuffer frame = rasterize(scene, options);
  ASSERT_EQ(frame.find(channels::kEdgeDistance), nullptr);
  const CoverageAudit audit = auditCoverage(scene, options, frame);
  EXPECT_EQ(audit.diagnosed, 0u);
  EXPECT_EQ(audit.violations(), 0u);
  EXPECT_GT(audit.covered, 0u);
}

// Found by checking slivers through random cameras: seen from 1.3 away with a field of view of
// 170 or 179 degrees, needles cross the near plane, and at 4 subpixel bits the snapped halves of
// a clipped needle turn over and overlap each other, so that two set-ups of one triangle cover
// the same centres. The depth test keeps one; its diagnostics must meet its own geometry, not
// its neighbour's (which the audit once required of them: 3 to 7 pixels of each kind failed a
// right rasterizer). Where the snapped half covers a centre its unsnapped plane puts behind the
// eye, the depth written is negative and so is the tie, whose slack once went the wrong way.
TEST(CoverageAudit, HoldsOverlappingSetUpsOfOneTriangleToTheOneThatWon) {
  struct Case {
    double fov;
    Precision precision;
  };
  for (const Case& c : {Case{179.0, Precision::kFloat}, Case{170.0, Precision::kFloat}, Case{179.0, Precision::kDouble}}) {
    SceneOverrides view;
    view.width = 320, view.height = 240;
    view.eye = glm::dvec3(-0.317436146, -1.3476794, 0.577056782);
    view.target = glm::dvec3(0.119009249, -0.164983302, 0.0811575854);
    view.fovYDegrees = c.fov;
    const Scene scene = loadScene("slivers", view);
    RasterOptions options;
    options.subpixelBits = 4;
    options.precision = c.precision;
    const std::string where = "fov " + std::to_string(c.fov) + ", " + precisionName(c.precision);
    // The premise: some centre is covered twice by one triangle.
    const Framebuffer frame = rasterize(scene, options);
    const auto& ids = frame.find(channels::kTriangleId)->uints;
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    std::size_t twice = 0, at = 0;
    for (const auto& pair : coveredPixels(scene, options)) {
      if (!seen.insert(pair).second && ids[pair.second] == pair.first) twice++, at = pair.second;
    }
    ASSERT_GT(twice, 0u) << where;
    const CoverageAudit audit = auditCoverage(scene, options, frame);
    EXPECT_EQ(audit.violations(), 0u) << where << ": " << audit.edgeDistanceShort << " edge distances short at "
                                      << audit.firstEdgeDistanceShort.x << "," << audit.firstEdgeDistanceShort.y << "; "
                                      << audit.boundWide << " bounds wide; " << audit.depthTieWide << " ties wide at "
                                      << audit.firstDepthTieWide.x << "," << audit.firstDepthTieWide.y;
    EXPECT_EQ(audit.diagnosed, audit.covered) << where << ": each pixel once";
    EXPECT_EQ(audit.covered, coveredCount(frame)) << where;
    // Diagnostics that meet neither set-up at a pixel covered twice are still found, there.
    Framebuffer changed = frame;
    changed.find(channels::kEdgeDistance)->floats[at] = -1.0f;
    changed.find(channels::kDepthTie)->floats[at] = std::numeric_limits<float>::infinity();
    changed.find(channels::kBaryBound)->floats[at] = std::numeric_limits<float>::infinity();
    const CoverageAudit wrong = auditCoverage(scene, options, changed);
    EXPECT_EQ(wrong.edgeDistanceShort, 1u) << where;
    EXPECT_EQ(wrong.depthTieWide, 1u) << where;
    EXPECT_EQ(wrong.boundWide, 1u) << where;
    EXPECT_EQ(wrong.violations(), 3u) << where;
    const int x = int(at % std::size_t(frame.width())), y = int(at / std::size_t(frame.width()));
    for (const CoverageAudit::Diagnostic* first :
         {&wrong.firstEdgeDistanceShort, &wrong.firstDepthTieWide, &wrong.firstBoundWide}) {
      EXPECT_EQ(first->x, x) << where;
      EXPECT_EQ(first->y, y) << where;
      EXPECT_EQ(first->triangle, ids[at]) << where;
    }
  }
}

}  // namespace
}  // namespace rc
