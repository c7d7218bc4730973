// "zfight": coplanar overlapping triangles: two quads in one tilted plane overlapping by half,
// a triangle repeated three times with the same vertices (once under other indices, once with
// its vertex order rotated), and a pair of triangles crossing each other.
//
// Stresses: depth ties. Any of the overlapping triangles is a right answer where they overlap.
// Must hold: the answer is the same on every run and for any thread count (the rasterizer
// gives a tie to the lower triangle index); compare classifies the disagreements with the
// reference as depth ties, never as unexplained.
#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeZFight(SceneArgs&) {
  Builder b("zfight", frontCamera(128, 96));
  const DepthPlane plane{64.0, 48.0, 3.0, 2e-3, 1e-3};
  const auto v = [&](double x, double y) { return b.at(x, y, plane.at(x, y)); };
  // Two quads in the same plane, overlapping in x from 40 to 70.
  const unsigned a0 = v(8.3, 8.2), a1 = v(70.6, 8.2), a2 = v(70.6, 50.1), a3 = v(8.3, 50.1);
  const unsigned c0 = v(40.2, 20.4), c1 = v(120.7, 20.4), c2 = v(120.7, 60.9), c3 = v(40.2, 60.9);
  b.triangle(a0, a1, a2);
  b.triangle(a0, a2, a3);
  b.triangle(c0, c1, c2);
  b.triangle(c0, c2, c3);
  // One triangle three times: same indices, same coordinates under new indices, rotated order.
  const unsigned t0 = v(10.4, 60.3), t1 = v(50.8, 66.1), t2 = v(25.2, 92.5);
  b.triangle(t0, t1, t2);
  b.triangle(v(10.4, 60.3), v(50.8, 66.1), v(25.2, 92.5));
  b.triangle(t1, t2, t0);
  // Two triangles crossing each other along a line (not coplanar): a tie only on the line.
  b.triangle(b.at(70.0, 65.0, 4.0), b.at(120.0, 68.0, 6.0), b.at(90.0, 94.0, 4.0));
  b.triangle(b.at(72.0, 90.0, 6.0), b.at(118.0, 92.0, 4.0), b.at(96.0, 64.0, 5.0));
  return b.finish();
}

}  // namespace rc::hard
