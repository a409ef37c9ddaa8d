// SPDX-License-Identifier: MIT
// The part of the Arduino core that the UnimouseSim library and its examples use, for building
// them as programs on the PC: Stream, and (with the simulator's clock) millis, micros and delay.
// Only what the library needs; a sketch that needs more is built for a board.
#ifndef UNIMOUSE_PC_ARDUINO_H_
#define UNIMOUSE_PC_ARDUINO_H_

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#define PI 3.1415926535897932384626433832795

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

/// The board's serial port; on the PC, the program's stdin and stdout, which `unimouse run
/// --link native:PROGRAM` connects to the simulator. Output goes out whenever input is looked
/// for. End of input (the simulator went away) ends the program.
class HardwareSerial : public Stream {
 public:
  void begin(unsigned long) {}
  int available() override;
  int read() override;
  size_t write(uint8_t byte) override;
  void flush() override;
};
extern HardwareSerial Serial;

/// Milliseconds and microseconds since the start: on the PC, sim time from the simulator's clock
/// frames once they come (lock-step), wall time before.
unsigned long millis();
unsigned long micros();
/// Waits on the wall clock. In lock-step sim time only moves while the firmware answers, so
/// wait with SimulationRobot::delay instead.
void delay(unsigned long ms);

/// The sketch.
void setup();
void loop();

/// Builds for the PC define this; the library then hands the simulator's clock frames to the
/// core's millis() and micros().
#define UNIMOUSE_PC_CORE 1
void unimousePcClock(uint32_t simMicros);
/// Sends what is written and waits, without using the CPU, until input comes. The library calls
/// it only in lock-step once it has sent all it owes the step, when the simulator is sure to
/// answer; a sketch that polls Serial must not call it.
void unimousePcAwaitInput();

#endif  // UNIMOUSE_PC_ARDUINO_H_
