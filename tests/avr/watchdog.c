// SPDX-License-Identifier: MIT
// Arms the watchdog for 15 ms and then hangs without resetting it.
#include <avr/wdt.h>

int main(void) {
  wdt_enable(WDTO_15MS);
  for (;;) {
  }
}
