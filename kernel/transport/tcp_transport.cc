// SPDX-License-Identifier: GPL-3.0-or-later
// A TCP server taking one client at a time: boards on Wi-Fi, remote labs.
#include "stream_transport.h"
#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

class TcpTransport final : public StreamTransport {
 public:
  TcpTransport(const std::string& host, unsigned short port) {
    boost::system::error_code ec;
    const auto address = asio::ip::make_address(host.empty() ? "0.0.0.0" : host, ec);
    UNIMOUSE_THROW_UNLESS(!ec, "tcp: '" + host + "' is not an IP address");
    const asio::ip::tcp::endpoint endpoint(address, port);
    acceptor_.open(endpoint.protocol(), ec);
    acceptor_.set_option(asio::socket_base::reuse_address(true), ec);
    acceptor_.bind(endpoint, ec);
    UNIMOUSE_THROW_UNLESS(
        !ec, "tcp: cannot listen on port " + std::to_string(port) + ": " + ec.message());
    acceptor_.listen(1, ec);
    acceptor_.non_blocking(true, ec);
    port_ = acceptor_.local_endpoint(ec).port();
  }

  std::string Describe() const override { return "TCP server on port " + std::to_string(port_); }

 protected:
  bool Reconnect() override {
    boost::system::error_code ec;
    asio::ip::tcp::socket client(io());
    acceptor_.accept(client, ec);
    if (ec) return false;
    client.set_option(asio::ip::tcp::no_delay(true), ec);
    Adopt(client.release(ec));
    return true;
  }

 private:
  asio::ip::tcp::acceptor acceptor_{io()};
  unsigned short port_ = 0;
};

}  // namespace

std::unique_ptr<Transport> OpenTcp(const std::string& rest) {
  const size_t port_at = rest.rfind(':');
  UNIMOUSE_THROW_UNLESS(port_at != std::string::npos, "tcp needs a port: tcp::5760");
  const std::string text = rest.substr(port_at + 1);
  const bool digits = !text.empty() && text.size() <= 5 &&
                      text.find_first_not_of("0123456789") == std::string::npos;
  UNIMOUSE_THROW_UNLESS(digits, "tcp: '" + text + "' is not a port number");
  const unsigned long port = std::stoul(text);
  UNIMOUSE_THROW_UNLESS(port < 65536, "tcp: port " + text + " is out of range");
  return std::make_unique<TcpTransport>(rest.substr(0, port_at), static_cast<unsigned short>(port));
}

}  // namespace unimouse::link
