// SPDX-License-Identifier: MIT
// Turns its receiver on at 1 Mbaud, then never reads it: whatever comes after the receiver's
// FIFO is full is lost, and the UART says so (DOR).
#include <avr/io.h>

int main(void) {
  UBRR0 = 1;  // 1 Mbaud at 16 MHz with U2X
  UCSR0A = _BV(U2X0);
  UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
  UCSR0B = _BV(RXEN0) | _BV(TXEN0);
  for (;;) {
  }
}
