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
  // a board's unsigned long has 32 bits; Arduino takes a base below 2 as 10
  uint32_t v = static_cast<uint32_t>(n);
  if (base < 2 || base > 36) base = 10;
  char digits[8 * sizeof(v) + 1];
  char* at = digits + sizeof(digits);
  do {
    const int d = static_cast<int>(v % static_cast<uint32_t>(base));
    *--at = static_cast<char>(d < 10 ? '0' + d : 'A' + d - 10);
    v /= static_cast<uint32_t>(base);
  } while (v != 0);
  return print(at, static_cast<size_t>(digits + sizeof(digits) - at));
}

size_t PcPrint::print(long n, int base) {
  // as Arduino's 32-bit long: a sign in base 10 only, the two's complement bits in the others
  const int32_t v = static_cast<int32_t>(n);
  if (base != 10 || v >= 0)
    return print(static_cast<unsigned long>(static_cast<uint32_t>(v)), base);
  const size_t sign = print('-');
  return sign + print(static_cast<unsigned long>(0U - static_cast<uint32_t>(v)), 10);
}

size_t PcPrint::print(double x, int digits) {
  // as Arduino writes it: nan, inf (either sign), ovf beyond 32 bits of whole part, else the
  // whole part and the decimals rounded half up
  if (isnan(x)) return print("nan");
  if (isinf(x)) return print("inf");
  if (x > 4294967040.0 || x < -4294967040.0) return print("ovf");
  if (digits < 0) digits = 2;
  size_t n = 0;
  if (x < 0) {
    n += print('-');
    x = -x;
  }
  double rounding = 0.5;
  for (int i = 0; i < digits; ++i) rounding /= 10.0;
  x += rounding;
  const uint32_t whole = static_cast<uint32_t>(x);
  double rest = x - whole;
  n += print(static_cast<unsigned long>(whole), 10);
  if (digits > 0) n += print('.');
  while (digits-- > 0) {
    rest *= 10.0;
    const unsigned int digit = static_cast<unsigned int>(rest);
    n += print(static_cast<char>('0' + digit));
    rest -= digit;
  }
  return n;
}
