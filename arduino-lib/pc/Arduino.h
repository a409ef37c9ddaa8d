// SPDX-License-Identifier: MIT
// The part of the Arduino core that the UnimouseSim library and its examples use, for building
// them as programs on the PC: Stream, and (with the simulator's clock) millis, micros and delay.
// Only what the library needs; a sketch that needs more is built for a board.
#ifndef UNIMOUSE_PC_ARDUINO_H_
#define UNIMOUSE_PC_ARDUINO_H_

#include <math.h>
#include <stddef.h>
#include <stdint.h>

/// A byte stream, as Arduino's: a board's Serial is one.
class Stream {
 public:
  virtual ~Stream() = default;
  /// Bytes that can be read now without waiting.
  virtual int available() = 0;
  /// The next byte, or -1 when none is available.
  virtual int read() = 0;
  virtual size_t write(uint8_t byte) = 0;
  virtual size_t write(const uint8_t* bytes, size_t size) {
    size_t n = 0;
    while (n < size && write(bytes[n]) == 1) ++n;
    return n;
  }
  virtual void flush() {}
};

/// Milliseconds and microseconds since the start; on the PC, of sim time once lock-step is on.
unsigned long millis();
unsigned long micros();

#endif  // UNIMOUSE_PC_ARDUINO_H_
