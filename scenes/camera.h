// The one camera contract both renderers share (docs/camera.md). Pixel (x, y) has row 0 at
// the top and is sampled at its centre (x + 0.5, y + 0.5). View space is right-handed and
// looks down -Z. Depth is the view-space distance along the camera's forward axis, which is
// also clip-space w. Nothing outside this class computes a projection or a camera ray.
#pragma once

#include <glm/glm.hpp>
#include <limits>
#include <string>

#include "core/lanes.h"

namespace rc {

// The vertical fields of view a camera may have, in degrees, whichever way it is given (--fov, a
// scene file, a glTF camera). Much narrower, the two paths part: at 1e-17 degrees the rays
// through neighbouring pixels are the same doubles, and at 1e-25 the gate failed the
// rasterizer for three quarters of a frame's pixels, each covered by one path alone.
inline constexpr double kMinFovYDegrees = 0.001;
inline constexpr double kMaxFovYDegrees = 179.999;

struct CameraSpec {
  glm::dvec3 eye{0.0, 0.0, 5.0};     // world position of the centre of projection
  glm::dvec3 target{0.0, 0.0, 0.0};  // a world point the camera looks at
  glm::dvec3 up{0.0, 1.0, 0.0};      // world direction that appears upwards on screen
  double fovYDegrees = 45.0;         // vertical field of view, kMinFovYDegrees..kMaxFovYDegrees
  double zNear = 0.1;                // nearest depth drawn, > 0
  double zFar = std::numeric_limits<double>::infinity();  // farthest depth drawn, or +inf
  int width = 640;                   // image size in pixels
  int height = 480;
};

// A spec looking from `eye` at `target` with +y up and an infinite far plane.
inline CameraSpec lookAt(glm::dvec3 eye, glm::dvec3 target, double fovYDegrees, double zNear,
                         int width = 640, int height = 480) {
  CameraSpec spec;
  spec.eye = eye;
  spec.target = target;
  spec.fovYDegrees = fovYDegrees;
  spec.zNear = zNear;
  spec.width = width;
  spec.height = height;
  return spec;
}

struct CameraRay {
  glm::dvec3 origin;     // the eye
  glm::dvec3 direction;  // not normalised: direction . forward == 1, so t is depth
  double tNear;          // depth == zNear
  double tFar;           // depth == zFar (may be +inf)
};

class Camera {
 public:
  // Validates the spec; throws badInput("<where>: camera", reason) for a degenerate camera.
  explicit Camera(const CameraSpec& spec, const std::string& where = "camera");

  const CameraSpec& spec() const { return spec_; }
  int width() const { return spec_.width; }
  int height() const { return spec_.height; }
  double zNear() const { return spec_.zNear; }
  double zFar() const { return spec_.zFar; }
  const glm::dvec3& forward() const { return forward_; }

  glm::dmat4 viewFromWorld() const;
  // OpenGL-style perspective (infinite when zFar is infinite); its w row yields w = depth.
  glm::dmat4 clipFromView() const;
  glm::dmat4 clipFromWorld() const { return clipFromView() * viewFromWorld(); }

  // Raster position of a pixel's sample: its centre.
  static glm::dvec2 pixelCenter(int x, int y) { return {x + 0.5, y + 0.5}; }
  // Raster position (pixels, y down) of normalised device coordinates (y up).
  template <typename Real>
  Real rasterXFromNdc(Real ndcX) const {
    return (ndcX + Real(1)) * Real(0.5) * Real(spec_.width);
  }
  template <typename Real>
  Real rasterYFromNdc(Real ndcY) const {
    return (Real(1) - ndcY) * Real(0.5) * Real(spec_.height);
  }

  // The ray through the centre of pixel (x, y), in double.
  CameraRay rayThroughPixel(int x, int y) const;
  // Direction (direction . forward == 1) of the ray through raster position r, in double.
  glm::dvec3 directionThroughRaster(const glm::dvec2& r) const {
    return lanes::dvec3Of(directionThroughRaster(r.x, r.y));
  }
  // The same for a double or for four lanes of raster positions (core/lanes.h), with the same
  // bits in every lane, in two halves for tracing many pixels: the offset along right_ of a
  // column and along up_ of a row (each computed once), then their sum with forward_.
  template <typename V>
  RC_LANES_INLINE lanes::Vec3<V> directionThroughRaster(const V& rx, const V& ry) const {
    return directionFromOffsets(rightOffset(rx), upOffset(ry));
  }
  template <typename V>
  RC_LANES_INLINE V rightOffset(const V& rx) const {
    const V ndcX = 2.0 * rx / double(spec_.width) - 1.0;  // inverse of rasterXFromNdc
    return ndcX * tanHalfFovY_ * aspect_;
  }
  template <typename V>
  RC_LANES_INLINE V upOffset(const V& ry) const {
    const V ndcY = 1.0 - 2.0 * ry / double(spec_.height);  // inverse of rasterYFromNdc
    return ndcY * tanHalfFovY_;
  }
  template <typename V>
  RC_LANES_INLINE lanes::Vec3<V> directionFromOffsets(const V& s, const V& t) const {
    return {forward_.x + s * right_.x + t * up_.x, forward_.y + s * right_.y + t * up_.y,
            forward_.z + s * right_.z + t * up_.z};
  }
  // The world point seen at raster position r at the given depth (w); depth <= 0 gives points
  // in or behind the eye plane that project (with w <= 0) to the same position.
  glm::dvec3 worldAtRaster(const glm::dvec2& r, double depth) const {
    return spec_.eye + depth * directionThroughRaster(r);
  }
  // tan(fovY / 2) and width / height: the image plane at depth 1 spans 2 tanHalfFovY()
  // vertically, so it holds height / (2 tanHalfFovY()) pixels per unit.
  double tanHalfFovY() const { return tanHalfFovY_; }
  double aspect() const { return aspect_; }
  // The camera's basis in world space.
  const glm::dvec3& right() const { return right_; }
  const glm::dvec3& up() const { return up_; }

  // One line, full precision: "eye=(..) target=(..) up=(..) fovy=.. near=.. far=.. size=WxH".
  std::string describe() const;

 private:
  CameraSpec spec_;
  glm::dvec3 forward_, right_, up_;  // orthonormal camera basis in world space
  double tanHalfFovY_ = 0.0;
  double aspect_ = 1.0;
};

}  // namespace rc
