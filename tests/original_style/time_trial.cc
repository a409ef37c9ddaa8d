// SPDX-License-Identifier: GPL-3.0-or-later
// Time trial, in the style of the original's circuit sketch: laps of the stadium track
// counter-clockwise, following the outer wall on the right. The right sensor, half a wheelbase
// right of the centre and looking 45 degrees to the right, reads (0.45 - 0.048) * sqrt(2) with
// the centre 0.45 m from the wall. The right motor's command never changes, so the library sends
// it once; only the left one steers.
#include <cmath>

#include "sim_robot.h"

SimRobot sr;

const float kDistance = 0.45f;  // m, from the outer wall to the robot's centre
const float kGoal = (kDistance - SimRobot::WHEEL_TO_WHEEL / 2) * std::sqrt(2.0f);
const float kBase = 900;
const float kGain = 300;  // per metre of error

void setup() {
  Serial.begin(115200);
  sr.initialize();
  sr.log("time trial: ready");
}

void loop() {
  sr.update();
  const float error = kGoal - sr.rightDistance();  // too far from the wall: negative, turn right
  sr.leftMotor(static_cast<int>(kBase - kGain * error));
  sr.rightMotor(static_cast<int>(kBase));
}
