// Shared by the hard-case scenes: geometry placed by raster position and depth through the
// scene's own camera, so a case can put a vertex on a pixel centre, or an edge through a row
// of them, at any depth. Positions are rounded once to float, like every mesh's; where a case
// needs an exact float (a repeated vertex, a collinear triple) it adds world points directly.
#pragma once

#include <cmath>
#include <string>

#include "scenes/registry.h"

namespace rc::hard {

class Builder {
 public:
  Builder(const std::string& name, const CameraSpec& spec)
      : name_(name), camera_(spec, "scene " + name) {}

  const Camera& camera() const { return camera_; }
  Mesh& mesh() { return mesh_; }

  // The world point seen at raster position (x, y) at depth w.
  unsigned at(double x, double y, double w) { return world(camera_.worldAtRaster({x, y}, w)); }
  // The centre of pixel (px, py) at depth w.
  unsigned atPixel(int px, int py, double w) { return at(px + 0.5, py + 0.5, w); }
  unsigned world(const glm::dvec3& p) {
    mesh_.positions.emplace_back(glm::vec3(p));
    return unsigned(mesh_.positions.size() - 1);
  }
  // A triangle; `flip` reverses its winding (b0 stays with the first vertex).
  void triangle(unsigned a, unsigned b, unsigned c, bool flip = false) {
    mesh_.triangles.push_back(flip ? glm::uvec3(a, c, b) : glm::uvec3(a, b, c));
  }

  Scene finish() { return Scene{name_, "", std::move(mesh_), camera_}; }

 private:
  std::string name_;
  Camera camera_;
  Mesh mesh_;
};

// Depth of a plane seen in raster space: 1/w is affine over the image for any plane, so a
// plane is given by its depth w0 at raster point (cx, cy) and the raster gradient of 1/w.
struct DepthPlane {
  double cx, cy, w0, gx, gy;
  double at(double x, double y) const { return 1.0 / (1.0 / w0 + gx * (x - cx) + gy * (y - cy)); }
};

// A camera at the origin looking down -z with +y up: view space is world space.
inline CameraSpec frontCamera(int width, int height, double fovY = 60.0, double zNear = 0.1) {
  return lookAt({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, fovY, zNear, width, height);
}

}  // namespace rc::hard
