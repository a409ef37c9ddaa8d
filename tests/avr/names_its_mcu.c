// SPDX-License-Identifier: MIT
// Names its part and clock in simavr's .mmcu section, which win over the link's parameters.
#include <avr/io.h>

#include "avr/avr_mcu_section.h"
AVR_MCU(8000000, "atmega328p");

int main(void) {
  for (;;) {
  }
}
