// SPDX-License-Identifier: GPL-3.0-or-later
// A serial port, 8N1, no flow control; reopened when it comes back after being unplugged.
#include <termios.h>
#include <unistd.h>

#include "stream_transport.h"
#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

class SerialTransport final : public StreamTransport {
 public:
  SerialTransport(std::string path, unsigned baud) : path_(std::move(path)), baud_(baud) {
    Reconnect();
    UNIMOUSE_THROW_UNLESS(port_.is_open(),
                          path_ + ": cannot open the serial port (" + error_ + ")");
  }

  std::string Describe() const override {
    return "serial port " + path_ + " at " + std::to_string(baud_) + " baud, 8N1";
  }
  int line_baud() const override { return static_cast<int>(baud_); }

 protected:
  bool Reconnect() override {
    // retry at most twice a second of wall time while the port is gone
    const auto now = std::chrono::steady_clock::now();
    if (now - last_try_ < std::chrono::milliseconds(500)) return false;
    last_try_ = now;
    boost::system::error_code ec;
    port_.open(path_, ec);
    if (ec) {
      error_ = ec.message();
      return false;
    }
    port_.set_option(asio::serial_port::baud_rate(baud_), ec);
    port_.set_option(asio::serial_port::character_size(8), ec);
    port_.set_option(asio::serial_port::parity(asio::serial_port::parity::none), ec);
    port_.set_option(asio::serial_port::stop_bits(asio::serial_port::stop_bits::one), ec);
    port_.set_option(asio::serial_port::flow_control(asio::serial_port::flow_control::none), ec);
    termios t{};
    ::tcgetattr(port_.native_handle(), &t);
    ::cfmakeraw(&t);
    ::tcsetattr(port_.native_handle(), TCSANOW, &t);
    // Boost 1.74's serial_port reads block however its descriptor is set: configured through
    // serial_port, the port is read and written through a stream descriptor on the same line
    Adopt(::dup(port_.native_handle()));
    return true;
  }
  void Drop() override {
    // unplugged: reopened when it comes back
    CloseStream();
    boost::system::error_code ec;
    port_.close(ec);
  }

 private:
  std::string path_;
  unsigned baud_;
  asio::serial_port port_{io()};
  std::string error_;
  std::chrono::steady_clock::time_point last_try_{};
};

}  // namespace

int SerialLineBaud(const std::string& rest) {
  const size_t at = rest.rfind('@');
  if (at == std::string::npos) return 115200;
  const std::string text = rest.substr(at + 1);
  const bool digits = !text.empty() && text.size() <= 8 &&
                      text.find_first_not_of("0123456789") == std::string::npos;
  UNIMOUSE_THROW_UNLESS(digits && std::stoul(text) > 0,
                        "serial: '" + text + "' is not a baud rate");
  return static_cast<int>(std::stoul(text));
}

std::unique_ptr<Transport> OpenSerial(const std::string& rest) {
  UNIMOUSE_THROW_UNLESS(!rest.empty(), "serial needs a device: serial:/dev/ttyUSB0@115200");
  const auto baud = static_cast<unsigned>(SerialLineBaud(rest));
  return std::make_unique<SerialTransport>(rest.substr(0, rest.rfind('@')), baud);
}

}  // namespace unimouse::link
