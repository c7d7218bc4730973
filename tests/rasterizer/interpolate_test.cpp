// The perspective-correct formula against the seed notes' analytic results.
#include <gtest/gtest.h>

#include <random>

#include "rasterizer/interpolate.h"

namespace rc {
namespace {

// Seed 000: a point with true barycentrics alpha appears on screen with weights
// alpha'_i = alpha_i w_i / sum_j alpha_j w_j; its depth is w_p = sum_j alpha_j w_j.
TEST(PerspectiveCorrection, RecoversTheTrueBarycentricsOfSeedNote000) {
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> unit(0.0, 1.0), logW(-3.0, 3.0);
  for (int trial = 0; trial < 1000; ++trial) {
    double alpha[3] = {unit(rng), unit(rng), unit(rng)};
    const double sum = alpha[0] + alpha[1] + alpha[2];
    double w[3], invW[3], screen[3], wp = 0.0;
    for (int i = 0; i < 3; ++i) {
      alpha[i] /= sum;
      w[i] = std::pow(10.0, logW(rng));
      invW[i] = 1.0 / w[i];
      wp += alpha[i] * w[i];
    }
    for (int i = 0; i < 3; ++i) screen[i] = alpha[i] * w[i] / wp;
    const Recovered<double> r = perspectiveCorrect(screen, invW);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.b[i], alpha[i], 1e-13) << "trial " << trial;
    EXPECT_NEAR(r.depth, wp, 1e-12 * wp) << "trial " << trial;
  }
}

// Seed 002: along an edge, c = z (c0/z0 (1-q) + c1/z1 q) with 1/z = (1-q)/z0 + q/z1.
TEST(PerspectiveCorrection, MatchesTheOneDimensionalFormulaOfSeedNote002) {
  const double z0 = 0.5, z1 = 40.0, c0 = -2.0, c1 = 7.0;
  for (double q : {0.0, 0.1, 0.25, 0.5, 0.9, 1.0}) {
    const double z = 1.0 / ((1.0 - q) / z0 + q / z1);
    const double expected = z * (c0 / z0 * (1.0 - q) + c1 / z1 * q);
    const double screen[3] = {1.0 - q, q, 0.0};
    const double invW[3] = {1.0 / z0, 1.0 / z1, 1.0};
    const Recovered<double> r = perspectiveCorrect(screen, invW);
    EXPECT_NEAR(r.b[0] * c0 + r.b[1] * c1, expected, 1e-13) << "q=" << q;
    EXPECT_NEAR(r.depth, z, 1e-13 * z) << "q=" << q;
  }
}

TEST(AffineWeights, AreTheScreenWeightsAndMissTheTruthWhenDepthVaries) {
  const double screen[3] = {0.5, 0.5, 0.0};
  const double w[3] = {1.0, 10.0, 1.0}, invW[3] = {1.0, 0.1, 1.0};
  const Recovered<double> affine = affineWeights(screen, w);
  const Recovered<double> perspective = perspectiveCorrect(screen, invW);
  EXPECT_DOUBLE_EQ(affine.b[0], 0.5);
  EXPECT_NEAR(perspective.b[0], 10.0 / 11.0, 1e-15);  // the near vertex dominates
  EXPECT_GT(std::abs(affine.b[0] - perspective.b[0]), 0.4);
}

}  // namespace
}  // namespace rc
