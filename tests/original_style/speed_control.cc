// SPDX-License-Identifier: GPL-3.0-or-later
// Speed control, in the style of the original's example sketch: every 20 ms, the wheels' speeds
// from the encoders' counts, then integral control of the linear speed and of the turn rate
// towards the original challenge's targets, 0.8 m/s and 1.57 rad/s clockwise. As in the original,
// the turn rate counts clockwise positive: (left - right) / wheelbase.
#include <cmath>

#include "sim_robot.h"

SimRobot sr;

const float kSpeed = 0.8f;      // m/s
const float kTurnRate = 1.57f;  // rad/s, clockwise
const unsigned long kPeriodMs = 20;
const float kMetresPerCount =
    2 * 3.14159265f * SimRobot::WHEEL_RADIUS / (SimRobot::GEAR_RATIO * SimRobot::ENCODER_PPR);

float base = 0;
float offset = 0;

void setup() {
  Serial.begin(115200);
  sr.initialize();
  sr.log("speed control: ready");
}

void loop() {
  sr.delay(kPeriodMs);
  const float left = static_cast<float>(sr.leftEncoder()) * kMetresPerCount / (kPeriodMs / 1000.0f);
  const float right =
      static_cast<float>(sr.rightEncoder()) * kMetresPerCount / (kPeriodMs / 1000.0f);
  const float speed = (left + right) / 2;
  const float turnRate = (left - right) / SimRobot::WHEEL_TO_WHEEL;
  base += (kSpeed - speed) * 10;
  offset += (kTurnRate - turnRate) * 1.0f;
  sr.leftMotor(static_cast<int>(base + offset));
  sr.rightMotor(static_cast<int>(base - offset));
}
