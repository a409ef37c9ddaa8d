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
};

/// Opens a transport from its spec: "pty" or "pty:LINK" (a symlink to the pty for convenience),
/// "serial:PATH@BAUD", "tcp::PORT" or "tcp:HOST:PORT", or "native:PROGRAM [ARGS]" (a firmware
/// program talking on its stdin and stdout, stopped when the link goes). Throws InputError.
std::unique_ptr<Transport> OpenTransport(const std::string& spec);

}  // namespace unimouse::link

#endif  // UNIMOUSE_PLUGINS_LINK_TRANSPORT_H_
