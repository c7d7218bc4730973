// Polygon triangulation: convex polygons fanned, concave ones cut into ears that stay inside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "scenes/loaders/polygon.h"

namespace rc {
namespace {

using Triangles = std::vector<std::array<unsigned, 3>>;

double signedArea(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

double polygonArea(const std::vector<glm::dvec2>& p) {
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const glm::dvec2& a = p[i];
    const glm::dvec2& b = p[(i + 1) % p.size()];
    sum += a.x * b.y - b.x * a.y;
  }
  return 0.5 * sum;
}

// Even-odd point-in-polygon.
bool insidePolygon(const glm::dvec2& q, const std::vector<glm::dvec2>& p) {
  bool inside = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x) {
      inside = !inside;
    }
  }
  return inside;
}

// The polygon in 3D: the plane z = 0 placed by `place`.
std::vector<glm::dvec3> embed(const std::vector<glm::dvec2>& p, const glm::dmat4& place) {
  std::vector<glm::dvec3> out;
  for (const glm::dvec2& q : p) out.push_back(glm::dvec3(place * glm::dvec4(q, 0.0, 1.0)));
  return out;
}

// The triangulation of simple polygon p covers exactly p: n - 2 triangles of distinct corners,
// each wound as p is, adding up to p's area, each but flat ones with its centroid inside p.
void expectCoversExactly(const Triangles& triangles, const std::vector<glm::dvec2>& p, const std::string& what) {
  ASSERT_EQ(triangles.size(), p.size() - 2) << what;
  const double area = polygonArea(p);
  double sum = 0.0, sumAbs = 0.0;
  for (const auto& [a, b, c] : triangles) {
    ASSERT_TRUE(a < p.size() && b < p.size() && c < p.size() && a != b && b != c && a != c) << what;
    const double t = signedArea(p[a], p[b], p[c]);
    EXPECT_GE(t * area, 0.0) << what << ": triangle " << a << " " << b << " " << c << " is wound against the polygon";
    sum += t;
    sumAbs += std::fabs(t);
    if (std::fabs(t) <= 1e-12 * std::fabs(area)) continue;  // flat (corners on a line): covers nothing
    EXPECT_TRUE(insidePolygon((p[a] + p[b] + p[c]) / 3.0, p)) << what << ": triangle " << a << " " << b << " " << c
                                                              << " lies outside the polygon";
  }
  EXPECT_NEAR(sum, area, 1e-9 * std::fabs(area)) << what;
  EXPECT_NEAR(sumAbs, std::fabs(area), 1e-9 * std::fabs(area)) << what << ": triangles overlap";
}

Triangles fan(unsigned n) {
  Triangles t;
  for (unsigned k = 1; k + 1 < n; ++k) t.push_back({0, k, k + 1});
  return t;
}

TEST(Polygon, ConvexPolygonsAreFannedFromTheirFirstCorner) {
  for (unsigned n = 3; n <= 12; ++n) {
    std::vector<glm::dvec2> p;
    for (unsigned k = 0; k < n; ++k) p.push_back({std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n)});
    for (bool clockwise : {false, true}) {
      std::vector<glm::dvec2> q = p;
      if (clockwise) std::reverse(q.begin(), q.end());
      const glm::dmat4 place = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(3, -2, 7)), 1.1, glm::dvec3(1, 2, 0.5));
      EXPECT_EQ(triangulatePolygon(embed(q, place)), fan(n)) << n << (clockwise ? " clockwise" : "");
    }
  }
  // A non-planar quad, as OBJ files hold them, is convex seen along its normal: fanned too.
  EXPECT_EQ(triangulatePolygon({{0, 0, 0}, {1, 0, 0.1}, {1, 1, 0}, {0, 1, 0.1}}), fan(4));
}

TEST(Polygon, ConcavePolygonsAreCutIntoEarsInsideThem) {
  const struct { const char* name; std::vector<glm::dvec2> p; } cases[] = {
      {"dart, reflex corner 1", {{0, 0}, {1, 1}, {2, 0}, {1, 3}}},
      {"arrowhead, reflex corner 2", {{0, 0}, {2, 0}, {1, 0.5}, {2, 2}, {0, 2}}},
      {"L", {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}},
      {"comb", {{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}}},
      {"star", {}},
      {"comb of 255 corners", {}},
      {"square with a square hole through a bridge",
       {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}, {1, 1}, {1, 3}, {3, 3}, {3, 1}, {1, 1}}},
  };
  for (const auto& c : cases) {
    std::vector<glm::dvec2> p = c.p;
    if (std::string(c.name) == "comb of 255 corners") {
      p.push_back({0, 0});
      for (int t = 0; t < 126; ++t) {
        p.push_back({t + 0.25, t % 2 ? 0.2 : 1.0});
        p.push_back({t + 0.75, t % 2 ? 0.2 : 1.0});
      }
      p.push_back({126, 0});
      p.resize(255);
    }
    if (std::string(c.name) == "star") {
      for (int k = 0; k < 10; ++k) p.push_back({(k % 2 ? 0.4 : 1.0) * std::cos(M_PI * k / 5), (k % 2 ? 0.4 : 1.0) * std::sin(M_PI * k / 5)});
    }
    for (int rotation = 0; rotation < int(p.size()); ++rotation) {
      for (bool clockwise : {false, true}) {
        std::vector<glm::dvec2> q = p;
        std::rotate(q.begin(), q.begin() + rotation, q.end());
        if (clockwise) std::reverse(q.begin(), q.end());
        const glm::dmat4 place = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(-5, 1, 2)), 2.0, glm::dvec3(0.3, -1, 0.2));
        const std::string what = std::string(c.name) + ", from corner " + std::to_string(rotation) + (clockwise ? ", clockwise" : "");
        const Triangles triangles = triangulatePolygon(embed(q, place));
        expectCoversExactly(triangles, q, what);
      }
    }
  }
}

TEST(Polygon, AFanOfAConcavePolygonWouldFailTheCoverageCheck) {
  // The check above has teeth: the fan of the arrowhead covers area outside it.
  const std::vector<glm::dvec2> arrowhead = {{0, 0}, {2, 0}, {2, 2}, {1, 0.5}, {0, 2}};
  double outside = 0.0;
  for (const auto& [a, b, c] : fan(5)) {
    if (!insidePolygon((arrowhead[a] + arrowhead[b] + arrowhead[c]) / 3.0, arrowhead)) ++outside;
  }
  EXPECT_GT(outside, 0.0);
  expectCoversExactly(triangulatePolygon(embed(arrowhead, glm::dmat4(1.0))), arrowhead, "arrowhead");
}

TEST(Polygon, RandomSimplePolygonsOfUpTo255CornersAreCoveredExactly) {
  std::mt19937 rng(20261204);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const unsigned n = 4 + unsigned(unit(rng) * 252);
    // Star-shaped about the origin (angles sorted, radii random): simple, and mostly concave.
    std::vector<double> angles(n);
    for (double& a : angles) a = 2 * M_PI * unit(rng);
    std::sort(angles.begin(), angles.end());
    std::vector<glm::dvec2> p;
    for (double a : angles) p.push_back((0.2 + unit(rng)) * glm::dvec2(std::cos(a), std::sin(a)));
    if (trial % 2) std::reverse(p.begin(), p.end());
    const glm::dmat4 place = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(unit(rng), 100 * unit(rng), -3)),
                                         6 * unit(rng), glm::dvec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5));
    expectCoversExactly(triangulatePolygon(embed(p, place)), p, "trial " + std::to_string(trial) + ", " + std::to_string(n) + " corners");
    if (HasFailure()) break;
  }
}

TEST(Polygon, PolygonsWithoutAnEarOrAPlaneStillGiveNMinus2TrianglesOfTheirCorners) {
  const std::vector<std::vector<glm::dvec3>> cases = {
      {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}},                            // a bow tie (crosses itself)
      {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {4, 4, 4}},                 // all on a line
      {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}},                            // one point
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}},      // corners repeated
      {{0, 0, 0}, {1e300, 0, 0}, {1e300, 1e300, 0}, {0, 1e300, 0}},            // the normal overflows
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Triangles triangles = triangulatePolygon(cases[k]);
    ASSERT_EQ(triangles.size(), cases[k].size() - 2) << k;
    for (const auto& t : triangles) {
      for (unsigned corner : t) EXPECT_LT(corner, cases[k].size()) << k;
    }
  }
  // A pentagram drawn as five corners goes round twice: no ear, so it is fanned.
  std::vector<glm::dvec3> pentagram;
  for (int k = 0; k < 5; ++k) pentagram.push_back({std::cos(4 * M_PI * k / 5), std::sin(4 * M_PI * k / 5), 0});
  EXPECT_EQ(triangulatePolygon(pentagram).size(), 3u);
}

}  // namespace
}  // namespace rc
