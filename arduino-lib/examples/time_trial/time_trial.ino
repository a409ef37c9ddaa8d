// SPDX-License-Identifier: MIT
// Time trial (dissertation section 5.1.3): laps of the stadium track counter-clockwise, following
// the outer wall on the right like algorithm 4 follows its wall on the left. The right sensor
// sits 0.048 m right of the centre and looks 45 degrees to the right, so with the centre d from
// the wall it reads (d - 0.048) / cos(45 deg); the 0.8 m lane's middle is 0.4 m from the wall.
#include <UnimouseSim.h>

SimulationRobot robot(Serial);

const float kDistance = 0.40f;       // m, from the outer wall to the robot's centre
const float kSensorOffset = 0.048f;  // m, from the centre to the right sensor
const float kGoal = (kDistance - kSensorOffset) / 0.70710678f;
const int kBase = 600;
const int kGain = 900;  // per metre of error
const int kMaxTurn = 300;

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
}

void loop() {
  robot.update();
  const float error = robot.rightDistance() - kGoal;  // too far from the wall: positive, turn right
  int turn = static_cast<int>(kGain * error);
  if (turn > kMaxTurn) turn = kMaxTurn;
  if (turn < -kMaxTurn) turn = -kMaxTurn;
  robot.motorLeft(kBase + turn);
  robot.motorRight(kBase - turn);
}
