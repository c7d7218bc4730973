// The exact sign of a 2D orientation in doubles, for coverage without snapping
// (--subpixel-bits none): a floating-point filter, and exact rational arithmetic for the
// determinants the filter cannot decide.
#pragma once

#include <algorithm>
#include <cmath>

namespace rc {

// The filter's bound (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
// Geometric Predicates", 1997, orient2d's ccwerrboundA): with left = (ax - cx)(by - cy) and
// right = (ay - cy)(bx - cx) computed in double, the computed left - right has the sign of the
// exact determinant whenever its magnitude exceeds (3 + 16 eps) eps (|left| + |right|),
// eps = 2^-53.
constexpr double kOrientationBound = (3.0 + 16.0 * 0x1p-53) * 0x1p-53;
// That bound holds while the products keep their relative precision; below this floor they may
// have lost bits to underflow, and the exact path decides.
constexpr double kOrientationFloor = 0x1p-960;

// The sign (-1, 0 or 1) of (ax - cx)(by - cy) - (ay - cy)(bx - cx), computed exactly in
// rational arithmetic (GMP): twice the signed area of the triangle a, b, c, positive when c
// lies to the left of a -> b in a y-up frame (to the right on a y-down screen).
int exactOrientation(double ax, double ay, double bx, double by, double cx, double cy);

// The same sign: the filter first, the exact path when it cannot decide.
inline int orientation(double ax, double ay, double bx, double by, double cx, double cy) {
  const double left = (ax - cx) * (by - cy), right = (ay - cy) * (bx - cx), det = left - right;
  const double bound = std::max(kOrientationBound * (std::fabs(left) + std::fabs(right)), kOrientationFloor);
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return exactOrientation(ax, ay, bx, by, cx, cy);
}

}  // namespace rc
