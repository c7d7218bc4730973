// Polygon triangulation: a fan where the polygon is convex, ear clipping where it is not.
#include "scenes/loaders/polygon.h"

#include <cmath>

namespace rc {
namespace {

// Twice the signed area of triangle abc: positive when it turns counter-clockwise.
double turn(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Whether p lies inside counter-clockwise triangle abc or on its boundary.
bool inTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return turn(a, b, p) >= 0.0 && turn(b, c, p) >= 0.0 && turn(c, a, p) >= 0.0;
}

// The corners in the polygon's plane, or none where it has no plane: Newell's normal, robust for
// polygons that are not quite planar; projected along its largest component, mirrored where
// needed so that the polygon turns counter-clockwise.
std::vector<glm::dvec2> inPlane(const std::vector<glm::dvec3>& corners) {
  const std::size_t n = corners.size();
  glm::dvec3 normal(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3& a = corners[i];
    const glm::dvec3& b = corners[(i + 1) % n];
    normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::fabs(normal[k]) > std::fabs(normal[axis])) axis = k;
  }
  if (!(std::fabs(normal[axis]) > 0.0) || !std::isfinite(normal[axis])) return {};
  const int u = normal[axis] > 0.0 ? (axis + 1) % 3 : (axis + 2) % 3;
  const int v = normal[axis] > 0.0 ? (axis + 2) % 3 : (axis + 1) % 3;
  std::vector<glm::dvec2> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = {corners[i][u], corners[i][v]};
  return p;
}

}  // namespace

std::vector<std::array<unsigned, 3>> triangulatePolygon(const std::vector<glm::dvec3>& corners) {
  const unsigned n = unsigned(corners.size());
  std::vector<std::array<unsigned, 3>> triangles;
  if (n < 3) return triangles;
  triangles.reserve(n - 2);
  const auto fanFrom = [&](unsigned first, const std::vector<unsigned>& next) {
    for (unsigned j = next[first]; next[j] != first; j = next[j]) triangles.push_back({first, j, next[j]});
  };
  std::vector<unsigned> prev(n), next(n);
  for (unsigned i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }

  const std::vector<glm::dvec2> p = n == 3 ? std::vector<glm::dvec2>() : inPlane(corners);
  if (p.empty()) {
    fanFrom(0, next);  // a triangle, or no plane to work in
    return triangles;
  }

  // Only a reflex corner can lie in a candidate ear (a collinear one counts: it may lie on
  // the ear's edge). Cutting ears only narrows the corners beside them, but a polygon that
  // crosses itself may turn one reflex, which then joins the list.
  std::vector<char> reflex(n), listed(n);
  std::vector<unsigned> reflexList;
  const auto classify = [&](unsigned j) {
    reflex[j] = !(turn(p[prev[j]], p[j], p[next[j]]) > 0.0);
    if (reflex[j] && !listed[j]) {
      listed[j] = 1;
      reflexList.push_back(j);
    }
  };
  for (unsigned j = 0; j < n; ++j) classify(j);
  if (reflexList.empty()) {
    fanFrom(0, next);  // convex: the fan every tool draws
    return triangles;
  }

  std::vector<char> removed(n, 0);
  const std::size_t budget = std::size_t(n) * n;
  std::size_t steps = 0;
  unsigned remaining = n, i = 0, sinceEar = 0;
  while (remaining > 3 && sinceEar < remaining && steps < budget) {
    ++steps;
    const unsigned a = prev[i], c = next[i];
    bool ear = !reflex[i];
    for (std::size_t k = 0; ear && k < reflexList.size(); ++k) {
      const unsigned j = reflexList[k];
      ++steps;
      if (removed[j] || !reflex[j] || j == a || j == c) continue;
      if (p[j] == p[a] || p[j] == p[i] || p[j] == p[c]) continue;  // a corner repeated (a bridge)
      ear = !inTriangle(p[j], p[a], p[i], p[c]);
    }
    if (!ear) {
      i = c;
      ++sinceEar;
      continue;
    }
    triangles.push_back({a, i, c});
    removed[i] = 1;
    next[a] = c;
    prev[c] = a;
    --remaining;
    classify(a);
    classify(c);
    i = a;  // the corner before the ear is the likeliest next one
    sinceEar = 0;
  }
  fanFrom(i, next);  // the last triangle, or what no ear could be cut from
  return triangles;
}

}  // namespace rc
