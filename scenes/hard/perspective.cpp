// "perspective": triangles with one vertex just beyond the near plane and the others far
// away: w_max / w_min = 10^2, 10^4 and 10^6, plus a long floor-like strip whose depth ratio
// is 10^6 across a single triangle.
//
// Stresses: the perspective division b_i = (l_i / w_i) / sum(l_j / w_j), which amplifies the
// screen-space error by up to rho = w_max / w_min, and 1/w depth over such a range.
// Must hold: barycentrics within rho (c u K) + c' u of the exact oracle (docs/numerics.md);
// all outputs finite.
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makePerspective(SceneArgs&) {
  Builder b("perspective", frontCamera(192, 128, 60.0, 0.01));
  const double nearW = 0.0101;
  for (int k = 0; k < 3; ++k) {
    const double far = nearW * std::pow(10.0, 2 + 2 * k);
    const double x = 8.0 + 60.0 * k;
    b.triangle(b.at(x + 10.0, 10.0, nearW), b.at(x + 55.0, 20.0, far), b.at(x + 5.0, 60.0, far * 0.7));
  }
  // A strip of two triangles from depth 0.0101 to 10100, seen from above at a shallow angle.
  const unsigned a = b.world({-0.005, -0.005, -0.0101}), c = b.world({0.005, -0.005, -0.0101});
  const unsigned d = b.world({-1e4, -5.0, -10100.0}), e = b.world({1e4, -5.0, -10100.0});
  b.triangle(a, c, e);
  b.triangle(a, e, d);
  return b.finish();
}

}  // namespace rc::hard
