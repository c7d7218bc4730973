// core/split_vectors.h: comparisons, selects and splats split into register-wide halves give,
// lane for lane, the bits the plain operators give, for every width they are split down to.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "core/split_vectors.h"

#pragma GCC diagnostic ignored "-Wpsabi"  // vector values pass between inline functions

namespace rc {
namespace {

typedef float f32x8 __attribute__((vector_size(32)));
typedef std::uint32_t u32x8 __attribute__((vector_size(32)));
typedef std::int32_t i32x8 __attribute__((vector_size(32)));
typedef double f64x8 __attribute__((vector_size(64)));
typedef std::int64_t i64x8 __attribute__((vector_size(64)));

template <typename V>
bool sameBits(const V& a, const V& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Values that make comparisons interesting: signed zeros, NaN, infinities, ties, and for the
// integers both sides of the sign bit (an unsigned comparison must not read it as a sign).
template <typename E>
E interesting(std::mt19937& random) {
  if constexpr (std::is_floating_point_v<E>) {
    const E pool[] = {E(0), -E(0), E(1), E(-1), E(0.5), std::numeric_limits<E>::infinity(),
                      -std::numeric_limits<E>::infinity(), std::numeric_limits<E>::quiet_NaN(),
                      std::numeric_limits<E>::min(), std::numeric_limits<E>::max()};
    if (random() % 2) return pool[random() % std::size(pool)];
    return E(std::uniform_real_distribution<double>(-4, 4)(random));
  } else {
    const E pool[] = {E(0), E(1), E(-1), std::numeric_limits<E>::min(), std::numeric_limits<E>::max(),
                      E(std::numeric_limits<E>::max() / 2 + 1)};
    if (random() % 2) return pool[random() % std::size(pool)];
    return E(random() % 7) - E(3);  // small values, so that many lanes tie
  }
}

template <typename V>
V randomVector(std::mt19937& random) {
  V v;
  using Element = std::remove_cvref_t<decltype(v[0])>;
  for (std::size_t k = 0; k < sizeof(V) / sizeof(v[0]); ++k) v[k] = interesting<Element>(random);
  return v;
}

// Every comparison at width W against the plain operator, and a select by its result.
template <std::size_t W, typename V>
void checkWidth(const V& a, const V& b) {
  EXPECT_TRUE(sameBits(split::less<W>(a, b), a < b));
  EXPECT_TRUE(sameBits(split::greater<W>(a, b), a > b));
  EXPECT_TRUE(sameBits(split::lessEqual<W>(a, b), a <= b));
  EXPECT_TRUE(sameBits(split::greaterEqual<W>(a, b), a >= b));
  EXPECT_TRUE(sameBits(split::equal<W>(a, b), a == b));
  EXPECT_TRUE(sameBits(split::notEqual<W>(a, b), a != b));
  EXPECT_TRUE(sameBits(split::less<W>(a, b[3]), a < b[3])) << "against a scalar";
  EXPECT_TRUE(sameBits(split::notEqual<W>(a, b[5]), a != b[5])) << "against a scalar";
  const auto mask = a < b;
  EXPECT_TRUE(sameBits(split::select<W>(mask, a, b), mask ? a : b));
  EXPECT_TRUE(sameBits(split::splat<W, V>(b[2]), V{} + b[2]));
}

template <typename V>
void checkAllWidths() {
  std::mt19937 random(7);
  for (int round = 0; round < 2000; ++round) {
    const V a = randomVector<V>(random), b = randomVector<V>(random);
    checkWidth<16>(a, b);  // halves of halves (the SSE2 build)
    checkWidth<32>(a, b);
    checkWidth<64>(a, b);  // whole
  }
}

TEST(SplitVectors, FloatLanesGiveThePlainOperatorsBits) { checkAllWidths<f32x8>(); }
TEST(SplitVectors, UnsignedLanesGiveThePlainOperatorsBits) { checkAllWidths<u32x8>(); }
TEST(SplitVectors, Int32LanesGiveThePlainOperatorsBits) { checkAllWidths<i32x8>(); }
TEST(SplitVectors, DoubleLanesGiveThePlainOperatorsBits) { checkAllWidths<f64x8>(); }
TEST(SplitVectors, Int64LanesGiveThePlainOperatorsBits) { checkAllWidths<i64x8>(); }

// The halves go back in their places: lane k of a split comparison is lane k's own answer.
TEST(SplitVectors, LanesStayInPlace) {
  const f32x8 a{0, 1, 2, 3, 4, 5, 6, 7};
  const i32x8 below = split::less<16>(a, 4.5f);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(below[k], k < 5 ? -1 : 0) << "lane " << k;
  const f32x8 picked = split::select<16>(below, a, f32x8{} + 100.0f);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(picked[k], k < 5 ? float(k) : 100.0f) << "lane " << k;
  // A splat of -0 is +0 in every lane, as V{} + s is.
  const f32x8 zero = split::splat<16, f32x8>(-0.0f);
  for (int k = 0; k < 8; ++k) EXPECT_FALSE(std::signbit(zero[k])) << "lane " << k;
}

}  // namespace
}  // namespace rc
