// Watertightness at scale (issue 3): seeded random meshes (jittered grids and fans with
// vertices on the 1/16-pixel grid, as piglit does, so edges often pass exactly through pixel
// centres; and jittered closed spheres), each checked against the exact oracle:
//   - every triangle's rasterizer coverage equals the oracle's;
//   - planar meshes: no pixel centre covered twice, and none strictly inside the snapped
//     outline left uncovered (holes);
//   - closed meshes: at every pixel centre as many front- as back-facing triangles.
// CI runs RASTERCHECK_WATERTIGHT_MESHES (default 60) meshes; set it to 10000 for the full run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>

#include "rasterizer/rasterizer.h"
#include "scenes/hard/hard_scenes.h"
#include "tests/oracle/exact.h"

namespace rc {
namespace {

constexpr int kSize = 64;

int meshCount() {
  const char* env = std::getenv("RASTERCHECK_WATERTIGHT_MESHES");
  return env ? std::max(1, std::atoi(env)) : 60;
}

struct RandomMesh {
  Scene scene;
  std::vector<unsigned> outline;  // planar meshes: boundary vertices in order; empty = closed
};

Camera testCamera() { return Camera(lookAt({0, 0, 0}, {0, 0, -1}, 50.0, 0.1, kSize, kSize), "watertight"); }

unsigned addVertex(Mesh& mesh, const Camera& camera, double x, double y, double w) {
  mesh.positions.emplace_back(glm::vec3(camera.worldAtRaster({x, y}, w)));
  return unsigned(mesh.positions.size() - 1);
}

double onGrid(double v) { return std::round(v * 16.0) / 16.0; }  // 1/16-pixel grid

RandomMesh makeMesh(std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Camera camera = testCamera();
  Mesh mesh;
  std::vector<unsigned> outline;
  // A random plane for depth: 1/w affine in raster space, depth between about 2 and 6.
  const double w0 = 2.0 + 3.0 * unit(rng), gx = (unit(rng) - 0.5) * 0.004, gy = (unit(rng) - 0.5) * 0.004;
  const auto depth = [&](double x, double y) { return 1.0 / (1.0 / w0 + gx * (x - 32) + gy * (y - 32)); };
  if (kind == 0) {  // jittered grid
    const int nx = 2 + int(unit(rng) * 10), ny = 2 + int(unit(rng) * 10);
    const double sx = 56.0 / nx, sy = 56.0 / ny;
    std::vector<unsigned> id((nx + 1) * (ny + 1));
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        const double jitter = (i > 0 && i < nx && j > 0 && j < ny) ? 0.3 : 0.0;
        const double x = onGrid(4 + i * sx + (unit(rng) - 0.5) * jitter * sx);
        const double y = onGrid(4 + j * sy + (unit(rng) - 0.5) * jitter * sy);
        id[j * (nx + 1) + i] = addVertex(mesh, camera, x, y, depth(x, y));
      }
    }
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const unsigned a = id[j * (nx + 1) + i], b = id[j * (nx + 1) + i + 1];
        const unsigned c = id[(j + 1) * (nx + 1) + i + 1], d = id[(j + 1) * (nx + 1) + i];
        if (unit(rng) < 0.5) {
          mesh.triangles.push_back({a, b, c});
          mesh.triangles.push_back({a, c, d});
        } else {
          mesh.triangles.push_back({a, b, d});
          mesh.triangles.push_back({b, c, d});
        }
      }
    }
    for (int i = 0; i < nx; ++i) outline.push_back(id[i]);
    for (int j = 0; j < ny; ++j) outline.push_back(id[j * (nx + 1) + nx]);
    for (int i = nx; i > 0; --i) outline.push_back(id[ny * (nx + 1) + i]);
    for (int j = ny; j > 0; --j) outline.push_back(id[j * (nx + 1)]);
  } else if (kind == 1) {  // fan around a pixel centre
    const int n = 3 + int(unit(rng) * 62);
    const double cx = 28 + int(unit(rng) * 8) + 0.5, cy = 28 + int(unit(rng) * 8) + 0.5;
    const double radius = 8.0 + 18.0 * unit(rng), phase = unit(rng) * 6.28;
    const unsigned centre = addVertex(mesh, camera, cx, cy, depth(cx, cy));
    for (int k = 0; k < n; ++k) {
      const double a = phase + 2.0 * M_PI * (k + 0.4 * (unit(rng) - 0.5)) / n;
      const double r = radius * (0.7 + 0.3 * unit(rng));
      const double x = onGrid(cx + r * std::cos(a)), y = onGrid(cy + r * std::sin(a));
      outline.push_back(addVertex(mesh, camera, x, y, depth(x, y)));
    }
    for (int k = 0; k < n; ++k) mesh.triangles.push_back({centre, outline[k], outline[(k + 1) % n]});
  } else {  // closed jittered sphere, 4 units in front of the eye
    const Mesh sphere = hard::jitteredSphere(rng(), 1 + int(unit(rng) * 3), 0.2);
    for (const glm::vec3& p : sphere.positions) mesh.positions.push_back(p + glm::vec3(0.0f, 0.0f, -4.0f));
    mesh.triangles = sphere.triangles;
  }
  // Random vertex rotation per triangle: coverage must not care.
  for (glm::uvec3& t : mesh.triangles) {
    if (unit(rng) < 0.5) t = {t.y, t.z, t.x};
  }
  return {Scene{"random", "", std::move(mesh), camera}, outline};
}

// Winding number of the closed integer polygon around p; `onBoundary` when p lies on it.
int winding(const std::vector<std::array<std::int64_t, 2>>& poly, std::int64_t px, std::int64_t py, bool& onBoundary) {
  int wn = 0;
  onBoundary = false;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto& a = poly[i];
    const auto& b = poly[(i + 1) % poly.size()];
    const std::int64_t cross = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
    if (cross == 0 && std::min(a[0], b[0]) <= px && px <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= py &&
        py <= std::max(a[1], b[1])) {
      onBoundary = true;
    }
    if (a[1] <= py) {
      if (b[1] > py && cross > 0) ++wn;
    } else if (b[1] <= py && cross < 0) {
      --wn;
    }
  }
  return wn;
}

TEST(Watertight, RandomMeshesHaveNoHolesNoDoubleCoversAndMatchTheOracle) {
  std::mt19937_64 rng(20261122);
  const int count = meshCount();
  long long triangles = 0, coveredCentres = 0, holes = 0, doubles = 0, mismatches = 0, unbalanced = 0, ambiguous = 0;
  for (int m = 0; m < count; ++m) {
    const int kind = m % 3;
    const RandomMesh r = makeMesh(rng, kind);
    const Scene& scene = r.scene;
    RasterOptions options;
    options.culling = Culling::kNone;  // front and back faces both count
    const auto pairs = coveredPixels(scene, options);
    const oracle::Oracle exact(scene, options.subpixelBits);
    std::map<std::uint32_t, std::vector<std::uint32_t>> raster;
    for (const auto& [t, p] : pairs) raster[t].push_back(p);
    std::vector<int> covers(kSize * kSize, 0), signedCount(kSize * kSize, 0);
    for (std::size_t t = 0; t < scene.mesh.triangleCount(); ++t) {
      const oracle::CoverageResult o = exact.coverage(t);
      ambiguous += o.ambiguousSnaps;
      auto& got = raster[std::uint32_t(t)];
      std::sort(got.begin(), got.end());
      if (o.ambiguousSnaps == 0 && got != o.pixels) ++mismatches;
      // Orientation of the snapped triangle on screen (front or back facing).
      int amb = 0;
      const glm::uvec3 tri = scene.mesh.triangles[t];
      const auto a = exact.snapped(tri.x, amb), b = exact.snapped(tri.y, amb), c = exact.snapped(tri.z, amb);
      const std::int64_t area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      for (std::uint32_t p : got) {
        ++covers[p];
        signedCount[p] += area > 0 ? 1 : -1;
      }
    }
    triangles += long(scene.mesh.triangleCount());
    if (r.outline.empty()) {
      for (int v : signedCount) unbalanced += v != 0;
    } else {
      int amb = 0;
      std::vector<std::array<std::int64_t, 2>> poly;
      for (unsigned v : r.outline) poly.push_back(exact.snapped(v, amb));
      for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
          const int c = covers[y * kSize + x];
          coveredCentres += c > 0;
          doubles += c > 1;
          bool onBoundary = false;
          const std::int64_t half = std::int64_t(1) << (options.subpixelBits - 1);
          if (winding(poly, (2 * x + 1) * half, (2 * y + 1) * half, onBoundary) != 0 && !onBoundary && c == 0) ++holes;
        }
      }
    }
  }
  std::printf("[watertight] %d meshes (%lld triangles): %lld covered pixel centres in planar meshes, "
              "%lld holes, %lld double covers, %lld closed-mesh pixels with unequal front/back counts, "
              "%lld triangles differing from the oracle, %lld snapping ties skipped\n",
              count, triangles, coveredCentres, holes, doubles, unbalanced, mismatches, ambiguous);
  EXPECT_EQ(holes, 0);
  EXPECT_EQ(doubles, 0);
  EXPECT_EQ(unbalanced, 0);
  EXPECT_EQ(mismatches, 0);
}

}  // namespace
}  // namespace rc
