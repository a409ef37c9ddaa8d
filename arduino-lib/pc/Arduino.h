// SPDX-License-Identifier: MIT
// The Arduino core for building sketches as programs on the PC: Serial, print, the clock
// (millis, micros and delay on the simulator's clock), and the everyday language of a sketch
// (types, constants, math and bit helpers, random, PROGMEM, String). The PC has no pins wired to
// the robot: its motors and sensors are the library's, over the link; pinMode and
// digitalWrite keep what was written, analogRead reads 0, interrupts never fire.
#ifndef UNIMOUSE_PC_ARDUINO_H_
#define UNIMOUSE_PC_ARDUINO_H_

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>   // printf, as the board's Arduino.h brings it
#include <stdlib.h>  // abs, malloc, as on the board
#include <string.h>  // memcpy, strlen, as on the board

#include <type_traits>

#define PI 3.1415926535897932384626433832795
#define HALF_PI 1.5707963267948966192313216916398
#define TWO_PI 6.283185307179586476925286766559
#define DEG_TO_RAD 0.017453292519943295769236907684886
#define RAD_TO_DEG 57.295779513082320876798154814105
#define EULER 2.718281828459045235360287471352
#define DEC 10
#define HEX 16
#define OCT 8
#define BIN 2
/// Text kept in flash on a board; on the PC the text itself.
#define F(text) (text)

// the types and constants of a sketch, with the values of the board's core
typedef uint8_t byte;
typedef bool boolean;
typedef unsigned int word;
#define HIGH 0x1
#define LOW 0x0
#define INPUT 0x0
#define OUTPUT 0x1
#define INPUT_PULLUP 0x2
#define CHANGE 1
#define FALLING 2
#define RISING 3
#define LED_BUILTIN 13
/// The analog inputs' pin numbers, as on a Mega 2560.
enum : uint8_t { A0 = 54, A1, A2, A3, A4, A5, A6, A7, A8, A9, A10, A11, A12, A13, A14, A15 };

// the core's helpers; functions rather than the board's macros, so that std::min and friends
// still compile, with the macros' result type
template <typename A, typename B>
constexpr typename std::common_type<A, B>::type min(A a, B b) {
  return a < b ? a : b;
}
template <typename A, typename B>
constexpr typename std::common_type<A, B>::type max(A a, B b) {
  return a > b ? a : b;
}
template <typename T, typename L, typename H>
constexpr typename std::common_type<T, L, H>::type constrain(T x, L low, H high) {
  return x < low ? low : (x > high ? high : x);
}
template <typename T>
constexpr auto sq(T x) -> decltype(x * x) {
  return x * x;
}
#define radians(deg) ((deg)*DEG_TO_RAD)
#define degrees(rad) ((rad)*RAD_TO_DEG)
/// Arduino's map(): integer arithmetic on long, as on the board.
long map(long x, long in_min, long in_max, long out_min, long out_max);

/// word(x) and word(high, low), as the board's core has them beside the type word.
inline unsigned int makeWord(unsigned int w) { return w; }
inline unsigned int makeWord(uint8_t high, uint8_t low) {
  return static_cast<unsigned int>(high << 8 | low);
}
#define word(...) makeWord(__VA_ARGS__)
#define lowByte(w) ((uint8_t)((w)&0xff))
#define highByte(w) ((uint8_t)((w) >> 8))
#define bit(b) (1UL << (b))
#define bitRead(value, b) (((value) >> (b)) & 0x01)
#define bitSet(value, b) ((value) |= (1UL << (b)))
#define bitClear(value, b) ((value) &= ~(1UL << (b)))
#define bitWrite(value, b, bitvalue) ((bitvalue) ? bitSet(value, b) : bitClear(value, b))
#define bitToggle(value, b) ((value) ^= (1UL << (b)))

/// Pins: the PC's are wired to nothing. A pin reads back what was written to it (HIGH for
/// INPUT_PULLUP), an analog input reads 0.
void pinMode(uint8_t pin, uint8_t mode);
void digitalWrite(uint8_t pin, uint8_t value);
int digitalRead(uint8_t pin);
int analogRead(uint8_t pin);
void analogWrite(uint8_t pin, int value);
void tone(uint8_t pin, unsigned int frequency, unsigned long duration = 0);
void noTone(uint8_t pin);
/// Interrupts: no pin changes on the PC, so a handler is kept and never called.
#define digitalPinToInterrupt(p) \
  ((p) == 2 ? 0 : ((p) == 3 ? 1 : ((p) >= 18 && (p) <= 21 ? 23 - (p) : -1)))
void attachInterrupt(uint8_t interrupt, void (*handler)(), int mode);
void detachInterrupt(uint8_t interrupt);
inline void interrupts() {}
inline void noInterrupts() {}
inline void yield() {}

/// Arduino's random numbers: a sequence fixed by randomSeed(), the same in every run.
void randomSeed(unsigned long seed);
long random(long howbig);
long random(long howsmall, long howbig);

/// Arduino's dtostrf(): x in at least `width` characters with `precision` decimals.
char* dtostrf(double x, signed char width, unsigned char precision, char* text);

#include "WString.h"  // String, as the board's Arduino.h brings it

// flash on a board, plain memory on the PC
#define PROGMEM
#define PSTR(text) (text)
#define pgm_read_byte(address) (*(const uint8_t*)(address))
#define pgm_read_word(address) (*(const uint16_t*)(address))
#define pgm_read_dword(address) (*(const uint32_t*)(address))
#define pgm_read_float(address) (*(const float*)(address))
#define pgm_read_ptr(address) (*(void* const*)(address))
#define memcpy_P memcpy
#define strcpy_P strcpy
#define strlen_P strlen
#define strcmp_P strcmp

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
  size_t print(const String& text) { return print(text.c_str(), text.length()); }
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
  /// Whether the port is open: always, as a Mega 2560's (`while (!Serial) {}` goes on).
  explicit operator bool() const { return true; }
  int available() override;
  int read() override;
  size_t write(uint8_t byte) override;
  using Stream::write;
  size_t write(const char* text) {
    return write(reinterpret_cast<const uint8_t*>(text), strlen(text));
  }
  void flush() override;
};
extern HardwareSerial Serial;

/// Milliseconds and microseconds since the start, as clock.cc counts them on the PC: never
/// back, the same in every run; a loop that only reads them lets time go by (a step per 1000
/// reads), as a board's clock runs on while it spins.
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
/// millis() for the library's own reads: the same clock, never taken for a sketch's spin.
unsigned long unimousePcLibraryMillis();
/// Hands text to the firmware's log: each core's own way.
void unimousePcText(const char* text, size_t size);

#endif  // UNIMOUSE_PC_ARDUINO_H_
