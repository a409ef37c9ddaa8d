// SPDX-License-Identifier: MIT
// Recurses without end, each call keeping 32 bytes on the stack, until the stack runs into the
// 4 KiB of data below it.
#include <avr/io.h>
#include <stdint.h>

volatile uint8_t table[4096];

__attribute__((noinline)) uint16_t recurse(uint16_t depth) {
  volatile uint8_t frame[32];
  frame[depth % 32] = (uint8_t)depth;
  table[depth % sizeof(table)] = frame[0];
  return recurse(depth + 1) + frame[depth % 32];
}

int main(void) {
  // a little work first, so that the board has run a while
  for (uint16_t i = 0; i < 1000; ++i) table[i] = (uint8_t)i;
  return recurse(0);
}
