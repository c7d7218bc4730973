// "depthpairs": pairs of parallel quads facing the camera at depths z = near * 10^k,
// k = 0.5, 1, ..., 6 (near = 0.1). In each column the back quad fills the column and the front
// quad covers its middle third. The gap between the two is, in the upper half of the column,
// 4x the depth resolution of the standard float mapping d = 1 - near/z (2^-24 z/near relative,
// at least 4 ulps), and in the lower half 4x the resolution of a 1/w mapping (2^-22 relative)
// but below the standard mapping's once z/near exceeds 4.
//
// Stresses: depth-test precision for both mappings of the rasterizer (--depth-mapping
// inverse-w, the default, or standard).
// Must hold: with inverse-w depth, the front quad wins everywhere it covers; with the standard
// mapping, the front quad wins in the upper halves, and where it loses in a lower half compare
// classifies the pixel as a depth tie (within the rasterizer's reported depth resolution).
#include <algorithm>
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeDepthPairs(SceneArgs&) {
  Builder b("depthpairs", frontCamera(192, 96, 60.0, 0.1));
  const double zNear = 0.1, u = std::ldexp(1.0, -24);
  const auto quad = [&](double x0, double y0, double x1, double y1, double w) {
    const unsigned a = b.at(x0, y0, w), c = b.at(x1, y0, w), d = b.at(x1, y1, w), e = b.at(x0, y1, w);
    b.triangle(a, c, d);
    b.triangle(a, d, e);
  };
  for (int k = 0; k < 12; ++k) {
    const double z = zNear * std::pow(10.0, 0.5 * (k + 1));
    const double x0 = 16.0 * k + 0.3, x1 = x0 + 15.4;
    const double standardGap = 4.0 * std::max(u * z / zNear, 4.0 * u);  // relative
    const double inverseGap = 4.0 * 4.0 * u;
    quad(x0, 0.3, x1, 47.7, z * (1.0 + standardGap));
    quad(x0, 48.3, x1, 95.7, z * (1.0 + inverseGap));
    quad(x0 + 5.1, 4.2, x1 - 5.1, 91.8, z);
  }
  return b.finish();
}

}  // namespace rc::hard
