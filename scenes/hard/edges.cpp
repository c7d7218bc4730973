// "edges": pairs of triangles sharing an edge that runs exactly through pixel centres:
// horizontal, vertical, both diagonals and the slopes 1:2, 2:1, 1:3, 3:1, 2:3, 3:2, 3:5, 7:2.
//
// Stresses: the tie-breaking half of the fill rule. Each shared edge passes through several
// pixel centres, which must go to exactly one of the two triangles; the outer edges also run
// through pixel centres. Half the pairs are wound clockwise on screen, half anticlockwise.
// Must hold: exactly one owner for every pixel centre inside each pair's quad, and the owner
// does not change when a triangle's vertex order is rotated.
#include <cmath>

#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeEdges(SceneArgs&) {
  Builder b("edges", frontCamera(256, 192));
  const int slopes[12][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}, {2, 1}, {1, 2},
                             {3, 1}, {1, 3}, {3, 2}, {2, 3}, {5, 3}, {7, -2}};
  const DepthPlane plane{128.0, 96.0, 3.0, -3e-4, 5e-4};
  const auto vertex = [&](int px, int py) { return b.atPixel(px, py, plane.at(px + 0.5, py + 0.5)); };
  for (int c = 0; c < 12; ++c) {
    const int cx = 32 + 64 * (c % 4), cy = 32 + 64 * (c / 4);
    const int dx = slopes[c][0], dy = slopes[c][1];
    const int steps = 24 / std::max(std::abs(dx), std::abs(dy));  // half length, in slope steps
    // Shared edge A-B through pixel centres; C and D on either side, also on pixel centres.
    const unsigned A = vertex(cx - steps * dx, cy - steps * dy);
    const unsigned B = vertex(cx + steps * dx, cy + steps * dy);
    const double length = std::hypot(dx, dy);
    const int nx = int(std::lround(-dy / length * 20.0)), ny = int(std::lround(dx / length * 20.0));
    const unsigned C = vertex(cx + nx + 3, cy + ny - 2);
    const unsigned D = vertex(cx - nx - 2, cy - ny + 1);
    const bool flip = c % 2 == 1;
    b.triangle(A, B, C, flip);
    b.triangle(B, A, D, flip);
  }
  return b.finish();
}

}  // namespace rc::hard
