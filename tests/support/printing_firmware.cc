// SPDX-License-Identifier: GPL-3.0-or-later
// A sketch that prints as students' first sketches do, with printf and std::cout, while it
// drives: on the PC its text is its log, and the protocol is untouched by it.
#include <UnimouseSim.h>

#include <cstdio>
#include <iostream>

SimulationRobot robot(Serial);
unsigned long next_print_us = 100000;

void setup() { robot.begin(); }

void loop() {
  robot.update();
  robot.motorLeft(300);
  robot.motorRight(300);
  if (robot.simMicros() < next_print_us) return;
  std::printf("printf at %lu ms\n", next_print_us / 1000);
  std::cout << "cout at " << next_print_us / 1000 << " ms" << std::endl;
  next_print_us += 100000;
}
