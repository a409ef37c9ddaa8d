// SPDX-License-Identifier: MIT
// The facade students program against (dissertation figure 3.16, listing 3.1): the robot's three
// distance sensors, two encoders, two motors and the log over one Stream, usually Serial.
//
//   SimulationRobot robot(Serial);
//   void setup() { Serial.begin(UNIMOUSE_BAUD); robot.begin(); }  // 1 Mbaud
//   void loop() { robot.update(); robot.motorLeft(robot.frontDistance() > 0.3 ? 500 : 0); ... }
//
// begin() never blocks (the original waited for the first readings). In lock-step (begin(true),
// the default of PC builds) each update() first tells the simulator that the previous step is
// done, so everything loop() sent after it counts for that step, then waits for the next step.
#ifndef UNIMOUSE_SIM_SIMULATION_ROBOT_H_
#define UNIMOUSE_SIM_SIMULATION_ROBOT_H_

#include <Arduino.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "SimulationActuators.h"
#include "SimulationSensors.h"
#include "unimouse_protocol.h"

/// The simulator's clock frames (lock-step): sim time in microseconds.
class ClockSensor : public ISimulationSensor {
 public:
  uint8_t getId() const override { return UNIMOUSE_ID_CLOCK; }
  void notify(const uint8_t* payload) override {
    timeUs_ = unimouse_get_u32(payload);
    ticked_ = true;
#ifdef UNIMOUSE_PC_CORE
    unimousePcClock(timeUs_);  // millis() and micros() of a PC build are sim time
#endif
  }
  uint32_t timeUs() const { return timeUs_; }
  /// Whether a clock frame came since the last call.
  bool ticked() {
    const bool t = ticked_;
    ticked_ = false;
    return t;
  }

 private:
  uint32_t timeUs_ = 0;
  bool ticked_ = false;
};

/// The maze the simulator builds (extension frame 14, sent once asked): size in cells, the cell's
/// side, and the goal rectangle. received() is false until the frame has come.
class MazeInfoSensor : public ISimulationSensor {
 public:
  uint8_t getId() const override { return UNIMOUSE_ID_MAZE_INFO; }
  void notify(const uint8_t* payload) override {
    width_ = payload[0];
    height_ = payload[1];
    cellMm_ = unimouse_get_u16(payload + 2);
    for (uint8_t i = 0; i < 4; ++i) goal_[i] = payload[4 + i];
    received_ = true;
  }
  bool received() const { return received_; }
  /// Cells west to east and south to north; 0 when the world has no maze.
  uint8_t width() const { return width_; }
  uint8_t height() const { return height_; }
  /// The side of a cell (the posts' pitch) in metres: 0.18 classic, 0.09 half-size.
  float cellMetres() const { return cellMm_ / 1000.0f; }
  /// The goal rectangle's corners, inclusive: south-west (x0, y0) and north-east (x1, y1).
  uint8_t goalX0() const { return goal_[0]; }
  uint8_t goalY0() const { return goal_[1]; }
  uint8_t goalX1() const { return goal_[2]; }
  uint8_t goalY1() const { return goal_[3]; }

 private:
  bool received_ = false;
  uint8_t width_ = 0, height_ = 0;
  uint16_t cellMm_ = 0;
  uint8_t goal_[4] = {};
};

class SimulationRobot {
 public:
  explicit SimulationRobot(Stream& stream) : sensors_(stream), actuators_(stream) {
    sensors_.addSensor(left_);
    sensors_.addSensor(right_);
    sensors_.addSensor(front_);
    sensors_.addSensor(leftEncoder_);
    sensors_.addSensor(rightEncoder_);
    sensors_.addSensor(clock_);
    sensors_.addSensor(maze_);
    for (uint8_t i = 0; i < 6; ++i) sensors_.addSensor(imu_.axis(i));
  }

#ifdef UNIMOUSE_PC_CORE
  static const bool kLockstepByDefault = true;  // a PC build is driven step by step
#else
  static const bool kLockstepByDefault = false;
#endif

  /// Asks the simulator for sensor frames and, with `lockstep`, to run step by step with the
  /// firmware; says that it resends its commands, so that the simulator may stop the motors
  /// when it falls silent. Returns at once.
  void begin(bool lockstep = kLockstepByDefault) {
    lockstep_ = lockstep;
#ifdef UNIMOUSE_PC_CORE
    // Arduino's delay() keeps this robot stepping, as delay() below does
    unimousePcSetIdle(&SimulationRobot::step, this);
#endif
#ifdef __AVR__
    // avr-libc has no standard output of its own (printf would write through a null stream
    // and crash the board): printf becomes this robot's log, a log frame a line
    fdev_setup_stream(&stdout_, &SimulationRobot::putLogChar, NULL, _FDEV_SETUP_WRITE);
    fdev_set_udata(&stdout_, this);
    stdout = &stdout_;
#endif
    // UNIMOUSE_STARTUP_CODES, in their order: the simulator knows a restarted firmware by them.
    // The sizes of the simulator's data frames first, so that a robot's extra sensor, which
    // this sketch may not read, never desynchronises the frames
    manager(UNIMOUSE_MANAGER_FRAME_SIZES);
    manager(UNIMOUSE_MANAGER_SENSORS_ON);
    manager(UNIMOUSE_MANAGER_REPEATS_COMMANDS);
    if (lockstep) manager(UNIMOUSE_MANAGER_LOCKSTEP_ON);
  }

  /// Reads what the simulator sent and resends steady motor commands; call it every loop().
  /// In lock-step it waits for the whole of the next step, so that each loop() sees one step
  /// and the firmware does the same thing however fast it runs.
  void update() {
    if (stepPending_) {
      manager(UNIMOUSE_MANAGER_STEP_DONE);
      stepPending_ = false;
    }
    if (lockstep_) {
      for (;;) {
        sensors_.updateSensors();
        if (clock_.ticked()) break;
#ifdef UNIMOUSE_PC_CORE
        // everything this firmware owes the step has gone out: the next bytes are the
        // simulator's, so the core may sleep until they come instead of polling
        unimousePcAwaitInput();
#endif
      }
      stepPending_ = true;
    } else {
      sensors_.updateSensors();
      if (clock_.ticked()) stepPending_ = true;
    }
    const uint32_t now = nowMs();
    leftMotor_.refresh(now);
    rightMotor_.refresh(now);
  }

  /// Metres to what each sensor sees; 1.2 m when nothing is in range.
  float leftDistance() const { return left_.distance(); }
  float rightDistance() const { return right_.distance(); }
  float frontDistance() const { return front_.distance(); }
  /// Encoder counts since the previous call (the original's readReset behaviour).
  int32_t leftEncoder() { return leftEncoder_.readReset(); }
  int32_t rightEncoder() { return rightEncoder_.readReset(); }
  /// Encoder counts since the start, for the PoseEstimator.
  int32_t leftEncoderTotal() const { return leftEncoder_.count(); }
  int32_t rightEncoderTotal() const { return rightEncoder_.count(); }
  /// H-bridge commands, -1023..1023 (clamped); positive drives the wheel forward.
  /// The IMU's angular velocity about its z axis (yaw, counter-clockwise positive), rad/s: 0
  /// until the robot's link sends frame UNIMOUSE_ID_GYRO_Z (docs/firmware.md, "Reading the IMU").
  float gyroZ() const { return imu_.gyroRadPerS(2); }
  /// The IMU's six axes, raw counts and SI units.
  ImuSensor& imu() { return imu_; }

  void motorLeft(int32_t command) { leftMotor_.setCommand(command, nowMs()); }
  void motorRight(int32_t command) { rightMotor_.setCommand(command, nowMs()); }
  /// A line for the simulator's log. printf is one too: on the PC it is the firmware's text,
  /// on a board the library makes it log frames (begin()); Serial.print on a board is plain text
  /// between the frames, which the simulator logs line by line.
  void log(const char* text) { logger_.log(text); }
  /// A debug frame for the simulator's maze view (UNIMOUSE_ID_DEBUG_*; docs/protocol.md).
  void debug(uint8_t id, const uint8_t* payload, uint16_t size) {
    actuators_.send(id, payload, size);
  }

  /// A named number of the firmware for the simulator to show beside the run: its HUD, the
  /// replay and the recording's /firmware/values (frame UNIMOUSE_ID_DEBUG_VALUE). Names longer
  /// than 23 characters are cut.
  void debugValue(const char* name, float value) {
    uint8_t frame[4 + 24];
    memcpy(frame, &value, 4);  // little-endian, as on the AVR and the PC
    uint16_t n = 0;
    while (n < 23 && name[n] != '\0') {
      frame[4 + n] = static_cast<uint8_t>(name[n]);
      ++n;
    }
    frame[4 + n] = 0;
    actuators_.send(UNIMOUSE_ID_DEBUG_VALUE, frame, static_cast<uint16_t>(4 + n + 1));
  }

  /// Asks the simulator for the maze (an extension the original ignores); the answer comes
  /// with a later update(): maze().received(). Asked before begin(), in lock-step it comes with
  /// the first step's frames.
  void requestMaze() { manager(UNIMOUSE_MANAGER_MAZE_INFO); }
  /// Tells the simulator the size of the maze the firmware works with, so that it warns when
  /// the world's maze is another size.
  void reportMazeSize(uint8_t width, uint8_t height) {
    const uint8_t size[2] = {width, height};
    actuators_.send(UNIMOUSE_ID_MAZE_SIZE, size, 2);
  }
  /// What the simulator said about the maze (after requestMaze()).
  const MazeInfoSensor& maze() const { return maze_; }

  /// Sim time of the latest clock frame, in microseconds (lock-step only).
  uint32_t simMicros() const { return clock_.timeUs(); }

  /// Waits `ms` milliseconds while keeping up with the simulator (update() all along).
  void delay(uint32_t ms) {
    const uint32_t start = nowMs();
    do update();
    while (nowMs() - start < ms);
  }

  /// The devices themselves, for code written against IDistanceSensor, IEncoder and IMotor.
  DistanceSensor& leftSensor() { return left_; }
  DistanceSensor& rightSensor() { return right_; }
  DistanceSensor& frontSensor() { return front_; }
  EncoderSensor& leftEncoderSensor() { return leftEncoder_; }
  EncoderSensor& rightEncoderSensor() { return rightEncoder_; }
  MotorActuator& leftMotorActuator() { return leftMotor_; }
  MotorActuator& rightMotorActuator() { return rightMotor_; }

  /// Reads a sensor of the robot's beyond the three ToF sensors and two encoders: its frames
  /// (an entry of the link's `send` table, docs/robots.md) reach `sensor` from the next update()
  /// on. Returns false when three extra sensors are registered already.
  bool addSensor(ISimulationSensor& sensor) { return sensors_.addSensor(sensor); }

  /// The frame reader, for its counts of skipped bytes and unclaimed frames.
  const StreamSimulationSensorManager<16>& sensorManager() const { return sensors_; }

 private:
  static void step(void* robot) { static_cast<SimulationRobot*>(robot)->update(); }
#ifdef __AVR__
  static int putLogChar(char c, FILE* stream) {
    static_cast<SimulationRobot*>(fdev_get_udata(stream))->printChar(c);
    return 0;
  }
  void printChar(char c) {
    if (c == '\r') return;
    if (c != '\n') line_[lineLength_++] = c;
    // a line longer than the buffer goes out in pieces
    if (c == '\n' || lineLength_ == sizeof(line_) - 1) {
      line_[lineLength_] = 0;
      logger_.log(line_);
      lineLength_ = 0;
    }
  }
  FILE stdout_;
  char line_[64];
  uint8_t lineLength_ = 0;
#endif
  static uint32_t nowMs() { return unimouseLibraryMillis(); }
  void manager(uint8_t code) { actuators_.send(UNIMOUSE_ID_MANAGER, &code, 1); }

  StreamSimulationSensorManager<16> sensors_;
  StreamActuatorManager actuators_;
  DistanceSensor left_{UNIMOUSE_ID_TOF_LEFT}, right_{UNIMOUSE_ID_TOF_RIGHT},
      front_{UNIMOUSE_ID_TOF_FRONT};
  EncoderSensor leftEncoder_{UNIMOUSE_ID_ENCODER_LEFT}, rightEncoder_{UNIMOUSE_ID_ENCODER_RIGHT};
  ClockSensor clock_;
  MazeInfoSensor maze_;
  ImuSensor imu_;
  MotorActuator leftMotor_{actuators_, UNIMOUSE_ID_MOTOR_LEFT};
  MotorActuator rightMotor_{actuators_, UNIMOUSE_ID_MOTOR_RIGHT};
  SimulationLogger logger_{actuators_};
  bool lockstep_ = false;
  bool stepPending_ = false;
};

#endif  // UNIMOUSE_SIM_SIMULATION_ROBOT_H_
