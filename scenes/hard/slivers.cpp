// "slivers": needles with screen aspect ratios 10, 100, ..., 10^7 in eight orientations, each
// at its own depth, thin enough that some cover no pixel centre and long enough (up to 2e5
// pixels, far outside the image) that the thinnest still cover some.
//
// Stresses: the conditioning K = L^2 / 2A of the barycentric computation (docs/numerics.md),
// and snapping: a needle thinner than the subpixel grid may vanish or gain area.
// Must hold: no NaN or Inf anywhere; coverage equal to the exact oracle's; barycentrics within
// the bound, which grows with K.
#include <algorithm>
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeSlivers(SceneArgs&) {
  Builder b("slivers", frontCamera(256, 256));
  int index = 0;
  for (int e = 1; e <= 7; ++e) {
    const double aspect = std::pow(10.0, e);
    for (int o = 0; o < 8; ++o, ++index) {
      const double angle = o * (M_PI / 8.0) + 0.05 * e;
      const double length = std::max(180.0, 0.3 * aspect / 10.0);  // width >= 0.003 px
      const double width = length / aspect;
      const double cx = 20.0 + 216.0 * ((index * 37) % 56) / 56.0;
      const double cy = 20.0 + 216.0 * ((index * 17) % 56) / 56.0;
      const double ux = std::cos(angle), uy = std::sin(angle);
      const double depth = 2.0 + 0.15 * index;
      const unsigned p0 = b.at(cx - ux * length / 2, cy - uy * length / 2, depth);
      const unsigned p1 = b.at(cx + ux * length / 2, cy + uy * length / 2, depth * 1.3);
      const unsigned p2 = b.at(cx - uy * width, cy + ux * width, depth * 1.1);
      b.triangle(p0, p1, p2, o % 2 == 1);
    }
  }
  return b.finish();
}

}  // namespace rc::hard
