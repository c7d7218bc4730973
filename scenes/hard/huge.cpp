// "huge": triangles reaching far outside the viewport, with vertices 10^6 and 10^9 pixels
// away (the latter beyond the guard band, so they are clipped), at several depths and slopes.
//
// Stresses: integer ranges of the fixed-point edge functions and the guard-band clipping that
// keeps them exact (rasterizer/coverage.h), and float accuracy far from the vertices.
// Must hold: no overflow (the suite runs under UBSan), coverage equal to the exact oracle's,
// barycentrics within the bound.
#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeHuge(SceneArgs&) {
  Builder b("huge", frontCamera(128, 128));
  const double far1 = 1e6, far2 = 1e9;
  // Covers the whole image: vertices a million pixels out.
  b.triangle(b.at(-far1, -far1, 30.0), b.at(far1, -far1 / 3, 31.0), b.at(0.0, far1, 29.0));
  // An edge crossing the image diagonally, the other vertices a billion pixels out.
  b.triangle(b.at(-far2, -far2, 10.0), b.at(far2, far2 + 40.0, 12.0), b.at(-far2, far2, 11.0));
  // A thin wedge from inside the image to 1e9 px, and one whose every vertex is outside.
  b.triangle(b.at(64.3, 64.7, 5.0), b.at(far2, 1e7, 6.0), b.at(far2, 3e7, 6.0));
  b.triangle(b.at(-far2, 20.2, 8.0), b.at(far2, 30.9, 8.0), b.at(0.0, -far2, 8.5));
  // Huge in both directions, steeply sloped in depth.
  b.triangle(b.at(-far1, 90.5, 2.0), b.at(far1, 100.5, 50.0), b.at(64.0, far1, 7.0), true);
  return b.finish();
}

}  // namespace rc::hard
