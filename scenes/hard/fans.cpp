// "fans": vertex fans of 3 to 64 triangles, each around a vertex on a pixel centre.
//
// Stresses: the fill rule where many triangles meet. Every outer vertex also sits on a pixel
// centre, so every spoke runs exactly through pixel centres (its own slope each). Fans
// alternate in winding, and all lie in one plane tilted in depth.
// Must hold: every pixel centre inside a fan's outline has exactly one owner (the centre
// vertex's pixel included); none outside has any; the owners are the same when each
// triangle's vertex order is rotated (tests/oracle/coverage_oracle_test.cpp).
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeFans(SceneArgs&) {
  Builder b("fans", frontCamera(256, 192));
  const int counts[12] = {3, 4, 5, 6, 7, 8, 12, 16, 24, 32, 48, 64};
  const DepthPlane plane{128.0, 96.0, 4.0, 4e-4, -2.5e-4};
  for (int f = 0; f < 12; ++f) {
    const int cx = 32 + 64 * (f % 4), cy = 32 + 64 * (f / 4);
    const int n = counts[f];
    const double radius = 27.0, phase = 0.3 * f;
    const unsigned centre = b.atPixel(cx, cy, plane.at(cx + 0.5, cy + 0.5));
    unsigned ring[64];
    for (int k = 0; k < n; ++k) {
      const double angle = phase + 2.0 * M_PI * k / n;
      const int px = cx + int(std::lround(radius * std::cos(angle)));
      const int py = cy + int(std::lround(radius * std::sin(angle)));
      ring[k] = b.atPixel(px, py, plane.at(px + 0.5, py + 0.5));
    }
    for (int k = 0; k < n; ++k) b.triangle(centre, ring[k], ring[(k + 1) % n], f % 2 == 1);
  }
  return b.finish();
}

}  // namespace rc::hard
