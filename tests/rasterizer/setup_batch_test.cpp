// The batch set-up (setup_batch.h) against setupCoverage and setupShade, record by record and
// bit for bit, over random triangles from sub-pixel to guard-band size, for every subpixel
// precision.
#include "rasterizer/setup_batch.h"
#include "rasterizer/tile_kernel.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace rc {
namespace {

template <typename T>
std::uint64_t bitsOf(T v) {
  std::uint64_t b = 0;
  std::memcpy(&b, &v, sizeof v);
  return b;
}

// The names of the fields that differ, floating-point ones compared by their bits.
struct Differences {
  std::string names;
  void operator()(const char* name, bool same) {
    if (!same) names += std::string(names.empty() ? "" : ", ") + name;
  }
};

// Empty when the records are the same.
template <typename Real>
std::string differences(const CoverageSetup<Real>& x, const CoverageSetup<Real>& y) {
  Differences field;
  field("minX", x.minX == y.minX), field("minY", x.minY == y.minY);
  field("maxX", x.maxX == y.maxX), field("maxY", x.maxY == y.maxY);
  for (int i = 0; i < 3; ++i) field("x", x.x[i] == y.x[i]), field("y", x.y[i] == y.y[i]);
  field("flags", x.flags == y.flags);
  field("key0", bitsOf(x.key0) == bitsOf(y.key0));
  field("keyX", bitsOf(x.keyX) == bitsOf(y.keyX));
  field("keyY", bitsOf(x.keyY) == bitsOf(y.keyY));
  return field.names;
}

template <typename Real>
std::string differences(const ShadeSetup<Real>& x, const ShadeSetup<Real>& y) {
  Differences field;
  for (int i = 0; i < 3; ++i) {
    field("l0", bitsOf(x.l0[i]) == bitsOf(y.l0[i])), field("lx", bitsOf(x.lx[i]) == bitsOf(y.lx[i]));
    field("ly", bitsOf(x.ly[i]) == bitsOf(y.ly[i])), field("w", bitsOf(x.w[i]) == bitsOf(y.w[i]));
    field("invW", bitsOf(x.invW[i]) == bitsOf(y.invW[i]));
    field("edgeHeight", bitsOf(x.edgeHeight[i]) == bitsOf(y.edgeHeight[i]));
  }
  field("baryBound", bitsOf(x.baryBound) == bitsOf(y.baryBound));
  field("depthBound", bitsOf(x.depthBound) == bitsOf(y.depthBound));
  return field.names;
}

struct Counts {
  int accepted = 0, rejected = 0, narrow = 0, wide = 0, clockwise = 0, shaded = 0;
};

// The batch set-up's builds: setupCoverage has all three, setupShade the first two (the
// AVX-512 tile kernels call its AVX2 build).
enum class Isa { kSse2, kAvx2, kAvx512 };
const char* nameOf(Isa isa) { return isa == Isa::kSse2 ? "sse2" : isa == Isa::kAvx2 ? "avx2" : "avx512"; }

// Random batches of four triangles in a width x height viewport at `bits`; every lane of
// every batch compared with setupCoverage.
template <typename Real>
Counts compareBatches(int bits, bool cull, Isa isa, std::uint64_t seed) {
  SetupContext ctx{};
  ctx.width = 640, ctx.height = 480, ctx.subpixelBits = bits;
  ctx.unitRoundoff = sizeof(Real) == 4 ? 0x1p-24 : 0x1p-53, ctx.clipError = 3e-15;
  ctx.keyA = -0.001, ctx.keyB = 0.1;
  ctx.cullBackFaces = cull;
  // Vertices within the guard band, 2^(28 - bits) pixels (pipeline.cpp), at most 2^20; without
  // snapping 8 bits'.
  const double guard = std::min(std::ldexp(1.0, 28 - (bits == 0 ? 8 : bits)), std::ldexp(1.0, 20)) * 0.99;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Counts counts;
  bool mismatch = false;
  for (int round = 0; round < 4000; ++round) {
    std::vector<glm::dvec4> clip(12);
    std::vector<glm::dvec2> raster(12);
    glm::uvec3 tris[batch::kLanes];
    for (int k = 0; k < batch::kLanes; ++k) {
      // Size from a tenth of a pixel to the guard band, centred anywhere near the viewport.
      const double size = std::exp(std::log(0.1) + unit(rng) * (std::log(guard) - std::log(0.1)));
      const glm::dvec2 centre(-50.0 + unit(rng) * 740.0, -50.0 + unit(rng) * 580.0);
      const int shape = int(rng() % 8);
      for (int i = 0; i < 3; ++i) {
        glm::dvec2 p = centre + size * glm::dvec2(unit(rng) - 0.5, unit(rng) - 0.5);
        if (shape == 0 && i == 2) p = raster[3 * k];                                    // repeated vertex
        if (shape == 1 && i == 2) p = 0.5 * (raster[3 * k] + raster[3 * k + 1]);        // collinear
        if (shape == 2 && i > 0) p.y = raster[3 * k].y;                                  // horizontal edge
        if (shape == 3 && i > 0) p = glm::dvec2(std::round(p.x), std::round(p.y)) + 0.5;  // on pixel centres
        const double w = std::exp(std::log(0.05) + unit(rng) * (std::log(5000.0) - std::log(0.05)));
        raster[3 * k + i] = p;
        // Clip x and y as the camera would give them (raster to NDC), for setupShade's bound.
        clip[3 * k + i] = glm::dvec4((p.x / 320.0 - 1.0) * w, (1.0 - p.y / 240.0) * w, w, w);
      }
      tris[k] = glm::uvec3(3 * k, 3 * k + 1, 3 * k + 2);
    }
    CoverageSetup<Real> batched[batch::kLanes];
    // Without snapping the AVX-512 kernels' level takes the AVX2 build (no int64 lanes).
    const unsigned accepted =
        bits == 0 ? (isa == Isa::kSse2 ? batch::setupUnsnappedSse2(tris, clip.data(), raster.data(), ctx, batched)
                                       : batch::setupUnsnappedAvx2(tris, clip.data(), raster.data(), ctx, batched))
        : isa == Isa::kAvx512 ? batch::setupCoverageAvx512(tris, clip.data(), raster.data(), ctx, batched)
        : isa == Isa::kAvx2   ? batch::setupCoverageAvx2(tris, clip.data(), raster.data(), ctx, batched)
                              : batch::setupCoverageSse2(tris, clip.data(), raster.data(), ctx, batched);
    std::vector<ShadeSetup<Real>> shaded;
    std::vector<int> shadedLanes;
    for (int k = 0; k < batch::kLanes; ++k) {
      const glm::dvec4 c[3] = {clip[tris[k].x], clip[tris[k].y], clip[tris[k].z]};
      const glm::dvec2 r[3] = {raster[tris[k].x], raster[tris[k].y], raster[tris[k].z]};
      CoverageSetup<Real> scalar;
      const bool ok = setupCoverage(c, r, ctx, scalar);
      mismatch |= ok != bool((accepted >> k) & 1u);
      EXPECT_EQ(ok, bool((accepted >> k) & 1u)) << "round " << round << " lane " << k;
      if (!ok) {
        ++counts.rejected;
        continue;
      }
      if (!((accepted >> k) & 1u)) continue;
      ++counts.accepted;
      (scalar.flags & CoverageSetup<Real>::kNarrow ? counts.narrow : counts.wide) += 1;
      const glm::dvec2 e1 = r[1] - r[0], e2 = r[2] - r[0];
      if (e1.x * e2.y - e1.y * e2.x > 1.0) ++counts.clockwise;  // clearly so: not flipped by snapping
      const std::string d = differences(scalar, batched[k]);
      mismatch |= !d.empty();
      EXPECT_EQ(d, "") << "round " << round << " lane " << k;
      ShadeSetup<Real> shade;
      setupShade(c, r, 0u, false, ctx, scalar, shade);
      shaded.push_back(shade);
      shadedLanes.push_back(k);
    }
    // The resolve half for the accepted lanes, four at a time as the tiles call it (a short
    // batch repeats its first lane into a spare record).
    if (!shadedLanes.empty()) {
      glm::uvec3 shadeTris[batch::kLanes];
      const CoverageSetup<Real>* coverage[batch::kLanes];
      ShadeSetup<Real> got[batch::kLanes];
      ShadeSetup<Real>* into[batch::kLanes];
      for (int k = 0; k < batch::kLanes; ++k) {
        const int lane = shadedLanes[std::min<std::size_t>(k, shadedLanes.size() - 1)];
        shadeTris[k] = tris[lane];
        coverage[k] = &batched[lane];
        into[k] = &got[k];
      }
      if (isa != Isa::kSse2) {
        batch::setupShadeAvx2(shadeTris, clip.data(), raster.data(), ctx, coverage, into);
      } else {
        batch::setupShadeSse2(shadeTris, clip.data(), raster.data(), ctx, coverage, into);
      }
      for (std::size_t k = 0; k < shadedLanes.size(); ++k) {
        const std::string d = differences(shaded[k], got[k]);
        mismatch |= !d.empty();
        EXPECT_EQ(d, "") << "round " << round << " lane " << shadedLanes[k] << " (shade)";
      }
      counts.shaded += int(shadedLanes.size());
    }
    if (mismatch) break;  // one report, not thousands
  }
  return counts;
}

template <typename Real>
void checkAllPrecisions(Isa isa) {
  Counts total;
  for (const int bits : {0, 1, 4, 8, 12, 16}) {  // 0: without snapping
    SCOPED_TRACE("bits " + std::to_string(bits) + ", " + nameOf(isa));
    // The same triangles with and without culling.
    const Counts drawn = compareBatches<Real>(bits, false, isa, 1000u * bits);
    const Counts culled = compareBatches<Real>(bits, true, isa, 1000u * bits);
    EXPECT_GT(drawn.accepted, 1000);
    EXPECT_EQ(drawn.shaded, drawn.accepted);
    EXPECT_GT(drawn.rejected, 1000);
    EXPECT_GT(drawn.clockwise, 100);
    EXPECT_GT(culled.accepted, 1000);
    EXPECT_GT(culled.rejected, drawn.rejected + 1000);
    total.narrow += drawn.narrow, total.wide += drawn.wide;
  }
  // Both edge widths (narrow set-ups need spans below about 2^(15.5 - bits) pixels).
  EXPECT_GT(total.narrow, 1000);
  EXPECT_GT(total.wide, 1000);
}

TEST(SetupBatch, MatchesSetupCoverageAndSetupShadeBitForBit) {
  checkAllPrecisions<float>(Isa::kSse2);
  checkAllPrecisions<double>(Isa::kSse2);
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "no AVX2 on this CPU";
  checkAllPrecisions<float>(Isa::kAvx2);
  checkAllPrecisions<double>(Isa::kAvx2);
  if (!kernel::cpuHasKernelAvx512()) GTEST_SKIP() << "no AVX-512 on this CPU";
  checkAllPrecisions<float>(Isa::kAvx512);
  checkAllPrecisions<double>(Isa::kAvx512);
}

// The comparison above sees a change of one bit in any field.
TEST(SetupBatch, ComparisonSeesOneBit) {
  SetupContext ctx{};
  ctx.width = 64, ctx.height = 64, ctx.subpixelBits = 8, ctx.keyA = -0.001, ctx.keyB = 0.1;
  const glm::dvec4 clip[3] = {{0, 0, 1, 1}, {0, 0, 1, 2}, {0, 0, 1, 3}};
  const glm::dvec2 raster[3] = {{3.2, 4.1}, {40.7, 9.3}, {12.5, 50.9}};
  CoverageSetup<float> c;
  ASSERT_TRUE(setupCoverage(clip, raster, ctx, c));
  EXPECT_EQ(differences(c, c), "");
  CoverageSetup<float> d = c;
  d.keyX = std::nextafter(d.keyX, 1.0f);
  EXPECT_EQ(differences(c, d), "keyX");
  d = c;
  d.flags ^= CoverageSetup<float>::kNarrow;
  EXPECT_EQ(differences(c, d), "flags");
  d = c;
  d.y[2] += 1;
  EXPECT_EQ(differences(c, d), "y");
}

}  // namespace
}  // namespace rc
