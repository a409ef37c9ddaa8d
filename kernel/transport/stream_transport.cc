// SPDX-License-Identifier: GPL-3.0-or-later
#include "stream_transport.h"

#include <poll.h>

#include <algorithm>

namespace unimouse::link {
namespace {

// errors that mean the peer is gone rather than busy
bool Lost(const boost::system::error_code& ec) {
  return ec && ec != asio::error::would_block && ec != asio::error::try_again &&
         ec != asio::error::interrupted;
}

}  // namespace

void StreamTransport::Adopt(int fd) {
  boost::system::error_code ec;
  stream_.close(ec);
  stream_.assign(fd);
  stream_.non_blocking(true);
  connected_ = true;
  ++peers_;
}

void StreamTransport::CloseStream() {
  boost::system::error_code ec;
  stream_.close(ec);
}

void StreamTransport::Settle(bool lost) {
  connected_ = !lost;
  if (lost) Drop();
}

void StreamTransport::Read(std::vector<uint8_t>& out, size_t max_bytes) {
  const bool had_peer = connected_;
  const uint64_t peers_before = peers_;
  if (max_bytes == 0 || (!connected_ && !Reconnect()) || !stream_.is_open()) return;
  uint8_t buffer[4096];
  size_t total = 0;
  bool lost = false;
  while (total < max_bytes) {
    boost::system::error_code ec;
    const size_t n =
        stream_.read_some(asio::buffer(buffer, std::min(sizeof(buffer), max_bytes - total)), ec);
    out.insert(out.end(), buffer, buffer + n);
    total += n;
    if (ec || n == 0) {
      // an end of file without an error is a peer gone too
      lost = Lost(ec) || (!ec && n == 0);
      break;
    }
  }
  // a stream that stays open for the next peer (a pty) has a new one when bytes come again
  if (!had_peer && peers_ == peers_before && total > 0) ++peers_;
  Settle(lost);
}

bool StreamTransport::WaitReadable(std::chrono::milliseconds timeout) {
  if (!stream_.is_open()) return false;
  pollfd p{stream_.native_handle(), POLLIN, 0};
  return ::poll(&p, 1, static_cast<int>(timeout.count())) > 0 && (p.revents & POLLIN) != 0;
}

size_t StreamTransport::Write(std::span<const uint8_t> bytes) {
  if ((!connected_ && !Reconnect()) || !stream_.is_open()) return 0;
  boost::system::error_code ec;
  const size_t n = stream_.write_some(asio::buffer(bytes.data(), bytes.size()), ec);
  if (Lost(ec)) Settle(true);
  return n;
}

}  // namespace unimouse::link
