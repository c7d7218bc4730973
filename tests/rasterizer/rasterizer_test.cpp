// End-to-end rasterizer behaviour against an independent analytic answer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/channels.h"
#include "core/clock.h"
#include "rasterizer/rasterizer.h"
#include "rasterizer/setup.h"
#include "scenes/registry.h"
#include "tests/analytic.h"
#include "tests/same_bits.h"
#include "tests/test_scenes.h"

namespace rc {
namespace {

struct Accuracy {
  int covered = 0;
  double baryError = 0.0, depthError = 0.0, uvError = 0.0;
  bool allFinite = true;
  bool idsValid = true;
};

// Measures every covered pixel of `fb` against the analytic hit of the pixel's triangle.
Accuracy measure(const Scene& scene, const Framebuffer& fb) {
  Accuracy a;
  const auto& ids = fb.find(channels::kTriangleId)->uints;
  const float* b[3] = {fb.find(channels::kBary[0])->floats.data(), fb.find(channels::kBary[1])->floats.data(),
                       fb.find(channels::kBary[2])->floats.data()};
  const float* depth = fb.find(channels::kDepth)->floats.data();
  const float* u = fb.find(channels::attributeChannel("uv", 0))->floats.data();
  for (int y = 0; y < fb.height(); ++y) {
    for (int x = 0; x < fb.width(); ++x) {
      const std::size_t i = std::size_t(y) * fb.width() + x;
      if (ids[i] == channels::kNoTriangle) continue;
      if (ids[i] >= scene.mesh.triangleCount()) {
        a.idsValid = false;
        continue;
      }
      ++a.covered;
      const testing::Analytic truth = testing::analyticHit(scene, ids[i], x, y);
      long double uTruth = 0;
      const glm::uvec3 t = scene.mesh.triangles[ids[i]];
      const std::uint32_t corner[3] = {t.x, t.y, t.z};
      for (int k = 0; k < 3; ++k) {
        a.allFinite = a.allFinite && std::isfinite(b[k][i]);
        a.baryError = std::max(a.baryError, double(std::fabs(b[k][i] - truth.b[k])));
        uTruth += truth.b[k] * scene.mesh.positions[corner[k]].x;
      }
      a.allFinite = a.allFinite && std::isfinite(depth[i]) && std::isfinite(u[i]);
      a.depthError = std::max(a.depthError, double(std::fabs(depth[i] - truth.depth) / truth.depth));
      a.uvError = std::max(a.uvError, double(std::fabs(u[i] - uTruth)));
    }
  }
  return a;
}

RasterOptions options(Precision precision, int threads = 1) {
  RasterOptions o;
  o.precision = precision;
  o.threads = threads;
  return o;
}

TEST(Rasterizer, TiltedTriangleMatchesAnalyticBarycentricsInBothPrecisions) {
  const Scene scene = testing::makeTriangleScene({{-1.2f, -0.9f, -2.0f}, {1.4f, -0.5f, 0.8f}, {0.1f, 1.1f, -0.4f}});
  const Accuracy exact = measure(scene, rasterize(scene, options(Precision::kDouble)));
  EXPECT_GT(exact.covered, 300);
  EXPECT_LT(exact.baryError, 1e-7);  // float output rounding of values in [0, 1]
  EXPECT_LT(exact.depthError, 1e-7);
  const Accuracy single = measure(scene, rasterize(scene, options(Precision::kFloat)));
  EXPECT_EQ(single.covered, exact.covered);  // coverage does not depend on precision
  EXPECT_LT(single.baryError, 2e-6);
  EXPECT_LT(single.depthError, 2e-6);
}

TEST(Rasterizer, NearPlaneCrossingTriangleKeepsSourceIdAndBarycentrics) {
  // One vertex behind the eye (z = 3), two in front: the clipped polygon is rendered as
  // sub-triangles whose barycentrics must still refer to the source triangle.
  const Scene scene =
      testing::makeTriangleScene({{-1.0f, -0.6f, 0.0f}, {1.0f, -0.6f, 0.0f}, {0.0f, -0.3f, 6.0f}});
  for (Precision precision : {Precision::kDouble, Precision::kFloat}) {
    const Framebuffer fb = rasterize(scene, options(precision));
    const Accuracy a = measure(scene, fb);
    EXPECT_GT(a.covered, 300) << precisionName(precision);
    EXPECT_TRUE(a.idsValid);
    EXPECT_TRUE(a.allFinite);
    EXPECT_LT(a.baryError, precision == Precision::kDouble ? 1e-6 : 1e-4) << precisionName(precision);
    EXPECT_LT(a.depthError, precision == Precision::kDouble ? 1e-6 : 1e-4) << precisionName(precision);
    const float* depth = fb.find(channels::kDepth)->floats.data();
    for (std::size_t i = 0; i < fb.pixelCount(); ++i) {
      if (fb.find(channels::kTriangleId)->uints[i] != channels::kNoTriangle) {
        ASSERT_GE(depth[i], float(scene.camera.zNear()) * (1 - 1e-5f)) << "drawn in front of near";
      }
    }
  }
}

TEST(Rasterizer, TriangleBehindTheEyeDrawsNothing) {
  const Scene scene = testing::makeTriangleScene({{-1.0f, -1.0f, 4.0f}, {1.0f, -1.0f, 4.0f}, {0.0f, 1.0f, 5.0f}});
  const Framebuffer fb = rasterize(scene, options(Precision::kFloat));
  const auto& ids = fb.find(channels::kTriangleId)->uints;
  for (std::uint32_t id : ids) ASSERT_EQ(id, channels::kNoTriangle);
}

TEST(Rasterizer, OutputBitsAreIdenticalForOneAndTwoThreads) {
  const Scene scene = makeBuiltinScene("blob:tris=20000");
  const Framebuffer one = rasterize(scene, options(Precision::kFloat, 1));
  const Framebuffer two = rasterize(scene, options(Precision::kFloat, 2));
  const Framebuffer again = rasterize(scene, options(Precision::kFloat, 2));
  EXPECT_EQ(testing::differingChannels(one, two), std::vector<std::string>{});
  EXPECT_EQ(testing::differingChannels(one, again), std::vector<std::string>{});
  EXPECT_EQ(one.attributes, two.attributes);
}

// The instruction sets this CPU can run beyond SSE2.
std::vector<KernelIsa> widerKernelIsas() {
  std::vector<KernelIsa> isas;
  for (KernelIsa isa : {KernelIsa::kAvx2, KernelIsa::kAvx512}) {
    try {
      isas.push_back(resolveKernelIsa(isa));
    } catch (const std::exception&) {  // this CPU lacks it
    }
  }
  return isas;
}

// A frame's header attributes but the kernel's name.
std::map<std::string, std::string> headerButKernel(const Framebuffer& fb) {
  std::map<std::string, std::string> header = fb.attributes;
  header.erase("rastercheck.kernelIsa");
  return header;
}

// A float set-up whose own error bound gives up (setup.h's kPromoteAbove: slivers' needles,
// whose planes reach 1e7 and more) is resolved again in double. No pixel of a float frame then
// carries a bound above that, and a pixel so resolved has the double frame's bits wherever the
// same triangle won it: the same double set-up and resolve. Its bounds are the double ones,
// which a float set-up's never equal, and that is how the test finds such pixels; the depth
// tie alone stays the float key's.
TEST(Rasterizer, FloatResolvesInDoubleWhatItsOwnBoundGivesUpOn) {
  std::size_t promoted = 0;
  for (const char* spec : {"slivers", "perspective"}) {
    const Scene scene = makeBuiltinScene(spec);
    const Framebuffer single = rasterize(scene, options(Precision::kFloat, 2));
    const Framebuffer twice = rasterize(scene, options(Precision::kDouble, 2));
    const auto& ids = single.find(channels::kTriangleId)->uints;
    const auto& idsTwice = twice.find(channels::kTriangleId)->uints;
    const auto bitsOf = [](const Framebuffer& fb, const char* name, std::size_t i) {
      std::uint32_t bits;
      std::memcpy(&bits, &fb.find(name)->floats[i], sizeof bits);
      return bits;
    };
    std::size_t found = 0;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (ids[i] == channels::kNoTriangle) continue;
      const bool doubles = ids[i] == idsTwice[i] &&
                           bitsOf(single, channels::kBaryBound, i) == bitsOf(twice, channels::kBaryBound, i) &&
                           bitsOf(single, channels::kDepthBound, i) == bitsOf(twice, channels::kDepthBound, i);
      // Above the limit only where double gives up too (perspective's 1e6 depth ratio: 0.64).
      const bool within = single.find(channels::kBaryBound)->floats[i] <= kPromoteAbove &&
                          single.find(channels::kDepthBound)->floats[i] <= kPromoteAbove;
      ASSERT_TRUE(within || doubles) << spec << " pixel " << i << ": a float bound above the limit";
      if (!doubles) continue;
      ++found;
      for (const Channel& c : single.channels()) {
        if (c.type != ChannelType::kFloat || c.name == channels::kDepthTie) continue;
        ASSERT_EQ(bitsOf(single, c.name.c_str(), i), bitsOf(twice, c.name.c_str(), i))
            << spec << " " << c.name << " pixel " << i;
      }
    }
    // The header counts them; where the float key chose another winner than the double one, a
    // pixel resolved in double is not found above.
    const std::size_t counted = std::stoull(single.attributes.at(channels::header::kPromotedPixels));
    EXPECT_GE(counted, found) << spec;
    EXPECT_GE(found, counted * 9 / 10) << spec;
    EXPECT_EQ(twice.attributes.count(channels::header::kPromotedPixels), 0u) << "a double frame promotes nothing";
    promoted += found;
  }
  EXPECT_GT(promoted, 100u);
}

// The SSE2, AVX2 and AVX-512 kernels run the same IEEE operations lane by lane: the same bits,
// for both precisions and modes, on scenes with clipping, attributes and slivers, and the same
// header (the edge band comes from the transform's facts, which each instruction set finds).
TEST(Rasterizer, OutputBitsAreIdenticalOnEveryKernelIsa) {
  const std::vector<KernelIsa> wider = widerKernelIsas();
  if (wider.empty()) GTEST_SKIP() << "this CPU has no AVX2";
  for (const char* spec : {"blob:tris=20000", "nearplane", "attributes", "slivers", "huge", "cube"}) {
    const Scene scene = makeBuiltinScene(spec);
    for (Precision precision : {Precision::kFloat, Precision::kDouble}) {
      for (Interpolation mode : {Interpolation::kPerspective, Interpolation::kAffine}) {
        RasterOptions o = options(precision);
        o.interpolation = mode;
        o.isa = KernelIsa::kSse2;
        const Framebuffer sse2 = rasterize(scene, o);
        EXPECT_EQ(sse2.attributes.at("rastercheck.kernelIsa"), "sse2");
        for (KernelIsa isa : wider) {
          o.isa = isa;
          const Framebuffer other = rasterize(scene, o);
          // The header names the kernel; everything else must match.
          EXPECT_EQ(other.attributes.at("rastercheck.kernelIsa"), kernelIsaName(isa));
          EXPECT_EQ(testing::differingChannels(sse2, other), std::vector<std::string>{})
              << spec << " " << precisionName(precision) << " " << interpolationName(mode) << " "
              << kernelIsaName(isa);
          EXPECT_EQ(headerButKernel(sse2), headerButKernel(other)) << spec << " " << kernelIsaName(isa);
        }
      }
    }
  }
}

// Without snapping (--subpixel-bits none) too: the kernels' coverage decides each centre
// exactly, so every instruction set and thread count gives the same bits, on scenes with
// clipped triangles, slivers and sub-pixel triangles; and the header records it.
TEST(Rasterizer, UnsnappedCoverageGivesTheSameBitsOnEveryKernelIsaAndThreadCount) {
  const std::vector<KernelIsa> wider = widerKernelIsas();
  for (const char* spec : {"blob:tris=20000", "nearplane", "slivers", "subpixel", "huge"}) {
    const Scene scene = makeBuiltinScene(spec);
    for (Precision precision : {Precision::kFloat, Precision::kDouble}) {
      RasterOptions o = options(precision, 2);
      o.subpixelBits = 0;
      o.isa = KernelIsa::kSse2;
      const Framebuffer sse2 = rasterize(scene, o);
      EXPECT_EQ(sse2.attributes.at("rastercheck.subpixelBits"), "none");
      o.threads = 1;
      EXPECT_EQ(testing::differingChannels(sse2, rasterize(scene, o)), std::vector<std::string>{}) << spec << " 1 thread";
      o.threads = 2;
      for (KernelIsa isa : wider) {
        o.isa = isa;
        const Framebuffer other = rasterize(scene, o);
        EXPECT_EQ(testing::differingChannels(sse2, other), std::vector<std::string>{})
            << spec << " " << precisionName(precision) << " " << kernelIsaName(isa);
        EXPECT_EQ(headerButKernel(sse2), headerButKernel(other)) << spec << " " << kernelIsaName(isa);
      }
    }
  }
}

// auto takes the widest level the CPU has.
TEST(Rasterizer, AutoPicksTheWidestKernelIsa) {
  const std::vector<KernelIsa> wider = widerKernelIsas();
  EXPECT_EQ(resolveKernelIsa(KernelIsa::kAuto), wider.empty() ? KernelIsa::kSse2 : wider.back());
  EXPECT_EQ(resolveKernelIsa(KernelIsa::kSse2), KernelIsa::kSse2);
}

// bench's write-out floor writes what a frame writes: every value of every channel, the uint
// id plane and the float planes alike, in the partial tiles of an image that is no multiple of
// 64 wide or high (rows whose starts are not 32-byte aligned take the narrower stores), on any
// number of threads and with every instruction set's stores.
TEST(Rasterizer, WriteOutPassWritesEveryValueOfEveryChannel) {
  Scene scene = makeBuiltinScene("attributes");
  CameraSpec spec = scene.camera.spec();
  spec.width = 133, spec.height = 70;
  scene.camera = Camera(spec);
  std::vector<KernelIsa> isas = widerKernelIsas();
  isas.insert(isas.begin(), KernelIsa::kSse2);
  for (KernelIsa isa : isas) {
    for (int threads : {1, 3}) {
      RasterOptions o = options(Precision::kFloat, threads);
      o.isa = isa;
      Framebuffer fb;
      Rasterizer(o).render(scene, fb);
      ASSERT_GT(fb.channels().size(), 9u) << "diagnostics and attributes included";
      const std::uint32_t value = 0x3F8CCCCDu + std::uint32_t(threads);
      const double ms = writeOutPass(fb, value, o);
      EXPECT_GT(ms, 0.0);
      for (const Channel& c : fb.channels()) {
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < fb.pixelCount(); ++i) {
          std::uint32_t bits;
          if (c.type == ChannelType::kFloat) {
            std::memcpy(&bits, &c.floats[i], sizeof bits);
          } else {
            bits = c.uints[i];
          }
          wrong += bits != value;
        }
        EXPECT_EQ(wrong, 0u) << c.name << ", " << kernelIsaName(isa) << ", " << threads << " threads";
      }
    }
  }
}

// A row chunk of several winners is resolved either in one pass over its lanes, each lane
// reading its winner's packed record (tile_gather.h), or winner by winner (tile_resolve.h);
// each lane must run the same operations either way. Small triangles give most chunks several
// winners; nearplane has clipped winners, attributes several attribute sets, and every
// instruction set has the gathered path.
TEST(Rasterizer, GatheredResolveGivesTheSameBitsAsWinnerByWinner) {
  for (const char* spec : {"blob:tris=200000", "blob:tris=20000", "attributes", "nearplane", "subpixel", "slivers"}) {
    const Scene scene = makeBuiltinScene(spec);
    for (Interpolation mode : {Interpolation::kPerspective, Interpolation::kAffine}) {
      std::vector<KernelIsa> isas = widerKernelIsas();
      isas.insert(isas.begin(), KernelIsa::kSse2);
      for (KernelIsa isa : isas) {
        for (bool diagnostics : {true, false}) {
          RasterOptions o = options(Precision::kFloat);
          o.interpolation = mode;
          o.isa = isa;
          o.diagnostics = diagnostics;
          o.gatheredResolve = false;
          const Framebuffer byWinner = rasterize(scene, o);
          o.gatheredResolve = true;
          const Framebuffer gathered = rasterize(scene, o);
          EXPECT_EQ(testing::differingChannels(byWinner, gathered), std::vector<std::string>{})
              << spec << " " << interpolationName(mode) << " " << kernelIsaName(isa) << " diagnostics " << diagnostics;
        }
      }
    }
  }
}

// When every vertex lies inside the view volume, set-up takes the triangles four at a time
// without reading outcodes (RasterOptions::wholeMeshBatches); it must make the same set-ups,
// in the same order, as the loop that tests each triangle. The blob's 19,880 triangles fill
// several blocks; fans and perspective end on a short batch (229 and 5 triangles); huge has
// vertices a billion pixels out, past the guard band, so both of its frames take the loop (the
// switch must change nothing there). Both precisions, the SSE2 set-up and the widest.
TEST(Rasterizer, WholeMeshBatchesGiveTheSameBitsAsTheOutcodeLoop) {
  for (const char* spec : {"blob:tris=20000", "fans", "huge", "perspective", "attributes", "cube"}) {
    const Scene scene = makeBuiltinScene(spec);
    for (Precision precision : {Precision::kFloat, Precision::kDouble}) {
      for (KernelIsa isa : {KernelIsa::kSse2, KernelIsa::kAuto}) {
        RasterOptions o = options(precision);
        o.isa = isa;
        o.wholeMeshBatches = false;
        const Framebuffer loop = rasterize(scene, o);
        o.wholeMeshBatches = true;
        const Framebuffer batches = rasterize(scene, o);
        EXPECT_EQ(testing::differingChannels(loop, batches), std::vector<std::string>{})
            << spec << " " << precisionName(precision) << " " << kernelIsaName(isa);
      }
    }
  }
}

// Each block writes its coverage set-ups into its slice of one frame-wide array and spills into
// a vector of its own when the slice is full (pipeline.h's SetupList), which with full-size
// slices only clipped triangles splitting into several set-ups can cause. Slices of 1 record
// (every block spills at once and grows its vector) and of 100 (the records already in the
// slice move to the vector) must give the bits of full-size ones, frame after frame with one
// Rasterizer (the second frame's spills reuse the vectors). The blob's 20,000 triangles fill
// three blocks; nearplane and huge are clipped.
TEST(Rasterizer, SetupsSpilledFromTheirSliceGiveTheSameBits) {
  for (const char* spec : {"blob:tris=20000", "nearplane", "huge", "fans", "cube"}) {
    const Scene scene = makeBuiltinScene(spec);
    for (Precision precision : {Precision::kFloat, Precision::kDouble}) {
      RasterOptions o = options(precision);
      Framebuffer whole;
      Rasterizer(o).render(scene, whole);
      for (std::size_t slice : {std::size_t(1), std::size_t(100)}) {
        o.setupSlice = slice;
        Rasterizer spilling(o);
        for (int frame = 0; frame < 2; ++frame) {
          Framebuffer fb;
          spilling.render(scene, fb);
          EXPECT_EQ(testing::differingChannels(whole, fb), std::vector<std::string>{})
              << spec << " " << precisionName(precision) << ", slices of " << slice << ", frame " << frame;
        }
      }
    }
  }
}

// A Rasterizer reused across frames, scenes, sizes and attribute sets writes every pixel of
// every channel: no stale value or channel survives from an earlier frame.
TEST(Rasterizer, ReusedRasterizerAndFramebufferMatchAFreshOne) {
  const Scene blob = makeBuiltinScene("blob:tris=5000");
  const Scene cube = makeBuiltinScene("cube");  // other size, other attributes
  const Scene floor = makeBuiltinScene("floor");
  Rasterizer reused(options(Precision::kFloat));
  Framebuffer target;
  for (const Scene* scene : {&blob, &cube, &blob, &floor, &blob}) {
    reused.render(*scene, target);
    Framebuffer fresh;
    Rasterizer(options(Precision::kFloat)).render(*scene, fresh);
    EXPECT_EQ(testing::differingChannels(target, fresh), std::vector<std::string>{}) << scene->name;
  }
  // Without diagnostics the four channels go, and nothing else changes.
  RasterOptions lean = options(Precision::kFloat);
  lean.diagnostics = false;
  Rasterizer(lean).render(blob, target);
  Framebuffer fresh;
  Rasterizer(options(Precision::kFloat)).render(blob, fresh);
  EXPECT_EQ(testing::differingChannels(target, fresh),
            (std::vector<std::string>{channels::kBaryBound, channels::kDepthBound, channels::kEdgeDistance,
                                      channels::kDepthTie}));
}

// The four stage times are disjoint parts of the frame: each took time, and together they fit
// in the frame as timed around render(). A stage timed from too early would hold another's time
// too, and on 100k triangles transform, set-up and binning take about a millisecond, far more
// than render() does outside its stages (the header's attributes). bench reports these times
// (stage_ms); on its test's cube they are microseconds, too few to tell such a mistake apart.
TEST(Rasterizer, StageTimesAreDisjointPartsOfTheFrame) {
  const Scene blob = makeBuiltinScene("blob:tris=100000");
  Rasterizer rasterizer(options(Precision::kFloat));
  Framebuffer target;
  rasterizer.render(blob, target);  // the planes allocated and touched
  for (int frame = 0; frame < 5; ++frame) {
    const long long start = nowNanoseconds();
    rasterizer.render(blob, target);
    const double frameMs = millisecondsSince(start);
    const StageTimes& t = rasterizer.stageTimes();
    for (const double ms : {t.transformMs, t.setupMs, t.binMs, t.tilesMs}) EXPECT_GT(ms, 0.0) << "frame " << frame;
    EXPECT_LE(t.transformMs + t.setupMs + t.binMs + t.tilesMs, frameMs)
        << "frame " << frame << ": transform " << t.transformMs << ", set-up " << t.setupMs << ", binning " << t.binMs
        << ", tiles " << t.tilesMs << " ms";
  }
}

TEST(Rasterizer, WritesExactlyTheScenesAttributes) {
  const Framebuffer fb = rasterize(makeBuiltinScene("cube"), options(Precision::kFloat));
  EXPECT_NE(fb.find("attr.uv.x"), nullptr);
  EXPECT_NE(fb.find("attr.uv.y"), nullptr);
  for (const Channel& c : fb.channels()) {
    EXPECT_TRUE(c.name.rfind("attr.", 0) != 0 || c.name.rfind("attr.uv.", 0) == 0) << c.name;
  }
  EXPECT_EQ(fb.attributes.at("rastercheck.mode"), "perspective");
}

// The sign convention: a triangle counter-clockwise seen from the eye is a front face. A lone
// triangle is no closed solid; the flag is set here only to reach the cull.
TEST(Rasterizer, CullingDropsTrianglesClockwiseFromTheEyeAndOnlyThem) {
  const glm::vec3 a{-1.0f, -0.8f, 0.0f}, b{1.0f, -0.8f, 0.0f}, c{0.0f, 0.9f, 0.0f};  // CCW seen from +z
  const auto covered = [](const Framebuffer& fb) {
    int n = 0;
    for (std::uint32_t id : fb.find(channels::kTriangleId)->uints) n += id != channels::kNoTriangle;
    return n;
  };
  for (const bool clockwise : {false, true}) {
    Scene scene = clockwise ? testing::makeTriangleScene({a, c, b}) : testing::makeTriangleScene({a, b, c});
    const int drawn = covered(rasterize(scene, options(Precision::kFloat)));
    EXPECT_GT(drawn, 300);
    scene.mesh.closedSolid = true;
    const Framebuffer culled = rasterize(scene, options(Precision::kFloat));
    EXPECT_EQ(covered(culled), clockwise ? 0 : drawn);
    EXPECT_EQ(culled.attributes.at("rastercheck.cull"), "back");
    RasterOptions none = options(Precision::kFloat);
    none.culling = Culling::kNone;
    const Framebuffer all = rasterize(scene, none);
    EXPECT_EQ(covered(all), drawn);
    EXPECT_EQ(all.attributes.at("rastercheck.cull"), "none");
  }
}

// On a closed solid seen from outside, culling changes no pixel a front face wins: the pixels
// that change are those a snapped back face won at the silhouette, a sliver of the edge band.
TEST(Rasterizer, CullingABlobChangesOnlyPixelsBackFacesWon) {
  const Scene scene = makeBuiltinScene("blob:tris=20000");
  ASSERT_TRUE(scene.mesh.closedSolid);
  RasterOptions none = options(Precision::kFloat, 2);
  none.culling = Culling::kNone;
  const Framebuffer all = rasterize(scene, none);
  const Framebuffer culled = rasterize(scene, options(Precision::kFloat, 2));
  EXPECT_EQ(culled.attributes.at("rastercheck.cull"), "back");
  const glm::dvec3 eye = scene.camera.spec().eye;
  const auto backFacing = [&](std::uint32_t t) {
    const glm::uvec3 tri = scene.mesh.triangles[t];
    const glm::dvec3 p0(scene.mesh.positions[tri.x]), p1(scene.mesh.positions[tri.y]), p2(scene.mesh.positions[tri.z]);
    return glm::dot(glm::cross(p1 - p0, p2 - p0), eye - p0) < 0.0;
  };
  const auto& idAll = all.find(channels::kTriangleId)->uints;
  const auto& idCulled = culled.find(channels::kTriangleId)->uints;
  int covered = 0, changed = 0, backWinners = 0;
  for (std::uint32_t id : idAll) backWinners += id != channels::kNoTriangle && backFacing(id);
  for (std::size_t i = 0; i < idAll.size(); ++i) {
    covered += idAll[i] != channels::kNoTriangle;
    if (idAll[i] == idCulled[i]) {
      for (const Channel& channel : all.channels()) {
        if (channel.type != ChannelType::kFloat) continue;
        const float x = channel.floats[i], y = culled.find(channel.name)->floats[i];
        ASSERT_EQ(std::memcmp(&x, &y, sizeof x), 0) << channel.name << " at pixel " << i;
      }
      continue;
    }
    ++changed;
    ASSERT_NE(idAll[i], channels::kNoTriangle);
    EXPECT_TRUE(backFacing(idAll[i])) << "pixel " << i << ": triangle " << idAll[i];
    EXPECT_TRUE(idCulled[i] == channels::kNoTriangle || !backFacing(idCulled[i])) << "pixel " << i;
  }
  EXPECT_EQ(changed, backWinners);  // every pixel a back face won changed, and no other
  EXPECT_LT(changed, covered / 1000);
  std::printf("[cull] blob:tris=20000: %d of %d covered pixels changed\n", changed, covered);
}

// Where a view ray may start inside the solid, auto does not cull: the same bits as none.
TEST(Rasterizer, CullingIsOffWhenTheNearPlaneCutsTheSolidOrTheEyeIsInside) {
  for (const glm::dvec3 eye : {glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(0.0, 0.3, 1.02)}) {
    const Scene sphere = makeBuiltinScene("sphere:segments=24");
    CameraSpec spec = sphere.camera.spec();
    spec.eye = eye;
    spec.target = eye + glm::dvec3(0.0, -0.2, -1.0);
    const Scene scene{"sphere", "", sphere.mesh, Camera(spec)};
    ASSERT_TRUE(scene.mesh.closedSolid);
    RasterOptions none = options(Precision::kFloat);
    none.culling = Culling::kNone;
    const Framebuffer all = rasterize(scene, none);
    const Framebuffer automatic = rasterize(scene, options(Precision::kFloat));
    EXPECT_EQ(automatic.attributes.at("rastercheck.cull"), "none");
    EXPECT_EQ(testing::differingChannels(all, automatic), std::vector<std::string>{});
    int covered = 0;
    for (std::uint32_t id : automatic.find(channels::kTriangleId)->uints) covered += id != channels::kNoTriangle;
    EXPECT_GT(covered, int(automatic.pixelCount()) / 4);  // the inside of the sphere is in view
  }
}

TEST(Rasterizer, SubpixelBitsTooFineForTheImageAreRefused) {
  const Scene scene = makeBuiltinScene("blob:tris=1000");  // 1920 x 1080
  RasterOptions o;
  o.subpixelBits = 16;  // guard band 2^(28-16) = 4096 pixels: a 1920-wide image fits
  EXPECT_NO_THROW(rasterize(scene, o));
  o.subpixelBits = 17;  // outside 1..16
  EXPECT_ANY_THROW(rasterize(scene, o));
  o.subpixelBits = -1;
  EXPECT_ANY_THROW(rasterize(scene, o));
  o.subpixelBits = 0;  // none: a guard band of 2^20 pixels, as with 8 bits
  EXPECT_NO_THROW(rasterize(scene, o));
  const Scene wide = testing::makeTriangleScene({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, 8192, 16);
  o.subpixelBits = 16;  // 8192 pixels do not fit a 4096-pixel guard band
  EXPECT_ANY_THROW(rasterize(wide, o));
}

// Binning packs tile coordinates in 8 bits (pipeline.cpp, tileBoxOf): the widest image a
// camera takes, 16384 pixels, has 256 tile columns, and its last one is binned and drawn.
TEST(Rasterizer, TheWidestImageBinsItsLastTileColumn) {
  RasterOptions o;
  o.subpixelBits = 4;  // a guard band of 2^24 pixels
  // Wider than the view (half-width 4096 tan 30 deg 3 = 7094 at z = 0): it reaches the right edge.
  const Scene widest = testing::makeTriangleScene({{-1e4f, -1, 0}, {1e4f, -1, 0}, {1e4f, 1, 0}}, 16384, 4);
  const Framebuffer fb = rasterize(widest, o);
  const auto& ids = fb.find(channels::kTriangleId)->uints;
  EXPECT_EQ(ids[std::size_t(2) * 16384 + 16383], 0u);
}

}  // namespace
}  // namespace rc
