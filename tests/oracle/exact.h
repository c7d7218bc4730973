// The exact oracle (issue 3): exact rational arithmetic (GMP mpq_class) from the same float
// vertices and double camera both renderers use. It decides
//   (a) which pixel centres a triangle covers under the rasterizer's documented rules
//       (clipping against near, far and the guard band; snapping to the subpixel grid, ties to
//       even; top-left fill rule), written here from those definitions, not from the code;
//   (b) the exact barycentrics of a pixel centre: through the projection (what the rasterizer
//       approximates) and along the camera's double ray (what the reference approximates).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <gmpxx.h>

#include "scenes/scene.h"

namespace rc::oracle {

using Q = mpq_class;

struct CoverageResult {
  std::vector<std::uint32_t> pixels;  // covered pixel indices (y * width + x), sorted
  int ambiguousSnaps = 0;  // snapped coordinates within 2^-20 grid steps of a rounding tie,
                           // where double rounding may legitimately go either way
  int doubleCovered = 0;   // pixels covered by two sub-triangles of this one triangle
};

// (c) Coverage without snapping (--subpixel-bits none), for a triangle with these double raster
// positions: the pixels (y * width + x, sorted) whose centres it covers under the top-left
// rule, decided in rationals. Empty for a zero-area triangle, and with cullBackFaces for one
// clockwise on screen (a back face).
std::vector<std::uint32_t> unsnappedCoverage(const std::array<glm::dvec2, 3>& raster, int width, int height,
                                             bool cullBackFaces);

// The raster position the rasterizer's transform gives a vertex in front of the camera, in
// double: the camera's clip-from-world matrix (glm's product), then its raster mapping of x / w
// and y / w.
glm::dvec2 rasterPosition(const Camera& camera, const glm::vec3& p);

class Oracle {
 public:
  Oracle(const Scene& scene, int subpixelBits);

  // (a) The pixels triangle t covers.
  CoverageResult coverage(std::size_t t) const;
  // The snapped raster position of vertex v (fixed point, `bits` fraction bits), for vertices
  // the camera sees without clipping; counts a tie-adjacent rounding in `ambiguous`.
  std::array<std::int64_t, 2> snapped(std::size_t v, int& ambiguous) const;
  // The exact raster position of vertex v (in front of the camera), before any snapping.
  std::array<Q, 2> raster(std::size_t v) const;

  // (b) Exact barycentrics of pixel (x, y)'s centre for triangle t, rounded to double:
  // through the projection (homogeneous 2D barycentrics of the clip-space vertices), and along
  // the camera's ray (signed volumes of the double ray against the float vertices). `defined`
  // is false where the point is at infinity or the ray parallel to the plane.
  std::array<double, 3> projected(std::size_t t, int x, int y, bool& defined) const;
  std::array<double, 3> alongRay(std::size_t t, int x, int y, bool& defined) const;

 private:
  struct Clip { Q x, y, w; };
  const Scene& scene_;
  int bits_;
  std::vector<Clip> clip_;  // per vertex, exact
  Q guard_, zNear_, zFar_;
  bool finiteFar_;
};

}  // namespace rc::oracle
