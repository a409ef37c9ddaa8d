// SPDX-License-Identifier: GPL-3.0-or-later
// Byte transports for the link, on Boost.Asio: a pseudo-terminal whose path a board emulator or
// terminal program opens, a real serial port, a TCP server, a firmware process on this machine.
// All non-blocking: the simulation
// never waits on a board except in lock-step, and then only up to a timeout.
#ifndef UNIMOUSE_PLUGINS_LINK_TRANSPORT_H_
#define UNIMOUSE_PLUGINS_LINK_TRANSPORT_H_

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace unimouse::link {

class Transport {
 public:
  virtual ~Transport() = default;
  /// Appends the bytes available now; never waits. Notices a lost peer and tries to get it
  /// back (a reopened pty, a replugged port, a new TCP client).
  virtual void Read(std::vector<uint8_t>& out) = 0;
  /// Waits up to `timeout` for bytes to read; false on timeout or without a peer.
  virtual bool WaitReadable(std::chrono::milliseconds timeout) = 0;
  /// Writes what the peer takes now; returns how many bytes went.
  virtual size_t Write(std::span<const uint8_t> bytes) = 0;
  /// Whether a peer is there to talk to.
  virtual bool Connected() const = 0;
  /// One line for the console: what it is and where to connect.
  virtual std::string Describe() const = 0;
  /// Whether the transport carries the firmware's own clock (an emulated board): then the link
  /// runs it for each step with RunUntil instead of waiting for it.
  virtual bool clocked() const { return false; }
  /// Runs a clocked peer until simulated time `time_s`: what was written goes in at its line's
  /// pace and what it sends meanwhile can be read after. Returns "", or why the firmware cannot
  /// go on (a crash, say), which ends the run.
  virtual std::string RunUntil(double /*time_s*/) { return ""; }
  /// Returns a line of what the transport measured over the run, for the link's last line.
  virtual std::string Summary() const { return ""; }
};

/// Opens the emulated board: the image at `path` on an emulated `mcu` at `f_cpu_hz`, unless the
/// image names its own (avr_transport.cc; throws InputError without simavr in the build).
std::unique_ptr<Transport> OpenAvrBoard(const std::string& path, const std::string& mcu,
                                        double f_cpu_hz);

/// Opens a transport from its spec: "pty" or "pty:LINK" (a symlink to the pty for convenience),
/// "serial:PATH@BAUD", "tcp::PORT" or "tcp:HOST:PORT", or "native:PROGRAM [ARGS]" (a firmware
/// program talking on its stdin and stdout, stopped when the link goes). Throws InputError.
std::unique_ptr<Transport> OpenTransport(const std::string& spec);

}  // namespace unimouse::link

#endif  // UNIMOUSE_PLUGINS_LINK_TRANSPORT_H_
