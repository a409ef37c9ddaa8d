// SPDX-License-Identifier: GPL-3.0-or-later
// A sketch that debugs as Arduino sketches do, with Serial.print, Serial.println and printf
// (and no include for it), every 100 ms while it drives.
#include <UnimouseSim.h>

SimulationRobot robot(Serial);
unsigned long next_ms = 100;

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
}

void loop() {
  robot.update();
  robot.motorLeft(300);
  robot.motorRight(300);
  if (millis() < next_ms) return;
  Serial.print("print at ");
  Serial.print(next_ms);
  Serial.print(F(" ms, "));
  Serial.print(1.5, 3);
  Serial.print(' ');
  Serial.print(-42);
  Serial.print(' ');
  Serial.println(255, HEX);
  printf("printf at %lu ms\n", next_ms);
  next_ms += 100;
}
