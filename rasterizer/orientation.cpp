// Exact orientation in GMP rationals: every finite double is a rational, converted exactly.
#include "rasterizer/orientation.h"

#include <gmp.h>

namespace rc {
namespace {

// mpq_t values that clear themselves.
struct Rational {
  mpq_t q;
  Rational() { mpq_init(q); }
  explicit Rational(double d) {
    mpq_init(q);
    mpq_set_d(q, d);
  }
  ~Rational() { mpq_clear(q); }
  Rational(const Rational&) = delete;
  Rational& operator=(const Rational&) = delete;
};

}  // namespace

int exactOrientation(double ax, double ay, double bx, double by, double cx, double cy) {
  const Rational xa(ax), ya(ay), xb(bx), yb(by), xc(cx), yc(cy);
  Rational u, v, left, right;
  mpq_sub(u.q, xa.q, xc.q);
  mpq_sub(v.q, yb.q, yc.q);
  mpq_mul(left.q, u.q, v.q);
  mpq_sub(u.q, ya.q, yc.q);
  mpq_sub(v.q, xb.q, xc.q);
  mpq_mul(right.q, u.q, v.q);
  return mpq_cmp(left.q, right.q) > 0 ? 1 : (mpq_cmp(left.q, right.q) < 0 ? -1 : 0);
}

}  // namespace rc
