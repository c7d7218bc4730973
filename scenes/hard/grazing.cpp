// "grazing": a floor and a wall seen nearly edge-on. The camera looks horizontally 1 unit above
// a floor reaching 10^4 units away, so the angle between the view ray and the surface falls
// from about 2 degrees at the bottom of the image to below 0.01 degrees near the horizon; a
// wall 0.5 units to the side runs the same way. Both are tessellated into strips whose depth
// grows geometrically, so no triangle is much thinner on screen than its neighbours.
//
// Stresses: the reference's conditioning (Embree's error grows as 1/|cos theta| between ray and
// normal) and the rasterizer's: screen-space triangles become long and thin near the horizon.
// Must hold: coverage equal to the exact oracle's; barycentrics within each path's bound;
// disagreements only in the edge band.
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeGrazing(SceneArgs&) {
  Builder b("grazing", lookAt({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 40.0, 0.1, 256, 128));
  const int strips = 40, columns = 6;
  const auto depthAt = [&](int i) { return 1.0 * std::pow(1e4, double(i) / strips); };
  // Floor y = -1 from x = -3 to 3; wall x = 0.5 from y = -1 to 1.
  unsigned floorRow[2][columns + 1], wallRow[2][columns + 1];
  for (int i = 0; i <= strips; ++i) {
    const double z = -depthAt(i);
    for (int k = 0; k <= columns; ++k) {
      floorRow[i % 2][k] = b.world({-3.0 + 6.0 * k / columns, -1.0, z});
      wallRow[i % 2][k] = b.world({0.5, -1.0 + 2.0 * k / columns, z});
    }
    if (i == 0) continue;
    const auto* f0 = floorRow[(i - 1) % 2];
    const auto* f1 = floorRow[i % 2];
    const auto* w0 = wallRow[(i - 1) % 2];
    const auto* w1 = wallRow[i % 2];
    for (int k = 0; k < columns; ++k) {
      b.triangle(f0[k], f0[k + 1], f1[k + 1]);
      b.triangle(f0[k], f1[k + 1], f1[k]);
      b.triangle(w0[k], w1[k + 1], w0[k + 1]);
      b.triangle(w0[k], w1[k], w1[k + 1]);
    }
  }
  return b.finish();
}

}  // namespace rc::hard
