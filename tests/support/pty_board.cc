// SPDX-License-Identifier: GPL-3.0-or-later
#include "pty_board.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "unimouse_protocol.h"

namespace unimouse::testing {

void PtyBoard::Open(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  EXPECT_GE(fd_, 0) << path << ": " << std::strerror(errno);
  termios t{};
  ::tcgetattr(fd_, &t);
  ::cfmakeraw(&t);
  ::tcsetattr(fd_, TCSANOW, &t);
}

void PtyBoard::Close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void PtyBoard::Send(std::vector<uint8_t> bytes) {
  ASSERT_EQ(::write(fd_, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
}

void PtyBoard::Motors(int16_t left, int16_t right) {
  uint8_t f[6] = {UNIMOUSE_ID_MOTOR_LEFT, 0, 0, UNIMOUSE_ID_MOTOR_RIGHT, 0, 0};
  unimouse_put_u16(f + 1, static_cast<uint16_t>(left));
  unimouse_put_u16(f + 4, static_cast<uint16_t>(right));
  Send({f, f + 6});
}

std::vector<uint8_t> PtyBoard::Bytes() {
  std::vector<uint8_t> bytes;
  uint8_t buffer[4096];
  ssize_t n;
  while ((n = ::read(fd_, buffer, sizeof(buffer))) > 0)
    bytes.insert(bytes.end(), buffer, buffer + n);
  return bytes;
}

std::map<int, int> PtyBoard::Drain() {
  const std::vector<uint8_t> bytes = Bytes();
  std::map<int, int> ids;
  for (size_t i = 0; i < bytes.size(); i += 1 + unimouse_payload_size(bytes[i])) ++ids[bytes[i]];
  return ids;
}

}  // namespace unimouse::testing
