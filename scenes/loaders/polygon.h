// Triangulating one polygon face (an OBJ "f" line with four or more corners).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

namespace rc {

// The n - 2 triangles of a polygon of n >= 3 corners, as corner numbers (0..n-1), each wound
// as the polygon is. A convex polygon (in the plane of its Newell normal) is fanned from corner
// 0. A concave one is cut into ears, so that no triangle covers area outside it: every
// triangle's corners are three consecutive ones of what remains, and the triangle holds no
// reflex corner. Ear clipping may test at most n * n points; a polygon that needs more, or has
// no ear left (it crosses itself, or it is degenerate), fans what remains from where it stopped.
std::vector<std::array<unsigned, 3>> triangulatePolygon(const std::vector<glm::dvec3>& corners);

}  // namespace rc
