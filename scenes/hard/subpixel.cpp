// "subpixel": triangles smaller than a pixel, in cells of 8x8 pixels: some covering no pixel
// centre, some exactly one, some two neighbouring centres, some with a vertex or an edge
// exactly on a centre, in both windings.
//
// Stresses: bounding boxes, snapping and the fill rule at the scale where one pixel decides
// everything.
// Must hold: coverage equal to the exact oracle's, pixel for pixel.
#include "scenes/hard/builder.h"
#include "scenes/hard/hard_scenes.h"

namespace rc::hard {

Scene makeSubpixel(SceneArgs&) {
  Builder b("subpixel", frontCamera(64, 64));
  // Triangle corners relative to a cell's pixel (cx, cy), in pixels.
  const double shapes[][6] = {
      {0.1, 0.1, 0.4, 0.1, 0.1, 0.4},    // corner of the pixel, no centre
      {0.6, 0.6, 0.9, 0.6, 0.6, 0.9},    // opposite corner, no centre
      {0.3, 0.3, 0.8, 0.4, 0.4, 0.8},    // around the centre (0.5, 0.5)
      {0.2, 0.3, 1.8, 0.4, 1.0, 0.8},    // two centres: (0.5, 0.5) and (1.5, 0.5)
      {0.5, 0.5, 0.9, 0.5, 0.5, 0.9},    // vertex on the centre
      {0.1, 0.5, 0.9, 0.5, 0.5, 0.9},    // edge through the centre (horizontal, y = 0.5)
      {0.1, 0.5, 0.5, 0.1, 0.9, 0.5},    // same edge, from the other side
      {0.5, 0.1, 0.9, 0.5, 0.5, 0.9},    // vertical edge x = 0.5, right side
      {0.5, 0.1, 0.5, 0.9, 0.1, 0.5},    // vertical edge x = 0.5, left side
      {0.45, 0.45, 0.55, 0.45, 0.5, 0.55},  // a tenth of a pixel around the centre
      {0.5, 0.45, 0.55, 0.5, 0.5, 0.55},    // tiny, vertex on the centre
      {0.2, 1.4, 0.8, 1.6, 1.4, 0.2},       // long thin, across (0.5, 0.5)? decided by the oracle
  };
  int cell = 0;
  for (const auto& s : shapes) {
    for (int flip = 0; flip < 2; ++flip, ++cell) {
      const int cx = 2 + 8 * (cell % 8), cy = 2 + 8 * (cell / 8);
      const double depth = 3.0 + 0.1 * cell;
      b.triangle(b.at(cx + s[0], cy + s[1], depth), b.at(cx + s[2], cy + s[3], depth),
                 b.at(cx + s[4], cy + s[5], depth), flip == 1);
    }
  }
  return b.finish();
}

}  // namespace rc::hard
