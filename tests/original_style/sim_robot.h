// SPDX-License-Identifier: GPL-3.0-or-later
// A PC stand-in for the original UnimouseSim Arduino library (`#include <sim_robot.h>`), written
// from the description of its behaviour, so that sketches in its style run unchanged against this
// simulator. It does exactly what the original did on the wire: `07 02` at start, motor frames
// only when a command changes, `08 text 00` for logs; no lock-step, no extension frames, distances
// decoded with a 1.0 m full scale.
//
// A program links sim_robot.cc, which supplies main(): it opens the serial port (the device path
// given as the first argument, e.g. a pseudo-terminal's slave, or else stdin and stdout), then
// calls the sketch's setup() once and loop() forever. It exits when the simulator goes away.
#ifndef UNIMOUSE_TESTS_ORIGINAL_STYLE_SIM_ROBOT_H_
#define UNIMOUSE_TESTS_ORIGINAL_STYLE_SIM_ROBOT_H_

#include <cstddef>
#include <cstdint>

/// The sketch's entry points, as on an Arduino.
void setup();
void loop();

/// Milliseconds of wall time since the program started, as an Arduino counts them.
unsigned long millis();

/// The board's serial port: a tty device opened raw, or stdin and stdout.
class SerialPort {
 public:
  /// Opens `device` (waiting up to `wait_ms` for it to appear), or stdin and stdout for nullptr.
  /// Exits the program when it cannot.
  void Open(const char* device, int wait_ms);
  /// Does nothing: the line's speed is the simulator's business.
  void begin(unsigned long baud) { (void)baud; }
  /// Returns how many received bytes can be read without waiting.
  int available();
  /// Returns the next received byte, or -1 when there is none.
  int read();
  /// Sends `size` bytes, all of them.
  void write(const uint8_t* data, size_t size);
  /// Waits up to `timeout_ms` for more bytes to arrive; returns whether some did.
  bool WaitReadable(int timeout_ms);

 private:
  void Fill(int timeout_ms);

  int in_fd_ = 0;
  int out_fd_ = 1;
  uint8_t buffer_[4096] = {};
  size_t head_ = 0;
  size_t tail_ = 0;
};

/// The board's only serial port.
extern SerialPort Serial;

/// The original library's robot: three distance sensors, two encoders, two motors and a log, over
/// Serial, with its frame ids (ToF 0-2, encoders 3-4, motors 5-6, manager 7, log 8).
class SimRobot {
 public:
  static constexpr float GEAR_RATIO = 29.86f;
  static constexpr int ENCODER_PPR = 12;
  static constexpr float WHEEL_RADIUS = 0.016f;    // m
  static constexpr float WHEEL_TO_WHEEL = 0.096f;  // m, between the wheels' centres

  /// Asks the simulator for sensor frames (`07 02`), then waits until each distance sensor has
  /// had a reading: until the simulator is there and streaming.
  void initialize();
  /// Reads every frame that has arrived; a frame begun is waited for until it is whole.
  void update();
  /// Waits `ms` milliseconds, calling update() all the while.
  void delay(unsigned long ms);
  /// Sends a log line (`08 text 00`).
  void log(const char* text);

  /// Returns the latest reading in metres, decoded with a 1.0 m full scale.
  float leftDistance() const { return Metres(tof_[0]); }
  float rightDistance() const { return Metres(tof_[1]); }
  float frontDistance() const { return Metres(tof_[2]); }
  /// Returns the counts since the previous call (kept in 16 bits, as the original did).
  int leftEncoder() { return ReadReset(encoder_[0]); }
  int rightEncoder() { return ReadReset(encoder_[1]); }
  /// Sets a motor's H-bridge command (-1023 to 1023); sent only when it differs from the last.
  void leftMotor(int command) { Motor(0, command); }
  void rightMotor(int command) { Motor(1, command); }

 private:
  static float Metres(uint16_t counts) { return counts * 1.0f / 65535.0f; }
  static int ReadReset(int16_t& counts) {
    const int value = counts;
    counts = 0;
    return value;
  }
  void Motor(int side, int command);

  uint16_t tof_[3] = {0, 0, 0};
  bool tof_seen_[3] = {false, false, false};
  int16_t encoder_[2] = {0, 0};
  int16_t motor_sent_[2] = {0, 0};
};

#endif  // UNIMOUSE_TESTS_ORIGINAL_STYLE_SIM_ROBOT_H_
