// SPDX-License-Identifier: MIT
// Writes a byte just beyond the end of the Mega 2560's 8 KiB of SRAM (RAMEND 0x21ff), as a
// stray pointer would.
#include <avr/io.h>
#include <stdint.h>

int main(void) {
  volatile uint8_t* stray = (volatile uint8_t*)0x2208;
  *stray = 0xa5;
  for (;;) {
  }
}
