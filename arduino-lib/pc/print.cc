// SPDX-License-Identifier: MIT
// Arduino's print() and println() for the PC cores: numbers written as Arduino writes them, the
// text handed to the core's log (unimousePcText).
#include <string.h>

#include "Arduino.h"

size_t PcPrint::print(const char* text, size_t size) {
  unimousePcText(text, size);
  return size;
}

size_t PcPrint::print(const char* text) { return print(text, strlen(text)); }

size_t PcPrint::print(unsigned long n, int base) {
  // Arduino takes a base below 2 as 10
  if (base < 2 || base > 36) base = 10;
  char digits[8 * sizeof(n) + 1];
  char* at = digits + sizeof(digits);
  do {
    const int d = static_cast<int>(n % static_cast<unsigned long>(base));
    *--at = static_cast<char>(d < 10 ? '0' + d : 'A' + d - 10);
    n /= static_cast<unsigned long>(base);
  } while (n != 0);
  return print(at, static_cast<size_t>(digits + sizeof(digits) - at));
}

size_t PcPrint::print(long n, int base) {
  // as Arduino: a sign in base 10 only, the two's complement bits in the others
  if (base != 10 || n >= 0) return print(static_cast<unsigned long>(n), base);
  const size_t sign = print('-');
  return sign + print(0UL - static_cast<unsigned long>(n), 10);
}

size_t PcPrint::print(double x, int digits) {
  if (digits < 0) digits = 2;
  char text[64];
  const int n = snprintf(text, sizeof(text), "%.*f", digits, x);
  return print(text, n < 0                                   ? 0
                     : static_cast<size_t>(n) < sizeof(text) ? static_cast<size_t>(n)
                                                             : sizeof(text) - 1);
}
