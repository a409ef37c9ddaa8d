// SPDX-License-Identifier: MIT
// The simulator's sensor frames on the firmware side (dissertation tables 3.10 and 3.11): a
// sensor manager reads a Stream and hands each whole frame to the sensor registered for its id.
// Unlike the original it never waits for the rest of a frame (a partial frame is kept for the
// next call), skips frames of ids nobody registered, by their size (the protocol's, or the one
// the simulator declares for each data frame it sends, such as a robot's extra sensor), and
// steps over bytes that are no frame id at all, so garbage on the line costs a few readings,
// never a hang.
#ifndef UNIMOUSE_SIM_SIMULATION_SENSORS_H_
#define UNIMOUSE_SIM_SIMULATION_SENSORS_H_

#include <Arduino.h>
#include <stdint.h>

#include "Devices.h"
#include "unimouse_protocol.h"

/// A sensor that the simulator sends frames for.
class ISimulationSensor {
 public:
  virtual uint8_t getId() const = 0;
  /// Takes a whole frame's payload (unimouse_payload_size(getId()) bytes).
  virtual void notify(const uint8_t* payload) = 0;

 protected:
  ~ISimulationSensor() = default;
};

class ISimulationSensorManager {
 public:
  /// Reads what has arrived and notifies sensors of every whole frame; returns at once.
  virtual void updateSensors() = 0;

 protected:
  ~ISimulationSensorManager() = default;
};

/// Reads frames from a Stream for up to N sensors.
template <uint8_t N>
class StreamSimulationSensorManager : public ISimulationSensorManager {
 public:
  explicit StreamSimulationSensorManager(Stream& stream) : stream_(stream) {}

  /// Registers a sensor; false when N are registered already.
  bool addSensor(ISimulationSensor& sensor) {
    if (count_ == N) return false;
    sensors_[count_++] = &sensor;
    return true;
  }

  void updateSensors() override {
    while (stream_.available() > 0) {
      const int next = stream_.read();
      if (next < 0) return;
      if (have_ == 0) {
        // a frame's id: sim -> MCU frames have a fixed size, the protocol's or the one the
        // simulator declared; anything else is not a frame
        const int size = payloadSize(static_cast<uint8_t>(next));
        if (size < 0 || size > static_cast<int>(sizeof(payload_))) {
          ++skippedBytes_;
          continue;
        }
        id_ = static_cast<uint8_t>(next);
        need_ = static_cast<uint8_t>(size);
        have_ = 1;
      } else {
        payload_[have_++ - 1] = static_cast<uint8_t>(next);
      }
      if (have_ == need_ + 1) {
        have_ = 0;
        deliver();
      }
    }
  }

  /// Payload bytes of a frame from the simulator: the protocol's (unimouse_payload_size), or
  /// what the simulator declared for a data frame of its send table (a frame size frame, sent
  /// when asked with UNIMOUSE_MANAGER_FRAME_SIZES: SimulationRobot::begin asks); -2 unknown.
  int payloadSize(uint8_t id) const {
    const int size = unimouse_payload_size(id);
    if (size != -2) return size;
    for (uint8_t i = 0; i < declaredCount_; ++i) {
      if (declared_[i][0] == id) return declared_[i][1];
    }
    return size;
  }

  /// Bytes stepped over because they could not start a frame.
  uint32_t skippedBytes() const { return skippedBytes_; }
  /// Whole frames of ids no sensor is registered for.
  uint32_t unclaimedFrames() const { return unclaimedFrames_; }

 private:
  void deliver() {
    if (id_ == UNIMOUSE_ID_FRAME_SIZE) {
      declare(payload_[0], payload_[1]);
      return;
    }
    for (uint8_t i = 0; i < count_; ++i) {
      if (sensors_[i]->getId() == id_) {
        sensors_[i]->notify(payload_);
        return;
      }
    }
    ++unclaimedFrames_;
  }

  // a data frame the protocol does not size itself (the ids it sizes keep their size)
  void declare(uint8_t id, uint8_t size) {
    if (unimouse_payload_size(id) != -2 || size > sizeof(payload_)) return;
    for (uint8_t i = 0; i < declaredCount_; ++i) {
      if (declared_[i][0] == id) {
        declared_[i][1] = size;
        return;
      }
    }
    if (declaredCount_ == kMaxDeclared) return;
    declared_[declaredCount_][0] = id;
    declared_[declaredCount_][1] = size;
    ++declaredCount_;
  }

  static const uint8_t kMaxDeclared = 8;
  Stream& stream_;
  ISimulationSensor* sensors_[N] = {};
  uint8_t declared_[kMaxDeclared][2] = {};  // id, payload bytes
  uint8_t declaredCount_ = 0;
  uint8_t count_ = 0;
  uint8_t id_ = 0, need_ = 0, have_ = 0;  // have_: bytes of the current frame, id included
  uint8_t payload_[8] = {};               // the longest sim -> MCU frame, maze info
  uint32_t skippedBytes_ = 0, unclaimedFrames_ = 0;
};

/// A time-of-flight sensor: the latest distance in metres.
class DistanceSensor : public ISimulationSensor, public IDistanceSensor {
 public:
  explicit DistanceSensor(uint8_t id) : id_(id) {}
  uint8_t getId() const override { return id_; }
  void notify(const uint8_t* payload) override {
    counts_ = unimouse_get_u16(payload);
    fresh_ = true;
  }
  /// Metres; UNIMOUSE_TOF_FULL_SCALE_M (1.2 m, table 3.8) when nothing is in range.
  float distance() const override {
    return static_cast<float>(unimouse_tof_to_metres(counts_, UNIMOUSE_TOF_FULL_SCALE_M));
  }
  /// Whether a reading came since the last call.
  bool hasNewData() {
    const bool f = fresh_;
    fresh_ = false;
    return f;
  }

 private:
  uint8_t id_;
  uint16_t counts_ = UNIMOUSE_TOF_NO_TARGET;
  bool fresh_ = false;
};

/// A wheel encoder: frames carry counts since the previous frame; this keeps a 32-bit running
/// total (the original's 16-bit one overflowed within seconds) and the counts since readReset.
class EncoderSensor : public ISimulationSensor, public IEncoder {
 public:
  explicit EncoderSensor(uint8_t id) : id_(id) {}
  uint8_t getId() const override { return id_; }
  void notify(const uint8_t* payload) override {
    const int16_t delta = static_cast<int16_t>(unimouse_get_u16(payload));
    total_ = static_cast<int32_t>(static_cast<uint32_t>(total_) +
                                  static_cast<uint32_t>(static_cast<int32_t>(delta)));
  }
  /// Counts since the start, wrapping around at 32 bits.
  int32_t count() const override { return total_; }
  /// Counts since the previous readReset.
  int32_t readReset() {
    const int32_t since =
        static_cast<int32_t>(static_cast<uint32_t>(total_) - static_cast<uint32_t>(read_));
    read_ = total_;
    return since;
  }

 private:
  uint8_t id_;
  int32_t total_ = 0, read_ = 0;
};

/// One axis of an IMU: the latest raw count of its data register (int16), as frames
/// UNIMOUSE_ID_GYRO_X..UNIMOUSE_ID_ACCEL_Z carry it.
class ImuAxisSensor : public ISimulationSensor {
 public:
  explicit ImuAxisSensor(uint8_t id) : id_(id) {}
  uint8_t getId() const override { return id_; }
  void notify(const uint8_t* payload) override {
    counts_ = static_cast<int16_t>(unimouse_get_u16(payload));
    fresh_ = true;
  }
  int16_t counts() const { return counts_; }
  /// Whether a reading came since the last call.
  bool hasNewData() {
    const bool f = fresh_;
    fresh_ = false;
    return f;
  }

 private:
  uint8_t id_;
  int16_t counts_ = 0;
  bool fresh_ = false;
};

/// A 6-axis IMU read through the link: raw counts, and the same in SI units at the chip's
/// sensitivities (LSB per dps and per g; 16.4 and 8192 are an ICM-20602's or MPU-6500's at
/// +-2000 dps and +-4 g, the gyro robot's settings).
class ImuSensor {
 public:
  explicit ImuSensor(float gyroLsbPerDps = 16.4f, float accelLsbPerG = 8192.0f)
      : gyroLsbPerDps_(gyroLsbPerDps), accelLsbPerG_(accelLsbPerG) {}
  /// Angular velocity about axis 0, 1, 2 (x, y, z), rad/s.
  float gyroRadPerS(uint8_t axis) const {
    return axes_[axis].counts() / gyroLsbPerDps_ * 0.017453292f;
  }
  /// Specific force along axis 0, 1, 2, m/s^2 (at rest and level, z reads +9.81).
  float accelMPerS2(uint8_t axis) const {
    return axes_[3 + axis].counts() / accelLsbPerG_ * 9.80665f;
  }
  /// The raw register counts of axis 0-2 (gyro) or 3-5 (accelerometer).
  int16_t counts(uint8_t axis) const { return axes_[axis].counts(); }
  ImuAxisSensor& axis(uint8_t i) { return axes_[i]; }

 private:
  float gyroLsbPerDps_, accelLsbPerG_;
  ImuAxisSensor axes_[6] = {ImuAxisSensor(UNIMOUSE_ID_GYRO_X),  ImuAxisSensor(UNIMOUSE_ID_GYRO_Y),
                            ImuAxisSensor(UNIMOUSE_ID_GYRO_Z),  ImuAxisSensor(UNIMOUSE_ID_ACCEL_X),
                            ImuAxisSensor(UNIMOUSE_ID_ACCEL_Y), ImuAxisSensor(UNIMOUSE_ID_ACCEL_Z)};
};

#endif  // UNIMOUSE_SIM_SIMULATION_SENSORS_H_
