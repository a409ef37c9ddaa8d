/* SPDX-License-Identifier: MIT */
/* printf and its kin for a firmware module: the module is linked -Bsymbolic, so the sketch's
 * calls bind to these, and what it prints is its log (unimouse_inproc_text), not text on the
 * terminal of the simulator that loaded it. C, where these carry no exception specification
 * to match. The compiler turns printf("line\n") into puts and printf("c") into putchar. */
#undef _FORTIFY_SOURCE
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "unimouse_inproc.h"

int vprintf(const char* format, va_list args) {
  char text[512];
  const int n = vsnprintf(text, sizeof(text), format, args);
  if (n < 0) return n;
  /* longer than a log line anyway: cut */
  unimouse_inproc_text(text, (size_t)n < sizeof(text) ? (size_t)n : sizeof(text) - 1);
  return n;
}

int printf(const char* format, ...) {
  va_list args;
  va_start(args, format);
  const int n = vprintf(format, args);
  va_end(args);
  return n;
}

/* what printf and vprintf become with _FORTIFY_SOURCE (a package build's flags) */
int __vprintf_chk(int flag, const char* format, va_list args) {
  (void)flag;
  return vprintf(format, args);
}

int __printf_chk(int flag, const char* format, ...) {
  (void)flag;
  va_list args;
  va_start(args, format);
  const int n = vprintf(format, args);
  va_end(args);
  return n;
}

int puts(const char* text) {
  const size_t n = strlen(text);
  unimouse_inproc_text(text, n);
  unimouse_inproc_text("\n", 1);
  return (int)n + 1;
}

int putchar(int c) {
  const char byte = (char)c;
  unimouse_inproc_text(&byte, 1);
  return (unsigned char)c;
}
