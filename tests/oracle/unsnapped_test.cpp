// Coverage without snapping (--subpixel-bits none): the orientation predicate against rationals,
// and the kernels' unsnapped coverage against the exact top-left rule (exact.h's
// unsnappedCoverage) on triangles made to be hard for doubles: vertices on the half-pixel
// lattice, so that edges run exactly through pixel centres; slivers a trillionth of a pixel
// wide; shared edges and fans, where every centre must have one owner.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "rasterizer/orientation.h"
#include "rasterizer/setup.h"
#include "rasterizer/tile_coverage.h"
#include "rasterizer/tile_kernel.h"
#include "tests/oracle/exact.h"

#pragma GCC diagnostic ignored "-Wpsabi"  // vector types in the kernels' inline helpers

namespace rc {
namespace {

constexpr int kSize = 40;

int rationalOrientation(double ax, double ay, double bx, double by, double cx, double cy) {
  using Q = oracle::Q;
  return sgn((Q(ax) - Q(cx)) * (Q(by) - Q(cy)) - (Q(ay) - Q(cy)) * (Q(bx) - Q(cx)));
}

// Points a hair off the line through a and b: the cases where the double determinant alone
// may get the sign wrong.
TEST(Orientation, AgreesWithRationalsWhereDoublesAloneDoNot) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(-1000.0, 1000.0), unit(0.0, 1.0);
  int naiveWrong = 0, exactPath = 0;
  for (int n = 0; n < 200000; ++n) {
    const double ax = coordinate(rng), ay = coordinate(rng), bx = coordinate(rng), by = coordinate(rng);
    const double t = unit(rng);
    double cx = ax + t * (bx - ax), cy = ay + t * (by - ay);
    if (n % 2) cx = std::nextafter(cx, n % 4 == 1 ? 1e9 : -1e9);
    if (n % 3 == 0) cx = 0.5 * std::round(2.0 * cx), cy = 0.5 * std::round(2.0 * cy);  // a pixel centre
    const int expected = rationalOrientation(ax, ay, bx, by, cx, cy);
    const double naive = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
    naiveWrong += (naive > 0) - (naive < 0) != expected;
    const double left = (ax - cx) * (by - cy), right = (ay - cy) * (bx - cx);
    exactPath += !(std::fabs(left - right) > kOrientationBound * (std::fabs(left) + std::fabs(right)));
    ASSERT_EQ(orientation(ax, ay, bx, by, cx, cy), expected) << n;
    ASSERT_EQ(exactOrientation(ax, ay, bx, by, cx, cy), expected) << n;
  }
  std::printf("[orientation] 200000 near-collinear cases: the double determinant alone wrong in %d, "
              "%d left to the exact path\n", naiveWrong, exactPath);
  EXPECT_GT(naiveWrong, 0) << "the cases should include ones doubles alone get wrong";
  EXPECT_EQ(orientation(0, 0, 1, 1, 2, 2), 0);
  EXPECT_EQ(orientation(0, 0, 1, 0, 0.5, 0x1p-1074), 1);  // a subnormal off the line
  EXPECT_EQ(orientation(0, 0, 1, 0, 0.5, -0x1p-1074), -1);
}

// The set-up and kernel coverage without snapping of one triangle, in a kSize x kSize image:
// the pixels of each of the three instantiations (16-, 32- and 64-byte comparisons), which must
// agree. Empty when set-up rejects the triangle.
std::vector<std::uint32_t> kernelCoverage(const std::array<glm::dvec2, 3>& v, bool cull) {
  SetupContext ctx{};
  ctx.width = kSize, ctx.height = kSize, ctx.subpixelBits = 0;
  ctx.unitRoundoff = 0x1p-24, ctx.keyA = 0.0, ctx.keyB = 1.0, ctx.cullBackFaces = cull;
  const glm::dvec4 clip[3] = {{0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}};
  const glm::dvec2 raster[3] = {v[0], v[1], v[2]};
  CoverageSetup<float> c{};
  if (!setupCoverage(clip, raster, ctx, c)) return {};
  std::vector<std::uint32_t> pixels[3];
  const auto into = [](std::vector<std::uint32_t>& out) {
    return [&out](int x, int y, int, const kernel::i32x8& mask) {
      for (int k = 0; k < kernel::kLanes; ++k) {
        if (mask[k]) out.push_back(std::uint32_t(y * kSize + x + k));
      }
    };
  };
  kernel::coverRowsUnsnapped<16>(c, raster, c.minX, c.minY, c.maxX, c.maxY, into(pixels[0]));
  kernel::coverRowsUnsnapped<32>(c, raster, c.minX, c.minY, c.maxX, c.maxY, into(pixels[1]));
  kernel::coverRowsUnsnapped<64>(c, raster, c.minX, c.minY, c.maxX, c.maxY, into(pixels[2]));
  EXPECT_EQ(pixels[0], pixels[1]);
  EXPECT_EQ(pixels[0], pixels[2]);
  return pixels[0];
}

TEST(UnsnappedCoverage, EqualsTheExactTopLeftRule) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> coordinate(-4.0, kSize + 4.0), unit(0.0, 1.0);
  int covered = 0, triangles = 0;
  for (int n = 0; n < 5000; ++n) {
    std::array<glm::dvec2, 3> v;
    for (auto& p : v) p = {coordinate(rng), coordinate(rng)};
    // 20 fraction bits: products of two such values below 64 are exact in double.
    const auto bits20 = [](double x) { return std::ldexp(std::round(std::ldexp(x, 20)), -20); };
    if (n % 5 == 4) {  // an edge through a centre near the origin, one end then moved by an ulp:
                       // its distance from the centre is below what its products round away
      const glm::dvec2 centre{0.5 + std::floor(unit(rng) * 3.0), 0.5 + std::floor(unit(rng) * 3.0)};
      const glm::dvec2 d{bits20(unit(rng) - 0.5), bits20(unit(rng) - 0.5)};
      v[0] = centre - bits20(1.0 + 60.0 * unit(rng)) * d;
      v[1] = centre + bits20(1.0 + 60.0 * unit(rng)) * d;
      v[1].x = std::nextafter(v[1].x, unit(rng) < 0.5 ? -1e9 : 1e9);
    } else if (n % 5 == 1) {  // on the half-pixel lattice: edges through centres, vertices on them
      for (auto& p : v) p = {0.5 * std::round(2.0 * p.x), 0.5 * std::round(2.0 * p.y)};
    } else if (n % 5 == 2) {  // a sliver: the third vertex a hair off the line of the others
      const double t = unit(rng) * 1.5 - 0.25, off = std::ldexp(unit(rng) - 0.5, -40);
      const glm::dvec2 d = v[1] - v[0];
      v[2] = v[0] + t * d + off * glm::dvec2(-d.y, d.x);
    } else if (n % 5 == 3) {  // from a vertex in the first pixel, through the centre (0.5, 0.5) but
                              // for rounding: the differences from the centre round, and the
                              // double determinant may get the sign wrong, not only miss it
      v[0] = {0.49 * unit(rng), 0.49 * unit(rng)};
      const double t = std::ldexp(1.0 + unit(rng), int(unit(rng) * 6.0));
      v[1] = {0.5 + t * (0.5 - v[0].x), 0.5 + t * (0.5 - v[0].y)};
    }
    for (bool cull : {false, true}) {
      const std::vector<std::uint32_t> got = kernelCoverage(v, cull);
      EXPECT_EQ(got, oracle::unsnappedCoverage(v, kSize, kSize, cull)) << "triangle " << n << (cull ? ", culling" : "");
      covered += int(got.size());
    }
    ++triangles;
  }
  std::printf("[unsnapped] %d triangles (a fifth each: random, on the half-pixel lattice, slivers, an edge from the "
              "first pixel through its centre but for rounding, an edge an ulp off a centre): %d covered centres\n",
              triangles, covered);
  EXPECT_GT(covered, 10000);
}

// Triangles that share their edges: a grid of quads split along random diagonals, inner vertices
// anywhere, outer ones on the lines x, y = 4.5 and 35.5 through pixel centres; and fans around
// a pixel centre. Every centre inside the grid's rectangle, and the fans' centre, is covered
// exactly once; none is covered twice.
TEST(UnsnappedCoverage, SharedEdgesGiveEveryCentreOneOwner) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int m = 0; m < 40; ++m) {
    std::vector<int> count(kSize * kSize, 0);
    std::vector<std::array<glm::dvec2, 3>> tris;
    if (m % 2 == 0) {
      const int n = 2 + int(unit(rng) * 6);
      const double lo = 4.5, hi = 35.5, step = (hi - lo) / n;
      std::vector<glm::dvec2> grid((n + 1) * (n + 1));
      for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
          double x = lo + i * step, y = lo + j * step;
          if (i > 0 && i < n) x += (unit(rng) - 0.5) * step * 0.6;
          if (j > 0 && j < n) y += (unit(rng) - 0.5) * step * 0.6;
          if (m % 4 == 2 && i > 0 && i < n && j > 0 && j < n) x = 0.5 * std::round(2.0 * x), y = 0.5 * std::round(2.0 * y);
          grid[j * (n + 1) + i] = {x, y};
        }
      }
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const glm::dvec2 a = grid[j * (n + 1) + i], b = grid[j * (n + 1) + i + 1];
          const glm::dvec2 c = grid[(j + 1) * (n + 1) + i + 1], d = grid[(j + 1) * (n + 1) + i];
          if (unit(rng) < 0.5) {
            tris.push_back({a, b, c}), tris.push_back({a, c, d});
          } else {
            tris.push_back({a, b, d}), tris.push_back({b, c, d});
          }
        }
      }
    } else {
      const glm::dvec2 centre{20.5, 19.5};
      const int n = 3 + int(unit(rng) * 40);
      std::vector<glm::dvec2> rim;
      for (int k = 0; k < n; ++k) {
        const double angle = 2.0 * M_PI * (k + 0.3 * (unit(rng) - 0.5)) / n, r = 6.0 + 12.0 * unit(rng);
        rim.push_back(centre + r * glm::dvec2(std::cos(angle), std::sin(angle)));
      }
      for (int k = 0; k < n; ++k) tris.push_back({centre, rim[std::size_t(k)], rim[std::size_t((k + 1) % n)]});
    }
    for (const auto& t : tris) {
      for (std::uint32_t p : kernelCoverage(t, false)) ++count[p];
    }
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        ASSERT_LE(count[y * kSize + x], 1) << "mesh " << m << ": centre (" << x << ", " << y << ") covered twice";
        if (m % 2 == 0 && x >= 5 && x <= 34 && y >= 5 && y <= 34) {
          ASSERT_EQ(count[y * kSize + x], 1) << "mesh " << m << ": centre (" << x << ", " << y << ") left out";
        }
      }
    }
    if (m % 2 == 1) {
      EXPECT_EQ(count[19 * kSize + 20], 1) << "mesh " << m << ": the fan's centre";
    }
  }
}

}  // namespace
}  // namespace rc
