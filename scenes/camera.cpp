// Camera: matrices and rays from one orthonormal basis, all in double.
#include "scenes/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/number_text.h"
#include "scenes/mesh.h"

namespace rc {
namespace {

bool finite3(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double largestMagnitude(const glm::dvec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

// The length of a finite v, without the overflow or underflow of its squares: (0, 1e-300, 0)
// has length 1e-300, not 0, and (1e200, 0, 0) 1e200, not infinity.
double length(const glm::dvec3& v) {
  const double scale = largestMagnitude(v);
  return scale == 0.0 ? 0.0 : scale * glm::length(v / scale);
}

std::string format3(const glm::dvec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g,%.17g,%.17g)", v.x, v.y, v.z);
  return buf;
}

std::string number3(const glm::dvec3& v) { return "(" + exactNumber(v.x) + "," + exactNumber(v.y) + "," + exactNumber(v.z) + ")"; }

}  // namespace

Camera::Camera(const CameraSpec& spec, const std::string& where) : spec_(spec) {
  const std::string at = where + ": camera";
  if (!finite3(spec.eye) || !finite3(spec.target) || !finite3(spec.up)) {
    throw badInput(at, "eye, target and up must be finite");
  }
  if (largestMagnitude(spec.eye) > kMaxCoordinate || largestMagnitude(spec.target) > kMaxCoordinate) {
    throw badInput(at, "eye and target must lie within 1e18 of the origin on each axis, as mesh positions do, got eye=" +
                           number3(spec.eye) + " target=" + number3(spec.target));
  }
  if (!(spec.fovYDegrees >= kMinFovYDegrees && spec.fovYDegrees <= kMaxFovYDegrees)) {
    throw badInput(at, "vertical field of view must be " + exactNumber(kMinFovYDegrees) + " to " + exactNumber(kMaxFovYDegrees) +
                           " degrees, got " + exactNumber(spec.fovYDegrees));
  }
  if (!(spec.zNear > 0.0) || !std::isfinite(spec.zNear)) {
    throw badInput(at, "near must be finite and > 0, got " + exactNumber(spec.zNear));
  }
  if (!(spec.zFar > spec.zNear)) {
    throw badInput(at, "far must be greater than near (or infinite), got near=" + exactNumber(spec.zNear) + " far=" +
                           exactNumber(spec.zFar));
  }
  if (spec.width < 1 || spec.height < 1 || spec.width > 16384 || spec.height > 16384) {
    throw badInput(at, "image size must be 1..16384 per side, got " + std::to_string(spec.width) +
                           "x" + std::to_string(spec.height));
  }
  const glm::dvec3 view = spec.target - spec.eye;
  const double distance = length(view);
  if (!(distance > 0.0)) {
    throw badInput(at, "eye and target are the same point");
  }
  forward_ = view / distance;
  const double upLength = length(spec.up);
  if (!(upLength > 0.0)) throw badInput(at, "up vector is zero");
  const glm::dvec3 side = glm::cross(forward_, spec.up / upLength);
  // sin(angle between up and the view direction) below 1e-9: no meaningful roll.
  if (!(glm::length(side) > 1e-9)) throw badInput(at, "up vector is parallel to the view direction");
  right_ = glm::normalize(side);
  up_ = glm::cross(right_, forward_);
  tanHalfFovY_ = std::tan(spec.fovYDegrees * (M_PI / 360.0));
  aspect_ = double(spec.width) / double(spec.height);
}

glm::dmat4 Camera::viewFromWorld() const {
  // Rows are the basis vectors (right, up, -forward); GLM matrices are column-major.
  glm::dmat4 m(1.0);
  for (int i = 0; i < 3; ++i) {
    m[i][0] = right_[i];
    m[i][1] = up_[i];
    m[i][2] = -forward_[i];
  }
  m[3][0] = -glm::dot(right_, spec_.eye);
  m[3][1] = -glm::dot(up_, spec_.eye);
  m[3][2] = glm::dot(forward_, spec_.eye);
  return m;
}

glm::dmat4 Camera::clipFromView() const {
  glm::dmat4 m(0.0);
  m[0][0] = 1.0 / (aspect_ * tanHalfFovY_);
  m[1][1] = 1.0 / tanHalfFovY_;
  m[2][3] = -1.0;  // w_clip = -z_view = depth
  if (std::isinf(spec_.zFar)) {
    m[2][2] = -1.0;
    m[3][2] = -2.0 * spec_.zNear;
  } else {
    const double n = spec_.zNear, f = spec_.zFar;
    m[2][2] = -(f + n) / (f - n);
    m[3][2] = -2.0 * f * n / (f - n);
  }
  return m;
}

CameraRay Camera::rayThroughPixel(int x, int y) const {
  CameraRay ray;
  ray.origin = spec_.eye;
  ray.direction = directionThroughRaster(pixelCenter(x, y));
  ray.tNear = spec_.zNear;
  ray.tFar = spec_.zFar;
  return ray;
}

std::string Camera::describe() const {
  char buf[160];
  std::snprintf(buf, sizeof buf, " fovy=%.17g near=%.17g far=%.17g size=%dx%d", spec_.fovYDegrees,
                spec_.zNear, spec_.zFar, spec_.width, spec_.height);
  return "eye=" + format3(spec_.eye) + " target=" + format3(spec_.target) +
         " up=" + format3(spec_.up) + buf;
}

}  // namespace rc
