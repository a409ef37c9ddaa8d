// SPDX-License-Identifier: GPL-3.0-or-later
// Byte transports for the link: a pseudo-terminal whose path a board emulator or terminal
// program opens, a real serial port, a TCP server, a firmware process on this machine. All
// non-blocking: the simulation never waits on a board except in lock-step, and then only up to a
// timeout. One table lists them (transports.cc, transport_spec.h); each lives in its own source
// file. This library is the link plugin's, and the host's where it needs to know a transport
// (a run's record, batch manifests, mms's boards).
#ifndef UNIMOUSE_TRANSPORT_TRANSPORT_H_
#define UNIMOUSE_TRANSPORT_TRANSPORT_H_

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "transport_spec.h"

namespace unimouse::link {

class Transport {
 public:
  virtual ~Transport() = default;
  /// Appends up to `max_bytes` of the bytes available now; never waits. Notices a lost peer
  /// and tries to get it back (a reopened pty, a replugged port, a new TCP client).
  virtual void Read(std::vector<uint8_t>& out, size_t max_bytes) = 0;
  /// Waits up to `timeout` for bytes to read; false on timeout or without a peer.
  virtual bool WaitReadable(std::chrono::milliseconds timeout) = 0;
  /// Writes what the peer takes now; returns how many bytes went.
  virtual size_t Write(std::span<const uint8_t> bytes) = 0;
  /// Returns whether a peer is there to talk to.
  virtual bool Connected() const = 0;
  /// Returns how many peers the transport has had so far (TCP clients accepted, a port
  /// plugged in again, a pty's other side speaking after it had none), so that a peer that
  /// came and went within one Read is still seen; 0 for a transport that does not count them.
  virtual uint64_t peers() const { return 0; }
  /// Returns one line for the console: what it is and where to connect.
  virtual std::string Describe() const = 0;
  /// Returns the line's own rate in baud (10 bits a byte), or 0 when it has none.
  virtual int line_baud() const { return 0; }
  /// Returns whether the firmware is to set the pace from the first step, as a program the
  /// simulator starts itself does: the first step waits until it asks for lock-step.
  virtual bool lockstep_from_start() const { return false; }
  /// Takes what the link's parameters say about the peer, before the first step; the emulated
  /// board loads its image here (throws InputError).
  virtual void Configure(const struct TransportSettings& /*settings*/) {}
  /// Returns whether the transport carries the firmware's own clock (an emulated board): then
  /// the link runs it for each step with RunUntil and never waits for it.
  virtual bool clocked() const { return false; }
  /// Runs a clocked peer until simulated time `time_s`: what was written goes in at its line's
  /// pace and what it sends meanwhile can be read after. Returns "", or why the firmware cannot
  /// go on (a crash, say), which ends the run.
  virtual std::string RunUntil(double /*time_s*/) { return ""; }
  /// Returns a line of what the transport measured over the run, for the link's last line.
  virtual std::string Summary() const { return ""; }
  /// Returns the same as named numbers, each with its unit in its name, for the run's record.
  virtual std::vector<std::pair<std::string, double>> Measurements() const { return {}; }
  /// Returns why the firmware ended for good (it crashed, called exit(), hung), or "" while it
  /// runs or when the transport cannot tell.
  virtual std::string Failure() const { return ""; }
  /// Appends the whole lines the firmware printed outside the protocol since the last call (a
  /// program's standard error); never waits.
  virtual void TakeText(std::vector<std::string>& /*lines*/) {}
  /// Returns what reset the firmware's board since the last call ("the watchdog", "a brown-out
  /// at reset_at_s"), oldest first: only an emulated board sees its resets; others show them
  /// by the firmware's start-up frames (docs/protocol.md, "Restarts").
  virtual std::vector<std::string> TakeResets() { return {}; }
  /// Returns, once each, what the user should know of the line since the last call (an
  /// emulated board losing bytes).
  virtual std::vector<std::string> TakeNotices() { return {}; }
  /// Hands an IMU on the board's bus (TransportSettings::spi_imu_part) what it measures now:
  /// gyro x, y, z in rad/s, then accelerometer x, y, z in m/s^2. Other transports ignore it.
  virtual void SetImuReading(std::span<const double, 6> /*gyro_then_accel*/) {}
};

/// What the link's parameters tell a transport beyond its spec.
struct TransportSettings {
  std::string mcu;             ///< avr: the part, unless the image names its own
  double f_cpu_hz = 0;         ///< avr: the clock, unless the image names its own
  std::string spi_imu_part;    ///< avr: an IMU chip on the SPI bus (mpu6500, icm20602), or ""
  std::string spi_imu_cs_pin;  ///< avr: its chip-select pin, "PB0"
  bool resets_restart = true;  ///< avr: a reset boots the firmware again; false: it ends the run
  double reset_at_s = 0;       ///< avr: reset the board at this simulated time; 0: never
  std::string reset_cause;     ///< avr: what that reset is, "external" or "brownout"
};

/// Returns "" when `part` is an IMU the emulated board's SPI bus can carry (mpu6500, icm20602),
/// else why not.
std::string SpiImuPartProblem(const std::string& part);
/// Returns "" when `pin` (port and bit, "PB0") is a pin of `mcu`, else why not.
std::string PinProblem(const std::string& mcu, const std::string& pin);

/// Returns a signal that ended a firmware, named for a student: "SIGFPE (division by zero?)".
std::string FirmwareSignalText(int sig);

/// Opens a transport from its spec, "SCHEME" or "SCHEME:REST". Throws InputError.
std::unique_ptr<Transport> OpenTransport(const std::string& spec);

}  // namespace unimouse::link

#endif  // UNIMOUSE_TRANSPORT_TRANSPORT_H_
