// SPDX-License-Identifier: GPL-3.0-or-later
// A pseudo-terminal: the simulator holds the master side, a board emulator or terminal program
// opens the slave path.
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <filesystem>

#include "stream_transport.h"
#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

class PtyTransport final : public StreamTransport {
 public:
  explicit PtyTransport(const std::string& link_path) : link_path_(link_path) {
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
    Adopt(master);
    if (!link_path_.empty()) {
      namespace fs = std::filesystem;
      std::error_code ec;
      // only a link left by an earlier run (to a pseudo-terminal) makes way; anything else at
      // that path is someone's file
      const fs::file_status status = fs::symlink_status(link_path_, ec);
      if (fs::exists(status)) {
        const bool ours = fs::is_symlink(status) &&
                          fs::read_symlink(link_path_, ec).string().rfind("/dev/pts/", 0) == 0;
        if (!ours) {
          throw InputError(link_path_ +
                           ": exists and is not a link to a pseudo-terminal; not replaced");
        }
        fs::remove(link_path_, ec);
      }
      fs::create_symlink(slave_path_, link_path_, ec);
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

  std::string Describe() const override {
    return "pty " + slave_path_ + (link_path_.empty() ? "" : " (also " + link_path_ + ")");
  }

 protected:
  // with no client on the slave side the master reads EIO; a client opening it ends that, so
  // the master stays open and every read asks again
  bool Reconnect() override { return true; }
  void Drop() override {}

 private:
  std::string slave_path_;
  std::string link_path_;
};

}  // namespace

std::unique_ptr<Transport> OpenPty(const std::string& link_path) {
  return std::make_unique<PtyTransport>(link_path);
}

}  // namespace unimouse::link
