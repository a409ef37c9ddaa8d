// SPDX-License-Identifier: MIT
// The part of the Arduino core that the UnimouseSim library and its examples use, for building
// them as programs on the PC: Stream, and (with the simulator's clock) millis, micros and delay.
// Only what the library needs; a sketch that needs more is built for a board.
#ifndef UNIMOUSE_PC_ARDUINO_H_
#define UNIMOUSE_PC_ARDUINO_H_

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>  // printf, as the board's Arduino.h brings it

#define PI 3.1415926535897932384626433832795
#define DEC 10
#define HEX 16
#define OCT 8
#define BIN 2
/// Text kept in flash on a board; on the PC the text itself.
#define F(text) (text)

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

/// Arduino's print() and println(). On the PC they are text, never bytes of the protocol: they
/// go to the firmware's log (the run's log.txt), a line at each newline, as printf does.
class PcPrint {
 public:
  size_t print(const char* text);
  size_t print(char c) { return print(&c, 1); }
  size_t print(unsigned char n, int base = DEC) {
    return print(static_cast<unsigned long>(n), base);
  }
  size_t print(int n, int base = DEC) { return print(static_cast<long>(n), base); }
  size_t print(unsigned int n, int base = DEC) {
    return print(static_cast<unsigned long>(n), base);
  }
  size_t print(long n, int base = DEC);
  size_t print(unsigned long n, int base = DEC);
  size_t print(double x, int digits = 2);
  /// Ends the line (Arduino sends "\r\n"; a log line ends at the newline).
  size_t println() { return print('\n'); }
  template <typename T>
  size_t println(T value) {
    const size_t n = print(value);
    return n + println();
  }
  template <typename T>
  size_t println(T value, int format) {
    const size_t n = print(value, format);
    return n + println();
  }

 private:
  size_t print(const char* text, size_t size);
};

/// The board's serial port; on the PC, the program's stdin and stdout, which `unimouse run
/// --link native:PROGRAM` connects to the simulator. Output goes out whenever input is looked
/// for. End of input (the simulator went away) ends the program. print() and println() are the
/// firmware's log (PcPrint).
class HardwareSerial : public Stream, public PcPrint {
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
/// Waits so many milliseconds (microseconds) of sim time once the simulator's clock frames come:
/// the library's robot keeps stepping the simulation meanwhile (as SimulationRobot::delay), a
/// step of the simulation (1 ms) at a time, so a wait ends at the first step boundary at or
/// after its end. Before lock-step, and without a SimulationRobot, it waits on the wall clock,
/// which the simulator then keeps pace with.
void delay(unsigned long ms);
void delayMicroseconds(unsigned int us);

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
/// The library registers here what keeps the simulation running while the sketch waits in
/// delay(): its robot's update(), which waits for one step of the simulation a call.
void unimousePcSetIdle(void (*idle)(void* context), void* context);
/// Waits on the wall clock: each core's own way, for delay() before sim time runs.
void unimousePcWallWait(unsigned long us);
/// Hands text to the firmware's log: each core's own way.
void unimousePcText(const char* text, size_t size);

#endif  // UNIMOUSE_PC_ARDUINO_H_
