// Recovering barycentrics from screen-space weights: the seed notes' derivation
// (shared/seeds 000, 001). With screen-space weights l_i of a point and clip w_i of the
// vertices, the true (3-D) barycentrics are b_i = (l_i / w_i) / sum_j (l_j / w_j), and the
// depth (= w) there is sum_j l_j / sum_j (l_j / w_j). Affine mode uses l_i as they are.
//
// Value is a scalar or a vector of lanes (the tile kernels evaluate eight pixels at once through
// these very functions); Scalar is the per-vertex type: Value's element type, or Value itself
// when each lane has its own triangle (the gathered resolve). Always inlined: the kernels' vector
// values never cross a call between code compiled for different instruction sets.
#pragma once

namespace rc {

template <typename Value>
struct Recovered {
  Value b[3];
  Value depth;
};

// l need not sum to exactly 1 (each l_i is its own edge function over the area); dividing by
// the sums makes the result independent of that rounding.
template <typename Value, typename Scalar>
inline __attribute__((always_inline)) Recovered<Value> perspectiveCorrect(const Value l[3], const Scalar invW[3]) {
  const Value q0 = l[0] * invW[0], q1 = l[1] * invW[1], q2 = l[2] * invW[2];
  const Value inv = 1 / (q0 + q1 + q2);
  return {{q0 * inv, q1 * inv, q2 * inv}, (l[0] + l[1] + l[2]) * inv};
}

template <typename Value, typename Scalar>
inline __attribute__((always_inline)) Recovered<Value> affineWeights(const Value l[3], const Scalar w[3]) {
  const Value inv = 1 / (l[0] + l[1] + l[2]);
  const Value b0 = l[0] * inv, b1 = l[1] * inv, b2 = l[2] * inv;
  return {{b0, b1, b2}, b0 * w[0] + b1 * w[1] + b2 * w[2]};
}

}  // namespace rc
