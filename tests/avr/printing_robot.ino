// SPDX-License-Identifier: MIT
// A student's debugging on a board: Serial.print and Serial.println between the library's frames,
// and printf, every 100 ms of its own time, while it drives in lock-step.
#include <UnimouseSim.h>

SimulationRobot robot(Serial);
unsigned long next_ms = 100;

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin(true);
}

void loop() {
  robot.update();
  robot.motorLeft(300);
  robot.motorRight(300);
  if (robot.simMicros() / 1000 < next_ms) return;
  Serial.print("print at ");
  Serial.println(next_ms);
  printf("printf at %lu ms\n", next_ms);
  next_ms += 100;
}
