// "degenerate": exactly degenerate triangles (three collinear float points, a repeated vertex
// index, two vertices with equal coordinates, all three the same), near-degenerate ones (the
// third vertex one float ulp off the line through the other two), and one ordinary triangle
// behind them so the images have content.
//
// Stresses: division by a zero or tiny area in set-up, in clipping and in the reference.
// Must hold: zero-area triangles produce no pixels in either path; no NaN or Inf anywhere;
// coverage equal to the exact oracle's.
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeDegenerate(SceneArgs&) {
  Builder b("degenerate", frontCamera(128, 128));
  // Background triangle, far behind.
  b.triangle(b.at(-20, -20, 20), b.at(300, -10, 20), b.at(10, 300, 20));
  for (int row = 0; row < 4; ++row) {
    const double z = -3.0 - row;
    const float y = float(0.5 - 0.3 * row);
    // Collinear in exact float arithmetic: equally spaced on a line through the origin's row.
    b.triangle(b.world({-1.0, y, z}), b.world({0.0, y, z}), b.world({1.0, y, z}));
    b.triangle(b.world({-1.0, -1.0, z}), b.world({0.0, 0.0, z}), b.world({1.0, 1.0, z}));
    // Repeated index, and repeated coordinates under different indices.
    const unsigned a = b.world({-0.5, y + 0.2f, z}), c = b.world({0.5, y + 0.25f, z});
    b.triangle(a, a, c);
    b.triangle(a, b.world({-0.5, y + 0.2f, z}), c);
    b.triangle(a, a, a);
    // Near-degenerate: the middle vertex one ulp above the segment's midpoint.
    const float mid = y - 0.1f;
    b.triangle(b.world({-0.9, mid, z}), b.world({0.0, std::nextafter(mid, 1.0f), z}),
               b.world({0.9, mid, z}));
    b.triangle(b.world({-0.9, mid - 0.05f, z}), b.world({0.9, mid - 0.05f, z}),
               b.world({0.0, std::nextafter(mid - 0.05f, -1.0f), z}));
  }
  return b.finish();
}

}  // namespace rc::hard
