// What the reference hands Embree: camera-relative float triangles, each no longer than
// kMaxLengthOverDistance times its distance from the eye. Embree's float hit test errs by
// about u |v| / d in angle for vertex magnitudes |v| seen at distance d; a triangle 10^9 pixels
// wide passing 10 units from the eye, or one reaching from 0.01 to 10^4 units, would make it
// choose wrongly by many pixels (measured on the "huge" and "perspective" hard cases). Such
// triangles are split (in double, by longest-edge bisection) until the ratio holds, so that
// Embree's angular error stays below (1 + kMaxLengthOverDistance) u times a small constant;
// each piece keeps its source triangle's index. Pieces entirely outside a frustum widened to
// twice the image's half-angles, or behind the near plane, are dropped.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/camera.h"
#include "scenes/mesh.h"

namespace rc {

inline constexpr double kMaxLengthOverDistance = 16.0;

struct EmbreeTriangles {
  // 3 floats per vertex, camera-relative: the mesh's vertices, then those splitting made.
  std::vector<float> vertices;
  // 3 per triangle; empty when no triangle was split: the mesh's own triangles are Embree's.
  std::vector<unsigned> indices;
  std::vector<std::uint32_t> source;  // per Embree triangle: the mesh triangle; empty = identity
};

// On up to `threads` threads; the result does not depend on their number.
EmbreeTriangles embreeTriangles(const Mesh& mesh, const Camera& camera, int threads);

// Distance from the origin to triangle (a, b, c), in double.
double distanceToTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

}  // namespace rc
