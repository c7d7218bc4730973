// frameMesh.
#include "scenes/loaders/framing.h"

#include <algorithm>
#include <cmath>

namespace rc {

CameraSpec frameMesh(const Mesh& mesh, double fovYDegrees, int width, int height) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  if (mesh.positions.empty()) lo = hi = glm::dvec3(0.0);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  double radius = 0.5 * glm::length(hi - lo);
  if (!(radius > 0.0)) radius = 1.0;
  const double halfY = fovYDegrees * M_PI / 360.0;
  const double halfX = std::atan(std::tan(halfY) * double(width) / double(height));
  const double distance = 1.05 * radius / std::sin(std::min(halfX, halfY));
  CameraSpec spec;
  spec.target = centre;
  spec.eye = centre + distance * glm::normalize(glm::dvec3(0.5, 0.4, 1.0));
  spec.fovYDegrees = fovYDegrees;
  spec.zNear = 0.5 * (distance - radius);
  spec.width = width;
  spec.height = height;
  return spec;
}

}  // namespace rc
