// SPDX-License-Identifier: MIT
// Frames from the firmware to the simulator (dissertation tables 3.10 and 3.11): an actuator
// manager writes whole frames to a Stream; motors send their command when it changes and again
// every resend period, so the simulator's failsafe (no command for 100 ms stops the motors) never
// trips while the firmware runs, and a command survives a reset of the simulated robot; the
// logger's text can never break the framing, as it ends at its first 0x00 and is cut at
// UNIMOUSE_LOG_MAX bytes. Nothing else may write to the Stream: Serial.print would corrupt it.
#ifndef UNIMOUSE_SIM_SIMULATION_ACTUATORS_H_
#define UNIMOUSE_SIM_SIMULATION_ACTUATORS_H_

#include <Arduino.h>
#include <stdint.h>

#include "Devices.h"

/// millis() as the library reads it, counted in 32 bits as on boards; on the PC a read the
/// core never takes for a sketch spinning on the clock (pc/clock.cc).
inline uint32_t unimouseLibraryMillis() {
#ifdef UNIMOUSE_PC_CORE
  return static_cast<uint32_t>(unimousePcLibraryMillis());
#else
  return static_cast<uint32_t>(millis());
#endif
}
#include "unimouse_protocol.h"

class IActuatorManager {
 public:
  /// Sends one whole frame: the id, then `size` payload bytes.
  virtual void send(uint8_t id, const uint8_t* payload, uint16_t size) = 0;
  /// Sends a text frame: the id, the text up to its first 0x00 or UNIMOUSE_LOG_MAX bytes, 0x00.
  virtual void sendText(uint8_t id, const char* text) = 0;

 protected:
  ~IActuatorManager() = default;
};

class StreamActuatorManager : public IActuatorManager {
 public:
  explicit StreamActuatorManager(Stream& stream) : stream_(stream) {}
  void send(uint8_t id, const uint8_t* payload, uint16_t size) override {
    stream_.write(id);
    if (size > 0) stream_.write(payload, size);
  }
  void sendText(uint8_t id, const char* text) override {
    uint16_t n = 0;
    while (text[n] != '\0' && n < UNIMOUSE_LOG_MAX) ++n;
    stream_.write(id);
    stream_.write(reinterpret_cast<const uint8_t*>(text), n);
    stream_.write(static_cast<uint8_t>(0));
  }

 private:
  Stream& stream_;
};

/// An H-bridge command: -1023..1023, the sign for the direction (10 bits and a sign, table 4.6).
class MotorActuator : public IMotor {
 public:
  static const uint16_t kResendMs = 50;  // half the simulator's 100 ms failsafe

  MotorActuator(IActuatorManager& manager, uint8_t id) : manager_(manager), id_(id) {}

  /// Sets the command (clamped), sending it at once if it changed.
  void setCommand(int32_t command, uint32_t nowMs) {
    const int16_t c = unimouse_clamp_motor(command);
    if (c != command_ || !sent_) {
      command_ = c;
      send(nowMs);
    }
  }
  /// Sets the command at the board's millis().
  void setCommand(int32_t command) override { setCommand(command, unimouseLibraryMillis()); }
  int16_t getCommand() const { return command_; }
  /// Sends the command again if it has not been sent for kResendMs.
  void refresh(uint32_t nowMs) {
    if (sent_ && nowMs - sentAtMs_ >= kResendMs) send(nowMs);
  }

 private:
  void send(uint32_t nowMs) {
    uint8_t payload[2];
    unimouse_put_u16(payload, static_cast<uint16_t>(command_));
    manager_.send(id_, payload, 2);
    sent_ = true;
    sentAtMs_ = nowMs;
  }

  IActuatorManager& manager_;
  uint8_t id_;
  int16_t command_ = 0;
  bool sent_ = false;
  uint32_t sentAtMs_ = 0;
};

/// Text for the simulator's log: one line a call.
class SimulationLogger {
 public:
  explicit SimulationLogger(IActuatorManager& manager) : manager_(manager) {}

  void log(const char* text) { manager_.sendText(UNIMOUSE_ID_LOG, text); }

 private:
  IActuatorManager& manager_;
};

#endif  // UNIMOUSE_SIM_SIMULATION_ACTUATORS_H_
