// "nearplane": triangles at and through the near plane (near = 0.1): vertices with w just
// above near (1 + 1e-3 ... 1 + 1e-7), one or two vertices behind the near plane, one or two
// behind the eye (w < 0), a vertex exactly in the eye plane (w = 0), triangles crossing w = 0,
// and a triangle entirely behind the eye. Two strips nearly facing the eye are cut lengthwise,
// one by the near plane (rows 1 to 8), one by the far plane (far = 5, rows 31 to 38), so that
// each plane's position is held to a few parts in 10^5 (docs/numerics.md, "Wrong rasterizers").
//
// Stresses: homogeneous clipping in barycentric space (rasterizer/clip.h): new vertices on the
// near and far planes, their barycentrics relative to the source triangle, and division by
// tiny w. Must hold: nothing at depth < near or > far is drawn by either path (the reference's
// rays run from near to far); the triangle behind the eye draws nothing; all outputs finite; barycentrics within
// the bound computed from the clipped sub-triangle's w ratio.
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeNearPlane(SceneArgs&) {
  CameraSpec camera = frontCamera(128, 128, 60.0, 0.1);
  camera.zFar = 5.0;
  Builder b("nearplane", camera);
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
  // Two strips tilted 0.6 degrees from facing the eye, w = plane (1 + 1e-4 s) at s pixels across
  // a cut that runs diagonally along the strip, 126 pixels long: rows 1 to 8 at the near plane,
  // rows 31 to 38 at the far plane. Clipping at 1.0001 near or far moves a cut a pixel, across
  // about 126 pixel centres; the reference's float ordering explains (as clip ties) only about
  // 0.17 pixel of it (docs/numerics.md).
  const auto strip = [&](double top, double plane) {
    const auto at = [&](double x, double y) {
      const double across =
          ((y - top - 3.5) + (x - 64.0) * 7.0 / 126.0) / std::sqrt(1.0 + 49.0 / 15876.0);
      return b.at(x, y, plane * (1.0 + 1e-4 * across));
    };
    b.triangle(at(1.0, top), at(127.0, top), at(127.0, top + 7.0));
    b.triangle(at(1.0, top), at(127.0, top + 7.0), at(1.0, top + 7.0));
  };
  strip(1.0, camera.zNear);
  strip(31.0, camera.zFar);
  return b.finish();
}

}  // namespace rc::hard
