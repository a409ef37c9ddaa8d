// SPDX-License-Identifier: GPL-3.0-or-later
// A sketch that waits as Arduino sketches do, with delay() in loop() and delayMicroseconds(),
// and says in the robot's log what millis() and micros() read around each wait.
#include <UnimouseSim.h>

SimulationRobot robot(Serial);

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
}

void loop() {
  robot.update();
  robot.motorLeft(400);
  robot.motorRight(400);
  char line[80];
  const unsigned long before_us = micros();
  delayMicroseconds(2500);
  snprintf(line, sizeof line, "delayMicroseconds(2500) took %lu us", micros() - before_us);
  robot.log(line);
  const unsigned long before_ms = millis();
  delay(50);
  snprintf(line, sizeof line, "delay(50) took %lu ms", millis() - before_ms);
  robot.log(line);
}
