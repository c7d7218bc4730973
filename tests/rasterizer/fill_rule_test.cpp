// Coverage: the top-left fill rule gives every pixel centre on a shared edge exactly one owner.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "rasterizer/coverage.h"
#include "rasterizer/tile_coverage.h"
#include "rasterizer/tile_kernel.h"

#pragma GCC diagnostic ignored "-Wpsabi"  // vector types in the kernels inline helpers

namespace rc {
namespace {

constexpr int kBits = 8;
constexpr int kSize = 40;

struct Tri {
  std::int64_t x[3], y[3];
};

std::int64_t fixed(double pixels) { return std::llround(pixels * (1 << kBits)); }

Tri tri(double x0, double y0, double x1, double y1, double x2, double y2) {
  return {{fixed(x0), fixed(x1), fixed(x2)}, {fixed(y0), fixed(y1), fixed(y2)}};
}

// Counts per pixel centre from the kernels' coverage code, run in int64 lanes and in int32
// lanes (exact here: the triangles span at most 40 pixels), each stepping in vectors (the AVX2
// and AVX-512 kernels) and in scalars (SSE2), and with its comparisons on vectors split in
// 16-byte halves (as in the SSE2 build, core/split_vectors.h) and on whole vectors; all six must
// give the same pixels, and every chunk its column.
std::vector<int> coverageCounts(const std::vector<Tri>& tris) {
  std::vector<std::vector<int>> counts(6, std::vector<int>(kSize * kSize, 0));
  const auto count = [](std::vector<int>& into) {
    return [&into](int x, int y, int column, const kernel::i32x8& mask) {
      EXPECT_EQ(x, column * kernel::kLanes);
      for (int k = 0; k < kernel::kLanes; ++k) {
        if (mask[k]) ++into[y * kSize + x + k];
      }
    };
  };
  for (const Tri& t : tris) {
    EdgeFunctions e;
    if (!makeEdgeFunctions(t.x, t.y, e)) continue;
    kernel::coverRows<std::int64_t, true, 64>(e, kBits, 0, 0, kSize - 1, kSize - 1, count(counts[0]));
    kernel::coverRows<std::int32_t, true, 64>(e, kBits, 0, 0, kSize - 1, kSize - 1, count(counts[1]));
    kernel::coverRows<std::int64_t, false, 16>(e, kBits, 0, 0, kSize - 1, kSize - 1, count(counts[2]));
    kernel::coverRows<std::int32_t, false, 16>(e, kBits, 0, 0, kSize - 1, kSize - 1, count(counts[3]));
    kernel::coverRows<std::int64_t, true, 16>(e, kBits, 0, 0, kSize - 1, kSize - 1, count(counts[4]));
    kernel::coverRows<std::int32_t, false, 64>(e, kBits, 0, 0, kSize - 1, kSize - 1, count(counts[5]));
  }
  EXPECT_EQ(counts[0], counts[1]) << "int32 and int64 lanes cover different pixels";
  EXPECT_EQ(counts[0], counts[2]) << "vector and scalar steps cover different pixels (int64 lanes)";
  EXPECT_EQ(counts[0], counts[3]) << "vector and scalar steps cover different pixels (int32 lanes)";
  EXPECT_EQ(counts[0], counts[4]) << "split and whole comparisons cover different pixels (vector steps)";
  EXPECT_EQ(counts[0], counts[5]) << "split and whole comparisons cover different pixels (scalar steps)";
  return counts[0];
}

// Closed-inside test without the fill rule: is the centre inside or on the triangle?
// Returns 2 strictly inside, 1 on its boundary, 0 outside.
int closedInside(const Tri& t, int x, int y) {
  const std::int64_t px = pixelCenterFixed(x, kBits), py = pixelCenterFixed(y, kBits);
  std::int64_t e[3];
  for (int i = 0; i < 3; ++i) {
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    e[i] = (t.x[b] - t.x[a]) * (py - t.y[a]) - (t.y[b] - t.y[a]) * (px - t.x[a]);
  }
  const bool pos = e[0] >= 0 && e[1] >= 0 && e[2] >= 0, neg = e[0] <= 0 && e[1] <= 0 && e[2] <= 0;
  if (!pos && !neg) return 0;
  return (e[0] != 0 && e[1] != 0 && e[2] != 0) ? 2 : 1;
}

bool isVertex(const Tri& t, int x, int y) {
  const std::int64_t px = pixelCenterFixed(x, kBits), py = pixelCenterFixed(y, kBits);
  for (int i = 0; i < 3; ++i) {
    if (t.x[i] == px && t.y[i] == py) return true;
  }
  return false;
}

// For a set of triangles that tile a region without overlap: a centre strictly inside one
// triangle, or inside an edge shared by two, has exactly one owner; nothing has two.
// (Vertices may lie on the union's outer boundary, so callers check interior ones.)
void expectExactlyOnce(const std::vector<Tri>& tris, const std::string& what) {
  const std::vector<int> counts = coverageCounts(tris);
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      int strict = 0, onBoundary = 0;
      bool vertex = false;
      for (const Tri& t : tris) {
        const int c = closedInside(t, x, y);
        strict += c == 2;
        onBoundary += c == 1;
        vertex = vertex || isVertex(t, x, y);
      }
      const int count = counts[y * kSize + x];
      ASSERT_LE(count, 1) << what << ": double cover at (" << x << "," << y << ")";
      if (strict > 0 || (onBoundary >= 2 && !vertex)) {
        ASSERT_EQ(count, 1) << what << ": hole at (" << x << "," << y << ")";
      }
    }
  }
}

TEST(FillRule, TopAndLeftEdgesAreInBottomAndRightEdgesAreOut) {
  // A square whose edges run exactly through pixel centres: x, y in [2.5, 6.5].
  const std::vector<int> counts =
      coverageCounts({tri(2.5, 2.5, 6.5, 2.5, 6.5, 6.5), tri(2.5, 2.5, 6.5, 6.5, 2.5, 6.5)});
  int covered = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const bool expected = x >= 2 && x <= 5 && y >= 2 && y <= 5;
      EXPECT_EQ(counts[y * kSize + x], expected ? 1 : 0) << "(" << x << "," << y << ")";
      covered += counts[y * kSize + x];
    }
  }
  EXPECT_EQ(covered, 16);
}

TEST(FillRule, SharedEdgeThroughPixelCentresIsCoveredExactlyOnce) {
  // Quads split along edges through pixel centres: horizontal, vertical, diagonal, slopes
  // 2 and 1/3, in both windings.
  const double shared[][4] = {{3.5, 20.5, 36.5, 20.5}, {20.5, 3.5, 20.5, 36.5},
                              {3.5, 3.5, 36.5, 36.5},  {10.5, 3.5, 26.5, 35.5},
                              {2.5, 10.5, 35.5, 21.5}, {36.5, 3.5, 3.5, 36.5}};
  for (const auto& e : shared) {
    const double mx = (e[0] + e[2]) / 2, my = (e[1] + e[3]) / 2, dx = e[2] - e[0], dy = e[3] - e[1];
    // Apexes on either side of the shared edge.
    const double ax = mx - dy * 0.4, ay = my + dx * 0.4, bx = mx + dy * 0.4, by = my - dx * 0.4;
    expectExactlyOnce({tri(e[0], e[1], e[2], e[3], ax, ay), tri(e[2], e[3], e[0], e[1], bx, by)},
                      "shared edge");
    expectExactlyOnce({tri(e[0], e[1], ax, ay, e[2], e[3]), tri(e[0], e[1], e[2], e[3], bx, by)},
                      "shared edge, other winding");
  }
}

TEST(FillRule, VertexFanAroundAPixelCentreIsCoveredExactlyOnce) {
  for (int n : {3, 4, 5, 7, 8, 16, 64}) {
    std::vector<Tri> fan;
    const double cx = 20.5, cy = 20.5, r = 15.0;
    for (int i = 0; i < n; ++i) {
      const double a0 = 2 * M_PI * i / n + 0.1, a1 = 2 * M_PI * (i + 1) / n + 0.1;
      // Rim points rounded to the grid once, so neighbours share them exactly.
      fan.push_back(tri(cx, cy, std::round((cx + r * std::cos(a0)) * 256) / 256,
                        std::round((cy + r * std::sin(a0)) * 256) / 256,
                        std::round((cx + r * std::cos(a1)) * 256) / 256,
                        std::round((cy + r * std::sin(a1)) * 256) / 256));
    }
    expectExactlyOnce(fan, "fan of " + std::to_string(n));
    EXPECT_EQ(coverageCounts(fan)[20 * kSize + 20], 1) << "the fan's centre pixel, n=" << n;
  }
}

TEST(FillRule, OwnerDoesNotChangeWithVertexRotationOrWinding) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coordinate(0, kSize * 256);
  for (int trial = 0; trial < 200; ++trial) {
    Tri t;
    for (int i = 0; i < 3; ++i) {
      // Half the vertices on pixel centres, so edges through centres are common.
      const bool onCentre = trial % 2 == 0;
      t.x[i] = onCentre ? pixelCenterFixed(coordinate(rng) / 256, kBits) : coordinate(rng);
      t.y[i] = onCentre ? pixelCenterFixed(coordinate(rng) / 256, kBits) : coordinate(rng);
    }
    const std::vector<int> base = coverageCounts({t});
    const Tri rotated = {{t.x[1], t.x[2], t.x[0]}, {t.y[1], t.y[2], t.y[0]}};
    const Tri reversed = {{t.x[0], t.x[2], t.x[1]}, {t.y[0], t.y[2], t.y[1]}};
    ASSERT_EQ(coverageCounts({rotated}), base) << "trial " << trial;
    ASSERT_EQ(coverageCounts({reversed}), base) << "trial " << trial;
  }
}

// coverRows over a small box inside a triangle reports the box's covered pixels and nothing
// else. The AVX2 and AVX-512 kernels run a box one chunk wide and at most 4 rows high as
// exactly 2 or 4 rows, the rows past the box masked off; here the triangle goes on below the
// box, so a row past it that is not masked off reports pixels.
TEST(FillRule, SmallBoxesReportOnlyTheirOwnPixels) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coordinate(0, kSize * 256);
  int boxes = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Tri t;
    for (int i = 0; i < 3; ++i) t.x[i] = coordinate(rng), t.y[i] = coordinate(rng);
    EdgeFunctions e;
    if (!makeEdgeFunctions(t.x, t.y, e)) continue;
    const std::vector<int> whole = coverageCounts({t});
    for (int ya = 0; ya < kSize; ya += 3) {
      for (int xa = 0; xa < kSize; xa += 5) {
        for (int height = 1; height <= 5; ++height) {
          for (int width = 1; width <= 9; width += 2) {
            const int xb = std::min(kSize - 1, xa + width - 1), yb = std::min(kSize - 1, ya + height - 1);
            std::vector<int> expected(kSize * kSize, 0);
            for (int y = ya; y <= yb; ++y) {
              for (int x = xa; x <= xb; ++x) expected[y * kSize + x] = whole[y * kSize + x];
            }
            if (std::count(expected.begin(), expected.end(), 1) > 0) ++boxes;
            std::vector<std::vector<int>> got(6, std::vector<int>(kSize * kSize, 0));
            int outside = 0;
            const auto record = [&](std::vector<int>& into) {
              return [&into, &outside, xa, ya, xb, yb](int x, int y, int, const kernel::i32x8& mask) {
                for (int k = 0; k < kernel::kLanes; ++k) {
                  if (!mask[k]) continue;
                  if (x + k < xa || x + k > xb || y < ya || y > yb) {
                    ++outside;
                  } else {
                    ++into[y * kSize + x + k];
                  }
                }
              };
            };
            kernel::coverRows<std::int64_t, true, 64>(e, kBits, xa, ya, xb, yb, record(got[0]));
            kernel::coverRows<std::int32_t, true, 64>(e, kBits, xa, ya, xb, yb, record(got[1]));
            kernel::coverRows<std::int64_t, true, 32>(e, kBits, xa, ya, xb, yb, record(got[2]));
            kernel::coverRows<std::int32_t, true, 32>(e, kBits, xa, ya, xb, yb, record(got[3]));
            kernel::coverRows<std::int64_t, false, 16>(e, kBits, xa, ya, xb, yb, record(got[4]));
            kernel::coverRows<std::int32_t, true, 16>(e, kBits, xa, ya, xb, yb, record(got[5]));
            ASSERT_EQ(outside, 0) << "trial " << trial << ", box " << xa << "," << ya << " to " << xb << "," << yb;
            for (int v = 0; v < 6; ++v) {
              ASSERT_EQ(got[v], expected) << "variant " << v << ", trial " << trial << ", box " << xa << "," << ya
                                          << " to " << xb << "," << yb;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(boxes, 1000) << "boxes with covered pixels";
}

TEST(FillRule, ZeroAreaTrianglesCoverNothing) {
  EdgeFunctions e;
  const Tri collinear = tri(1.5, 1.5, 10.5, 10.5, 20.5, 20.5);
  EXPECT_FALSE(makeEdgeFunctions(collinear.x, collinear.y, e));
  const Tri repeated = tri(1.5, 1.5, 1.5, 1.5, 20.5, 3.5);
  EXPECT_FALSE(makeEdgeFunctions(repeated.x, repeated.y, e));
}

}  // namespace
}  // namespace rc
