// SPDX-License-Identifier: GPL-3.0-or-later
// What every transport shares: one Asio stream descriptor, read and written without blocking,
// a wait for bytes with a timeout, and the bookkeeping of a peer that comes and goes. A
// transport adds how it opens, how it gets a lost peer back and how it lets one go.
#ifndef UNIMOUSE_TRANSPORT_STREAM_TRANSPORT_H_
#define UNIMOUSE_TRANSPORT_STREAM_TRANSPORT_H_

// clang-format off
// Boost 1.74's asio uses std::exchange without including <utility> in C++20
#include <utility>
#include <boost/asio.hpp>
// clang-format on

#include "transport.h"

namespace unimouse::link {

namespace asio = boost::asio;

/// A transport over one stream descriptor: a pty master, a serial line, a TCP client, a socket
/// to a child process.
class StreamTransport : public Transport {
 public:
  StreamTransport(const StreamTransport&) = delete;
  StreamTransport& operator=(const StreamTransport&) = delete;
  ~StreamTransport() override = default;

  void Read(std::vector<uint8_t>& out, size_t max_bytes) final;
  bool WaitReadable(std::chrono::milliseconds timeout) final;
  size_t Write(std::span<const uint8_t> bytes) final;
  bool Connected() const final { return connected_; }
  uint64_t peers() const final { return peers_; }

 protected:
  StreamTransport() = default;

  /// Returns the I/O context the transport's other Asio objects use.
  asio::io_context& io() { return io_; }
  /// Takes `fd` as the stream, non-blocking, with a peer on it.
  void Adopt(int fd);
  /// Closes the stream, if open.
  void CloseStream();
  /// Tries to get a peer back when there is none; returns whether the stream may now reach
  /// one. A transport that cannot get one back keeps this default.
  virtual bool Reconnect() { return false; }
  /// Lets go of a lost peer; by default closes the stream.
  virtual void Drop() { CloseStream(); }

 private:
  // notes how the last read or write went
  void Settle(bool lost);

  asio::io_context io_;
  asio::posix::stream_descriptor stream_{io_};
  bool connected_ = false;
  uint64_t peers_ = 0;
};

}  // namespace unimouse::link

#endif  // UNIMOUSE_TRANSPORT_STREAM_TRANSPORT_H_
