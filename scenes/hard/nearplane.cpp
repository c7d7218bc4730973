// "nearplane": triangles at and through the near plane (near = 0.1): vertices with w just
// above near (1 + 1e-3 ... 1 + 1e-7), one or two vertices behind the near plane, one or two
// behind the eye (w < 0), a vertex exactly in the eye plane (w = 0), triangles crossing w = 0,
// and a triangle entirely behind the eye.
//
// Stresses: homogeneous clipping in barycentric space (rasterizer/clip.h): new vertices on the
// near plane, their barycentrics relative to the source triangle, and division by tiny w.
// Must hold: nothing at depth < near is drawn by either path (the reference starts its rays at
// near); the triangle behind the eye draws nothing; all outputs finite; barycentrics within
// the bound computed from the clipped sub-triangle's w ratio.
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeNearPlane(SceneArgs&) {
  Builder b("nearplane", frontCamera(128, 128, 60.0, 0.1));
  const Camera& cam = b.camera();
  const auto eyePlane = [&](double right, double up) {  // w = 0: a point in the eye plane
    return b.world(cam.spec().eye + right * cam.right() + up * cam.up());
  };
  // Vertices approaching the near plane from above, one triangle per distance.
  for (int k = 0; k < 5; ++k) {
    const double w = 0.1 * (1.0 + std::pow(10.0, -3 - k));
    const double x = 8.0 + 24.0 * k;
    b.triangle(b.at(x, 10.0, w), b.at(x + 20.0, 12.0, 3.0), b.at(x + 4.0, 30.0, 3.0));
  }
  // One vertex behind the near plane (w = 0.05), and one behind the eye (w = -1).
  b.triangle(b.at(20.0, 40.0, 0.05), b.at(60.0, 45.0, 2.0), b.at(30.0, 70.0, 2.5));
  b.triangle(b.at(70.0, 40.0, -1.0), b.at(120.0, 50.0, 2.0), b.at(90.0, 75.0, 1.5));
  // Two vertices behind the eye, the third in front: a sliver of it is visible.
  b.triangle(b.at(10.0, 80.0, -2.0), b.at(60.0, 90.0, -0.5), b.at(35.0, 110.0, 1.0));
  // A vertex exactly in the eye plane; a triangle crossing w = 0 with its edge through the eye
  // plane; and one entirely behind the eye, which must draw nothing.
  b.triangle(eyePlane(0.3, -0.2), b.at(80.0, 90.0, 2.0), b.at(120.0, 120.0, 3.0));
  b.triangle(b.at(70.0, 100.0, 4.0), eyePlane(-0.5, -0.4), b.at(100.0, 126.0, -3.0));
  b.triangle(b.at(10.0, 10.0, -1.0), b.at(120.0, 10.0, -1.0), b.at(60.0, 120.0, -1.5));
  return b.finish();
}

}  // namespace rc::hard
