// SPDX-License-Identifier: GPL-3.0-or-later
// A firmware module that drives for a while and then fails the way UNIMOUSE_FAIL says: a null
// pointer, a loop() that never returns, exit(3) or abort(), just after it printed a line. Built
// once for each (tests/CMakeLists.txt).
#include <UnimouseSim.h>

#include <cstdlib>

SimulationRobot robot(Serial);

void setup() { robot.begin(); }

// the null pointer is a real fault for the simulator to catch, not a sanitizer's report
__attribute__((no_sanitize("null"))) void loop() {
  robot.update();
  robot.motorLeft(300);
  robot.motorRight(300);
  if (robot.simMicros() < 200000) return;
  // the line a student needs most: the last one before the end
  printf("failing at %lu ms\n", millis());
#if UNIMOUSE_FAIL == 1
  volatile int* nowhere = nullptr;
  *nowhere = 1;
#elif UNIMOUSE_FAIL == 2
  for (;;) asm volatile("");  // never yields
#elif UNIMOUSE_FAIL == 3
  std::exit(3);
#else
  std::abort();
#endif
}
