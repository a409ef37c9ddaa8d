// SPDX-License-Identifier: GPL-3.0-or-later
#include "rng.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unimouse {
namespace {

TEST(RngTest, SameSeedAndNameGiveTheSameStream) {
  RngStream a(42, "tof.front"), b(42, "tof.front");
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.NextBits(), b.NextBits());
}

TEST(RngTest, StreamsDependOnSeedAndName) {
  EXPECT_NE(RngStream(42, "tof.front").NextBits(), RngStream(43, "tof.front").NextBits());
  EXPECT_NE(RngStream(42, "tof.front").NextBits(), RngStream(42, "tof.left").NextBits());
}

TEST(RngTest, UniformSamplesLieInTheUnitInterval) {
  RngStream r(1, "u");
  double sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const double u = r.Uniform();
    ASSERT_GE(u, 0);
    ASSERT_LT(u, 1);
    sum += u;
  }
  EXPECT_NEAR(sum / 100000, 0.5, 0.005);
}

TEST(RngTest, NormalSamplesHaveZeroMeanAndUnitVariance) {
  RngStream r(1, "n");
  const int n = 200000;
  double sum = 0, squares = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.Normal();
    sum += x;
    squares += x * x;
  }
  const double mean = sum / n;
  // standard errors: 1/sqrt(n) = 0.0022 for the mean, sqrt(2/n) = 0.0032 for the variance
  EXPECT_NEAR(mean, 0, 0.01);
  EXPECT_NEAR(squares / n - mean * mean, 1, 0.015);
}

}  // namespace
}  // namespace unimouse
