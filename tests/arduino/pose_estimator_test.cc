// SPDX-License-Identifier: GPL-3.0-or-later
// The firmware library's PoseEstimator against the closed forms of differential drive
// kinematics (dissertation eq. 3.26-3.31): constant wheel speeds trace a circle of radius R
// (eq. 3.27) turning by (s_r - s_l) / 2d (eq. 3.26); equal and opposite speeds spin in place; the
// result does not depend on how often the estimate is updated.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "PoseEstimator.h"

namespace unimouse {
namespace {

const RobotConstructionSpecification kSpec;
const double kMetresPerCount = 2 * std::numbers::pi * 0.016 / 358.32;

struct Expected {
  double x, y, theta;
};

// from the origin facing +x, the left and right wheels travelling left_m and right_m
Expected ClosedForm(double left_m, double right_m) {
  const double turn = (right_m - left_m) / 0.096;  // eq. 3.26 integrated
  if (turn == 0) return {left_m, 0, 0};
  const double radius = 0.048 * (right_m + left_m) / (right_m - left_m);  // eq. 3.27
  return {radius * std::sin(turn), radius * (1 - std::cos(turn)),
          std::remainder(turn, 2 * std::numbers::pi)};
}

Pose Drive(int left_per_update, int right_per_update, int updates) {
  PoseEstimator estimator(kSpec);
  for (int i = 1; i <= updates; ++i)
    estimator.updatePose(left_per_update * i, right_per_update * i);
  return estimator.getPose();
}

TEST(FirmwarePoseEstimatorTest, ConstantWheelSpeedsTraceTheClosedFormArc) {
  for (const auto& [left, right] :
       {std::pair{2, 4}, std::pair{5, 3}, std::pair{-2, 6}, std::pair{4, 4}}) {
    const int updates = 700;
    const Expected e =
        ClosedForm(left * updates * kMetresPerCount, right * updates * kMetresPerCount);
    const Pose p = Drive(left, right, updates);
    EXPECT_NEAR(p.x, e.x, 2e-5) << left << "/" << right;
    EXPECT_NEAR(p.y, e.y, 2e-5) << left << "/" << right;
    EXPECT_NEAR(p.theta, e.theta, 2e-5) << left << "/" << right;
  }
}

TEST(FirmwarePoseEstimatorTest, OppositeWheelSpeedsSpinInPlace) {
  // a quarter turn takes 0.096 * pi / 4 of travel per wheel
  const double quarter_counts = 0.096 * std::numbers::pi / 4 / kMetresPerCount;
  const Pose p = Drive(-3, 3, static_cast<int>(std::lround(quarter_counts / 3)));
  EXPECT_EQ(p.x, 0);
  EXPECT_EQ(p.y, 0);
  EXPECT_NEAR(p.theta, 3 * std::lround(quarter_counts / 3) * kMetresPerCount * 2 / 0.096, 1e-5);
  EXPECT_NEAR(p.theta, std::numbers::pi / 2, 0.01);  // to within a count's worth of turn
}

TEST(FirmwarePoseEstimatorTest, TheEstimateDoesNotDependOnTheUpdateRate) {
  PoseEstimator often(kSpec), once(kSpec);
  for (int i = 1; i <= 1000; ++i) often.updatePose(3 * i, 5 * i);
  once.updatePose(3000, 5000);
  EXPECT_NEAR(often.getPose().x, once.getPose().x, 2e-5);
  EXPECT_NEAR(often.getPose().y, once.getPose().y, 2e-5);
  EXPECT_NEAR(often.getPose().theta, once.getPose().theta, 2e-5);
}

TEST(FirmwarePoseEstimatorTest, SetPoseMovesTheEstimateAndTheCountReference) {
  PoseEstimator estimator(kSpec);
  estimator.setPose({0.09f, 0.09f, static_cast<float>(std::numbers::pi / 2)}, 1000, 1000);
  estimator.updatePose(1100, 1100);  // 100 counts straight ahead: north
  EXPECT_NEAR(estimator.getPose().x, 0.09, 1e-6);
  EXPECT_NEAR(estimator.getPose().y, 0.09 + 100 * kMetresPerCount, 1e-6);
  // totals far beyond 16 bits keep working, also across the 32-bit wrap-around
  estimator.setPose({}, 2'147'483'600, 2'147'483'600);
  estimator.updatePose(static_cast<int32_t>(2'147'483'700u), static_cast<int32_t>(2'147'483'700u));
  EXPECT_NEAR(estimator.getPose().x, 100 * kMetresPerCount, 1e-6);
  EXPECT_EQ(estimator.getPose().theta, 0);
}

}  // namespace
}  // namespace unimouse
