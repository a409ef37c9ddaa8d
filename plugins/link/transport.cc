// SPDX-License-Identifier: GPL-3.0-or-later
#include "transport.h"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

// clang-format off
// Boost 1.74's asio uses std::exchange without including <utility> in C++20
#include <utility>
#include <boost/asio.hpp>
// clang-format on
#include <filesystem>

#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

namespace asio = boost::asio;
using boost::system::error_code;

bool WaitFd(int fd, std::chrono::milliseconds timeout) {
  pollfd p{fd, POLLIN, 0};
  return ::poll(&p, 1, static_cast<int>(timeout.count())) > 0 && (p.revents & POLLIN) != 0;
}

// errors that mean the peer is gone rather than busy
bool Lost(const error_code& ec) {
  return ec && ec != asio::error::would_block && ec != asio::error::try_again &&
         ec != asio::error::interrupted;
}

// reads and writes over any Asio stream in non-blocking mode
template <class Stream>
size_t ReadSome(Stream& s, std::vector<uint8_t>& out, bool& lost) {
  uint8_t buffer[4096];
  size_t total = 0;
  for (;;) {
    error_code ec;
    const size_t n = s.read_some(asio::buffer(buffer), ec);
    out.insert(out.end(), buffer, buffer + n);
    total += n;
    if (ec || n == 0) {
      lost = Lost(ec) || (!ec && n == 0);
      return total;
    }
  }
}

template <class Stream>
size_t WriteSome(Stream& s, std::span<const uint8_t> bytes, bool& lost) {
  error_code ec;
  const size_t n = s.write_some(asio::buffer(bytes.data(), bytes.size()), ec);
  lost = Lost(ec);
  return n;
}

// a pseudo-terminal: the simulator holds the master side, a client opens the slave path
class PtyTransport final : public Transport {
 public:
  explicit PtyTransport(const std::string& link_path) : stream_(io_), link_path_(link_path) {
    int master = -1, slave = -1;
    char name[256] = "";
    UNIMOUSE_THROW_UNLESS(::openpty(&master, &slave, name, nullptr, nullptr) == 0,
                          "cannot create a pseudo-terminal");
    // raw bytes both ways: no echo, no line editing, no CR/LF translation
    termios t{};
    ::tcgetattr(slave, &t);
    ::cfmakeraw(&t);
    ::tcsetattr(slave, TCSANOW, &t);
    ::close(slave);
    slave_path_ = name;
    stream_.assign(master);
    stream_.non_blocking(true);
    if (!link_path_.empty()) {
      std::error_code ec;
      std::filesystem::remove(link_path_, ec);
      std::filesystem::create_symlink(slave_path_, link_path_, ec);
      UNIMOUSE_THROW_UNLESS(!ec, link_path_ + ": cannot link it to the pty: " + ec.message());
    }
  }
  ~PtyTransport() override {
    // only our own link: another run may have taken the name since
    std::error_code ec;
    if (!link_path_.empty() && std::filesystem::read_symlink(link_path_, ec) == slave_path_) {
      std::filesystem::remove(link_path_, ec);
    }
  }

  void Read(std::vector<uint8_t>& out) override {
    bool lost = false;
    ReadSome(stream_, out, lost);
    // with no client on the slave side the master reads EIO; a client opening it ends that
    connected_ = !lost;
  }
  bool WaitReadable(std::chrono::milliseconds timeout) override {
    return WaitFd(stream_.native_handle(), timeout);
  }
  size_t Write(std::span<const uint8_t> bytes) override {
    bool lost = false;
    const size_t n = WriteSome(stream_, bytes, lost);
    if (lost) connected_ = false;
    return n;
  }
  bool Connected() const override { return connected_; }
  std::string Describe() const override {
    return "pty " + slave_path_ + (link_path_.empty() ? "" : " (also " + link_path_ + ")");
  }

 private:
  asio::io_context io_;
  asio::posix::stream_descriptor stream_;
  std::string slave_path_;
  std::string link_path_;
  bool connected_ = false;
};

// a serial port, reopened when it comes back after being unplugged
class SerialTransport final : public Transport {
 public:
  SerialTransport(std::string path, unsigned baud)
      : path_(std::move(path)), baud_(baud), port_(io_) {
    Open();
    UNIMOUSE_THROW_UNLESS(port_.is_open(),
                          path_ + ": cannot open the serial port (" + error_ + ")");
  }

  void Read(std::vector<uint8_t>& out) override {
    if (!port_.is_open() && !Open()) return;
    bool lost = false;
    ReadSome(stream_, out, lost);
    if (lost) Close();  // unplugged: reopened when it comes back
  }
  bool WaitReadable(std::chrono::milliseconds timeout) override {
    return port_.is_open() && WaitFd(stream_.native_handle(), timeout);
  }
  size_t Write(std::span<const uint8_t> bytes) override {
    if (!port_.is_open()) return 0;
    bool lost = false;
    const size_t n = WriteSome(stream_, bytes, lost);
    if (lost) Close();
    return n;
  }
  bool Connected() const override { return port_.is_open(); }
  std::string Describe() const override {
    return "serial port " + path_ + " at " + std::to_string(baud_) + " baud, 8N1";
  }

 private:
  bool Open() {
    // retry at most twice a second of wall time while the port is gone
    const auto now = std::chrono::steady_clock::now();
    if (now - last_try_ < std::chrono::milliseconds(500)) return false;
    last_try_ = now;
    error_code ec;
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
    stream_.assign(::dup(port_.native_handle()));
    stream_.non_blocking(true);
    return true;
  }
  void Close() {
    error_code ec;
    stream_.close(ec);
    port_.close(ec);
  }

  std::string path_;
  unsigned baud_;
  asio::io_context io_;
  asio::serial_port port_;
  asio::posix::stream_descriptor stream_{io_};
  std::string error_;
  std::chrono::steady_clock::time_point last_try_{};
};

// a TCP server taking one client at a time
class TcpTransport final : public Transport {
 public:
  TcpTransport(const std::string& host, unsigned short port) : acceptor_(io_), socket_(io_) {
    error_code ec;
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

  void Read(std::vector<uint8_t>& out) override {
    if (!socket_.is_open() && !Accept()) return;
    bool lost = false;
    ReadSome(socket_, out, lost);
    if (lost) Drop();
  }
  bool WaitReadable(std::chrono::milliseconds timeout) override {
    return socket_.is_open() && WaitFd(socket_.native_handle(), timeout);
  }
  size_t Write(std::span<const uint8_t> bytes) override {
    if (!socket_.is_open() && !Accept()) return 0;
    bool lost = false;
    const size_t n = WriteSome(socket_, bytes, lost);
    if (lost) Drop();
    return n;
  }
  bool Connected() const override { return socket_.is_open(); }
  std::string Describe() const override { return "TCP server on port " + std::to_string(port_); }

 private:
  bool Accept() {
    error_code ec;
    acceptor_.accept(socket_, ec);
    if (ec) return false;
    socket_.non_blocking(true, ec);
    socket_.set_option(asio::ip::tcp::no_delay(true), ec);
    return true;
  }
  void Drop() {
    error_code ec;
    socket_.close(ec);
  }

  asio::io_context io_;
  asio::ip::tcp::acceptor acceptor_;
  asio::ip::tcp::socket socket_;
  unsigned short port_ = 0;
};

// a firmware program on this machine, talking on its stdin and stdout; stopped with the run
class NativeTransport final : public Transport {
 public:
  explicit NativeTransport(const std::string& command) : command_(command), stream_(io_) {
    UNIMOUSE_THROW_UNLESS(!command.empty(), "native needs a program: native:PATH");
    const std::string program = command.substr(0, command.find(' '));
    UNIMOUSE_THROW_UNLESS(::access(program.c_str(), X_OK) == 0,
                          program + ": no such program, or it cannot be run");
    int sockets[2];
    UNIMOUSE_THROW_UNLESS(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) == 0,
                          "cannot make a socket pair for the firmware");
    child_ = ::fork();
    if (child_ == 0) {
      ::dup2(sockets[1], 0);
      ::dup2(sockets[1], 1);
      // words of the command become the arguments; no shell in between
      std::vector<std::string> words;
      for (size_t at = 0; at < command.size();) {
        const size_t end = std::min(command.find(' ', at), command.size());
        if (end > at) words.push_back(command.substr(at, end - at));
        at = end + 1;
      }
      std::vector<char*> argv;
      for (auto& w : words) argv.push_back(w.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(sockets[1]);
    UNIMOUSE_THROW_UNLESS(child_ > 0, "cannot start " + program);
    stream_.assign(sockets[0]);
    stream_.non_blocking(true);
  }
  ~NativeTransport() override {
    // a firmware never ends by itself: ask it to stop, then insist
    error_code ec;
    stream_.close(ec);
    if (child_ <= 0) return;
    ::kill(child_, SIGTERM);
    for (int i = 0; i < 100; ++i) {
      if (::waitpid(child_, nullptr, WNOHANG) == child_) return;
      ::usleep(10000);
    }
    ::kill(child_, SIGKILL);
    ::waitpid(child_, nullptr, 0);
  }

  void Read(std::vector<uint8_t>& out) override {
    if (!connected_) return;
    bool lost = false;
    ReadSome(stream_, out, lost);
    if (lost) connected_ = false;  // it exited or closed its output
  }
  bool WaitReadable(std::chrono::milliseconds timeout) override {
    return connected_ && WaitFd(stream_.native_handle(), timeout);
  }
  size_t Write(std::span<const uint8_t> bytes) override {
    if (!connected_) return 0;
    bool lost = false;
    const size_t n = WriteSome(stream_, bytes, lost);
    if (lost) connected_ = false;
    return n;
  }
  bool Connected() const override { return connected_; }
  std::string Describe() const override {
    return "firmware process " + command_ + " (pid " + std::to_string(child_) + ")";
  }

 private:
  std::string command_;
  asio::io_context io_;
  asio::posix::stream_descriptor stream_;
  pid_t child_ = -1;
  bool connected_ = true;
};

}  // namespace

std::unique_ptr<Transport> OpenTransport(const std::string& spec) {
  const size_t colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (kind == "pty") return std::make_unique<PtyTransport>(rest);
  if (kind == "native") return std::make_unique<NativeTransport>(rest);
  if (kind == "serial") {
    const size_t at = rest.rfind('@');
    UNIMOUSE_THROW_UNLESS(!rest.empty(), "serial needs a device: serial:/dev/ttyUSB0@115200");
    unsigned baud = 115200;
    if (at != std::string::npos) {
      try {
        baud = static_cast<unsigned>(std::stoul(rest.substr(at + 1)));
      } catch (const std::exception&) {
        throw InputError("serial: '" + rest.substr(at + 1) + "' is not a baud rate");
      }
    }
    return std::make_unique<SerialTransport>(rest.substr(0, at), baud);
  }
  if (kind == "tcp") {
    const size_t port_at = rest.rfind(':');
    UNIMOUSE_THROW_UNLESS(port_at != std::string::npos, "tcp needs a port: tcp::5760");
    unsigned long port = 0;
    try {
      port = std::stoul(rest.substr(port_at + 1));
    } catch (const std::exception&) {
      throw InputError("tcp: '" + rest.substr(port_at + 1) + "' is not a port number");
    }
    UNIMOUSE_THROW_UNLESS(port < 65536, "tcp: port " + std::to_string(port) + " is out of range");
    return std::make_unique<TcpTransport>(rest.substr(0, port_at),
                                          static_cast<unsigned short>(port));
  }
  throw InputError("unknown link '" + spec +
                   "': pty, pty:LINK, serial:PATH@BAUD, tcp::PORT or native:PROGRAM");
}

}  // namespace unimouse::link
