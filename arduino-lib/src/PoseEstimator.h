// SPDX-License-Identifier: MIT
// Dead reckoning from the wheel encoders (dissertation section 3.3): each update turns the
// counts since the last one into wheel travel, then into a turn (eq. 3.26) and a travel of the
// centre (eq. 3.28), and integrates eq. 3.29-3.31 over the interval as the exact circular arc
// those constant speeds describe, so the estimate does not depend on how often it is updated.
#ifndef UNIMOUSE_SIM_POSE_ESTIMATOR_H_
#define UNIMOUSE_SIM_POSE_ESTIMATOR_H_

#include <math.h>
#include <stdint.h>

#include "RobotConstructionSpecification.h"

/// A pose in the maze frame: metres, and radians counter-clockwise from +x in (-pi, pi].
struct Pose {
  float x = 0;
  float y = 0;
  float theta = 0;
};

class PoseEstimator {
 public:
  explicit PoseEstimator(const RobotConstructionSpecification& spec)
      : leftMetresPerCount_(2 * static_cast<float>(M_PI) * spec.leftWheelRadius /
                            spec.leftWheelCPR),
        rightMetresPerCount_(2 * static_cast<float>(M_PI) * spec.rightWheelRadius /
                             spec.rightWheelCPR),
        wheelBase_(spec.wheelBaseDistance) {}

  /// Takes the encoders' running totals (not increments); the first call after construction
  /// or setPose moves from the totals given to setPose (0 by default). Totals are 32-bit and
  /// may wrap around.
  void updatePose(int32_t leftCount, int32_t rightCount) {
    const float left =
        static_cast<float>(countsBetween(lastLeft_, leftCount)) * leftMetresPerCount_;
    const float right =
        static_cast<float>(countsBetween(lastRight_, rightCount)) * rightMetresPerCount_;
    lastLeft_ = leftCount;
    lastRight_ = rightCount;
    const float travel = (right + left) / 2;         // eq. 3.28 times the interval
    const float turn = (right - left) / wheelBase_;  // eq. 3.26 times the interval
    if (fabsf(turn) < 1e-6f) {
      // straight enough: the arc's chord, at the mean heading
      pose_.x += travel * cosf(pose_.theta + turn / 2);
      pose_.y += travel * sinf(pose_.theta + turn / 2);
    } else {
      const float radius = travel / turn;  // eq. 3.27
      pose_.x += radius * (sinf(pose_.theta + turn) - sinf(pose_.theta));
      pose_.y -= radius * (cosf(pose_.theta + turn) - cosf(pose_.theta));
    }
    // eq. 3.31 integrates exactly to the difference of the wheels' travels since setPose: taken
    // from the totals, the heading does not drift with float rounding, however long the run
    const float travelled =
        static_cast<float>(countsBetween(rightRef_, rightCount)) * rightMetresPerCount_ -
        static_cast<float>(countsBetween(leftRef_, leftCount)) * leftMetresPerCount_;
    pose_.theta = wrap(thetaRef_ + travelled / wheelBase_);
  }

  const Pose& getPose() const { return pose_; }

  /// Sets the pose, e.g. the start cell's centre, or a correction from walls seen; the
  /// encoders' totals at that moment are the new reference.
  void setPose(const Pose& pose, int32_t leftCount = 0, int32_t rightCount = 0) {
    pose_ = pose;
    pose_.theta = thetaRef_ = wrap(pose.theta);
    lastLeft_ = leftRef_ = leftCount;
    lastRight_ = rightRef_ = rightCount;
  }

 private:
  // counts from one total to another, also across the totals' wrap-around
  static int32_t countsBetween(int32_t from, int32_t to) {
    return static_cast<int32_t>(static_cast<uint32_t>(to) - static_cast<uint32_t>(from));
  }
  static float wrap(float a) {
    const float pi = static_cast<float>(M_PI);
    while (a > pi) a -= 2 * pi;
    while (a <= -pi) a += 2 * pi;
    return a;
  }

  float leftMetresPerCount_, rightMetresPerCount_, wheelBase_;
  Pose pose_;
  int32_t lastLeft_ = 0, lastRight_ = 0;  // totals at the last update
  int32_t leftRef_ = 0, rightRef_ = 0;    // totals at setPose, when the heading was thetaRef_
  float thetaRef_ = 0;
};

#endif  // UNIMOUSE_SIM_POSE_ESTIMATOR_H_
