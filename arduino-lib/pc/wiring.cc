// SPDX-License-Identifier: MIT
// The PC core's pins, random numbers and number helpers: what a sketch calls as on a board.
// The pins are wired to nothing (the robot is the library's, over the link); random() follows
// the board's sequence (avr-libc's generator), so a seeded sketch draws the same numbers there.
#include <stdio.h>

#include "Arduino.h"

namespace {

constexpr int kPins = 70;  // a Mega 2560's digital and analog pins
uint8_t level[kPins];      // what was written, or the pull-up's HIGH
uint32_t random_state = 1;

bool Valid(uint8_t pin) { return pin < kPins; }

// the "minimal standard" generator (multiplier 16807 modulo 2^31 - 1), as avr-libc computes it
// without overflow in 32 bits; a state of 0 would stay 0, so it starts again elsewhere
long NextRandom() {
  int32_t x = static_cast<int32_t>(random_state);
  if (x == 0) x = 123459876;
  const int32_t hi = x / 127773;
  const int32_t lo = x % 127773;
  x = 16807 * lo - 2836 * hi;
  if (x < 0) x += 0x7fffffff;
  random_state = static_cast<uint32_t>(x);
  return x;
}

}  // namespace

long map(long x, long in_min, long in_max, long out_min, long out_max) {
  // in 32 bits, wrapping as a board's long does
  const auto wrap = [](uint32_t v) { return static_cast<int32_t>(v); };
  const int32_t d = wrap(static_cast<uint32_t>(in_max) - static_cast<uint32_t>(in_min));
  const int32_t product = wrap((static_cast<uint32_t>(x) - static_cast<uint32_t>(in_min)) *
                               (static_cast<uint32_t>(out_max) - static_cast<uint32_t>(out_min)));
  // a board divides by zero here, and the PC would stop; -1 would overflow the quotient
  if (d == 0) return out_min;
  const int32_t quotient = d == -1 ? wrap(0U - static_cast<uint32_t>(product)) : product / d;
  return wrap(static_cast<uint32_t>(quotient) + static_cast<uint32_t>(out_min));
}

void pinMode(uint8_t pin, uint8_t mode) {
  // as the board's port bit: an output keeps the level written before
  if (Valid(pin) && mode != OUTPUT) level[pin] = mode == INPUT_PULLUP ? HIGH : LOW;
}

void digitalWrite(uint8_t pin, uint8_t value) {
  if (Valid(pin)) level[pin] = value == LOW ? LOW : HIGH;
}

int digitalRead(uint8_t pin) { return Valid(pin) ? level[pin] : LOW; }

int analogRead(uint8_t) { return 0; }

void analogWrite(uint8_t pin, int value) {
  if (Valid(pin)) level[pin] = value >= 128 ? HIGH : LOW;
}

void tone(uint8_t, unsigned int, unsigned long) {}

void noTone(uint8_t) {}

void attachInterrupt(uint8_t, void (*)(), int) {}

void detachInterrupt(uint8_t) {}

void randomSeed(unsigned long seed) {
  if (seed != 0) random_state = static_cast<uint32_t>(seed);
}

long random(long howbig) {
  if (howbig == 0) return 0;
  return NextRandom() % howbig;
}

long random(long howsmall, long howbig) {
  if (howsmall >= howbig) return howsmall;
  return random(howbig - howsmall) + howsmall;
}

char* dtostrf(double x, signed char width, unsigned char precision, char* text) {
  sprintf(text, "%*.*f", width, precision, x);
  return text;
}
