// SPDX-License-Identifier: MIT
// Wall distance (dissertation section 5.1.2, algorithm 4): keep the robot's centre 0.50 m from
// the wall on its left while driving along it, with a proportional controller on the left
// distance sensor. That sensor sits 0.048 m left of the centre and looks 45 degrees to the left,
// so with the centre d from the wall it reads (d - 0.048) / cos(45 deg). (Algorithm 4 as printed
// computes cos(45 deg) * d + L / 2, which is not what the sensor reads.)
#include <UnimouseSim.h>

SimulationRobot robot(Serial);

const float kDistance = 0.50f;       // m, from the wall to the robot's centre
const float kSensorOffset = 0.048f;  // m, from the centre to the left sensor
const float kGoal = (kDistance - kSensorOffset) / 0.70710678f;
const int kBase = 500;  // motor command when on target
const int kGain = 900;  // per metre of error
const int kMaxTurn = 300;

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
}

void loop() {
  robot.update();
  const float error = robot.leftDistance() - kGoal;  // too far from the wall: positive, turn left
  int turn = static_cast<int>(kGain * error);
  if (turn > kMaxTurn) turn = kMaxTurn;
  if (turn < -kMaxTurn) turn = -kMaxTurn;
  robot.motorLeft(kBase - turn);
  robot.motorRight(kBase + turn);
}
