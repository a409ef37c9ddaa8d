// SPDX-License-Identifier: MIT
// The library's lock-step on a board: begin(true), then each loop() one step; drives forward at
// 400 and logs "lockstep" once, so that a test sees the commands and the log line.
#include <UnimouseSim.h>

SimulationRobot robot(Serial);
bool said = false;

void setup() {
  Serial.begin(1000000);
  robot.begin(true);
}

void loop() {
  robot.update();
  if (!said) {
    robot.log("lockstep");
    said = true;
  }
  robot.motorLeft(400);
  robot.motorRight(400);
}
