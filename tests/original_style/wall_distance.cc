// SPDX-License-Identifier: GPL-3.0-or-later
// Wall distance, in the style of the original's example sketch: keep 0.5 m from the wall on the
// left by steering on the left sensor alone, proportionally, at a constant base speed. The sensor
// sits half a wheelbase left of the centre and looks 45 degrees to the left, so with the centre
// 0.5 m from the wall it reads (0.5 - 0.048) * sqrt(2). The motors are set every loop; the
// library sends a command only when it changes.
#include <cmath>

#include "sim_robot.h"

SimRobot sr;

const float kDistance = 0.5f;  // m, from the wall to the robot's centre
const float kGoal = (kDistance - SimRobot::WHEEL_TO_WHEEL / 2) * std::sqrt(2.0f);
const float kBase = 300;
const float kGain = 50;  // per metre of error

void setup() {
  Serial.begin(115200);
  sr.initialize();
  sr.log("wall distance: ready");
}

void loop() {
  sr.update();
  const float error = kGoal - sr.leftDistance();  // too far from the wall: negative, turn left
  sr.leftMotor(static_cast<int>(kBase + kGain * error));
  sr.rightMotor(static_cast<int>(kBase - kGain * error));
}
