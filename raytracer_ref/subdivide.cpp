// Splitting triangles that Embree's float arithmetic cannot place accurately (subdivide.h).
#include "raytracer_ref/subdivide.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/parallel.h"

namespace rc {

double distanceToTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  // Closest point on a triangle to p = 0, by Voronoi regions (Ericson, Real-Time Collision
  // Detection, 5.1.5). A degenerate triangle (a repeated vertex, collinear vertices) makes some
  // denominators zero: the segment's start, a vertex, stands in for the point then, or the
  // nearest vertex for the face region.
  const double nearestVertex = std::min({glm::length(a), glm::length(b), glm::length(c)});
  const auto ratio = [](double n, double d) { return d != 0.0 ? n / d : 0.0; };
  const glm::dvec3 ab = b - a, ac = c - a, ap = -a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return glm::length(a);
  const glm::dvec3 bp = -b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return glm::length(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return glm::length(a + ab * ratio(d1, d1 - d3));
  const glm::dvec3 cp = -c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return glm::length(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return glm::length(a + ac * ratio(d2, d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return glm::length(b + (c - b) * ratio(d4 - d3, (d4 - d3) + (d5 - d6)));
  }
  const double sum = va + vb + vc;
  if (!(sum != 0.0)) return nearestVertex;
  return glm::length(a + ab * (vb / sum) + ac * (vc / sum));
}

namespace {

constexpr int kMaxDepth = 64;

struct Splitter {
  glm::dvec3 forward, right, up;
  double zNear, tanX, tanY;
  EmbreeTriangles& out;

  // True when every vertex is outside the same plane of the widened frustum or behind near.
  bool outside(const glm::dvec3 p[3]) const {
    unsigned all = 0x1F;
    for (int i = 0; i < 3; ++i) {
      const double depth = glm::dot(p[i], forward), x = glm::dot(p[i], right), y = glm::dot(p[i], up);
      unsigned code = 0;
      if (depth < zNear) code |= 1;
      if (x > 2.0 * tanX * depth) code |= 2;
      if (-x > 2.0 * tanX * depth) code |= 4;
      if (y > 2.0 * tanY * depth) code |= 8;
      if (-y > 2.0 * tanY * depth) code |= 16;
      all &= code;
    }
    return all != 0;
  }

  void emit(const glm::dvec3 p[3], std::uint32_t source) {
    const auto base = unsigned(out.vertices.size() / 3);
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) out.vertices.push_back(float(p[i][k]));
      out.indices.push_back(base + unsigned(i));
    }
    out.source.push_back(source);
  }

  void split(const glm::dvec3 p[3], std::uint32_t source, int depth) {
    if (outside(p)) return;
    const double e[3] = {glm::length(p[1] - p[2]), glm::length(p[2] - p[0]), glm::length(p[0] - p[1])};
    const int longest = int(std::max_element(e, e + 3) - e);  // edge opposite vertex `longest`
    if (depth >= kMaxDepth || e[longest] <= kMaxLengthOverDistance * distanceToTriangle(p[0], p[1], p[2])) {
      emit(p, source);
      return;
    }
    const int i = longest, j = (i + 1) % 3, k = (i + 2) % 3;
    const glm::dvec3 mid = 0.5 * (p[j] + p[k]);
    glm::dvec3 first[3], second[3];  // both keep the winding of p
    first[i] = p[i], first[j] = p[j], first[k] = mid;
    second[i] = p[i], second[j] = mid, second[k] = p[k];
    split(first, source, depth + 1);
    split(second, source, depth + 1);
  }
};

constexpr std::size_t kBlock = 16384;  // vertices or triangles per parallel work item

int blocksOf(std::size_t count) { return int((count + kBlock - 1) / kBlock); }

}  // namespace

EmbreeTriangles embreeTriangles(const Mesh& mesh, const Camera& camera, int threads) {
  const glm::dvec3 eye = camera.spec().eye;
  const auto relativeTo = [&](const glm::uvec3& tri, glm::dvec3 p[3]) {
    for (int i = 0; i < 3; ++i) p[i] = glm::dvec3(mesh.positions[tri[i]]) - eye;  // in double
  };
  EmbreeTriangles out;
  const std::size_t vertexCount = mesh.vertexCount(), triangleCount = mesh.triangleCount();
  out.vertices.reserve(3 * vertexCount + 1);  // + Embree's padding (reference.cpp's buildGeometry)
  out.vertices.resize(3 * vertexCount);
  parallelFor(blocksOf(vertexCount), threads, [&](int b) {
    const std::size_t end = std::min(vertexCount, (std::size_t(b) + 1) * kBlock);
    for (std::size_t v = std::size_t(b) * kBlock; v < end; ++v) {
      const glm::dvec3 relative = glm::dvec3(mesh.positions[v]) - eye;  // rounded once, below
      for (int k = 0; k < 3; ++k) out.vertices[3 * v + std::size_t(k)] = float(relative[k]);
    }
  });
  // Which triangles Embree can take as they are: the test is most of the work, and each
  // triangle's answer is its own, so it runs in parallel; the rare splitting stays serial.
  std::vector<std::uint8_t> fits(triangleCount);
  std::vector<std::uint8_t> blockFits(std::size_t(blocksOf(triangleCount)));
  parallelFor(blocksOf(triangleCount), threads, [&](int b) {
    const std::size_t end = std::min(triangleCount, (std::size_t(b) + 1) * kBlock);
    bool all = true;
    for (std::size_t t = std::size_t(b) * kBlock; t < end; ++t) {
      glm::dvec3 p[3];
      relativeTo(mesh.triangles[t], p);
      const double longest =
          std::max({glm::length(p[1] - p[2]), glm::length(p[2] - p[0]), glm::length(p[0] - p[1])});
      fits[t] = longest <= kMaxLengthOverDistance * distanceToTriangle(p[0], p[1], p[2]);
      all = all && fits[t];
    }
    blockFits[std::size_t(b)] = all;
  });
  if (std::all_of(blockFits.begin(), blockFits.end(), [](std::uint8_t all) { return all != 0; })) {
    return out;  // the mesh's own triangles, identity source
  }
  Splitter splitter{camera.forward(), camera.right(), camera.up(), camera.zNear(),
                    camera.tanHalfFovY() * camera.aspect(), camera.tanHalfFovY(), out};
  out.indices.reserve(3 * triangleCount);
  out.source.reserve(triangleCount);
  for (std::size_t t = 0; t < triangleCount; ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    if (fits[t]) {
      for (int k = 0; k < 3; ++k) out.indices.push_back(tri[k]);
      out.source.push_back(std::uint32_t(t));
      continue;
    }
    glm::dvec3 p[3];
    relativeTo(tri, p);
    splitter.split(p, std::uint32_t(t), 0);
  }
  return out;
}

}  // namespace rc
