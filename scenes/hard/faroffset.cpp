// "faroffset:offset=D": a small scene (a fan, a tilted quad and a sphere-like patch, about 4
// units across, 6 units in front of the camera) moved together with its camera by D along
// (1, 0.7, -0.4) / |.|; D from 0 to 10^7 (default 10^5).
//
// Stresses: large world coordinates. Float positions near |p| are spaced |p| 2^-23 apart
// (1 unit at 10^7), so the offset scene's floats describe a slightly different shape; both
// paths must see that same shape without losing more. The rasterizer transforms to clip space
// in double; the reference hands Embree camera-relative floats (vertex - eye in double, then
// rounded) and recomputes in double (docs/numerics.md, "Large world coordinates").
// Must hold: barycentrics within the bound of the oracle computed from the same float
// vertices, at every offset; the gate passes at 10^3, 10^5 and 10^7.
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeFarOffset(SceneArgs& args) {
  const double distance = args.getDouble("offset", 1e5, 0.0, 1e7);
  const glm::dvec3 offset = distance * glm::normalize(glm::dvec3(1.0, 0.7, -0.4));
  Builder b("faroffset", lookAt(offset + glm::dvec3(0.3, 1.5, 6.0), offset, 45.0, 0.1, 160, 120));
  const auto at = [&](double x, double y, double z) { return b.world(offset + glm::dvec3(x, y, z)); };
  // A fan of 10 triangles.
  const unsigned centre = at(-1.0, 0.5, 0.0);
  unsigned ring[10];
  for (int k = 0; k < 10; ++k) {
    const double a = 2.0 * M_PI * k / 10.0;
    ring[k] = at(-1.0 + 1.2 * std::cos(a), 0.5 + 1.2 * std::sin(a), 0.3 * std::sin(2.0 * a));
  }
  for (int k = 0; k < 10; ++k) b.triangle(centre, ring[k], ring[(k + 1) % 10]);
  // A tilted quad.
  const unsigned q0 = at(0.5, -1.5, -1.0), q1 = at(2.5, -1.2, 0.5), q2 = at(2.2, 1.0, 0.8), q3 = at(0.3, 0.8, -0.7);
  b.triangle(q0, q1, q2);
  b.triangle(q0, q2, q3);
  // A patch of a sphere of radius 1 around (0, -1, 1): 8 x 8 quads.
  const int n = 8;
  unsigned grid[n + 1][n + 1];
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double theta = 0.3 + 1.2 * i / n, phi = -0.8 + 1.6 * j / n;
      grid[i][j] = at(std::sin(theta) * std::sin(phi), -1.0 + std::cos(theta), 1.0 + std::sin(theta) * std::cos(phi));
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      b.triangle(grid[i][j], grid[i + 1][j], grid[i + 1][j + 1]);
      b.triangle(grid[i][j], grid[i + 1][j + 1], grid[i][j + 1]);
    }
  }
  return b.finish();
}

}  // namespace rc::hard
