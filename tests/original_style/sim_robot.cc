// SPDX-License-Identifier: GPL-3.0-or-later
#include "sim_robot.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>

SerialPort Serial;

namespace {

const auto kStart = std::chrono::steady_clock::now();

// frame ids of the original; a simulator it talks to never sends an id above the sensors
constexpr int kSensorIds = 5;
constexpr uint8_t kManagerId = 7;
constexpr uint8_t kEnableSensors = 0x02;
constexpr uint8_t kLogId = 8;

[[noreturn]] void Quit(const char* why) {
  std::fprintf(stderr, "firmware: %s\n", why);
  std::exit(0);
}

}  // namespace

unsigned long millis() {
  return static_cast<unsigned long>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                        std::chrono::steady_clock::now() - kStart)
                                        .count());
}

void SerialPort::Open(const char* device, int wait_ms) {
  // a simulator that has gone away is noticed on reading, not by a signal on writing
  ::signal(SIGPIPE, SIG_IGN);
  if (device == nullptr) return;
  // the simulator makes the device when it starts: it may not be there yet
  const unsigned long until = millis() + static_cast<unsigned long>(wait_ms);
  int fd = -1;
  while ((fd = ::open(device, O_RDWR | O_NOCTTY)) < 0 && millis() < until) ::usleep(20000);
  if (fd < 0) {
    std::fprintf(stderr, "firmware: %s: %s\n", device, std::strerror(errno));
    std::exit(2);
  }
  // raw bytes: no echo, no line editing, no CR/LF translation
  termios t{};
  if (::tcgetattr(fd, &t) == 0) {
    ::cfmakeraw(&t);
    ::cfsetspeed(&t, B115200);
    ::tcsetattr(fd, TCSANOW, &t);
  }
  in_fd_ = out_fd_ = fd;
}

void SerialPort::Fill(int timeout_ms) {
  if (head_ > 0 && tail_ == sizeof(buffer_)) {
    std::memmove(buffer_, buffer_ + head_, tail_ - head_);
    tail_ -= head_;
    head_ = 0;
  }
  if (head_ == tail_) head_ = tail_ = 0;
  if (tail_ == sizeof(buffer_)) return;
  pollfd p{in_fd_, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) <= 0 || p.revents == 0) return;
  const ssize_t n = ::read(in_fd_, buffer_ + tail_, sizeof(buffer_) - tail_);
  if (n > 0) {
    tail_ += static_cast<size_t>(n);
  } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
    Quit("the simulator has gone away");
  }
}

int SerialPort::available() {
  Fill(0);
  return static_cast<int>(tail_ - head_);
}

int SerialPort::read() { return available() > 0 ? buffer_[head_++] : -1; }

void SerialPort::write(const uint8_t* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(out_fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) Quit("the simulator has gone away");
    data += n;
    size -= static_cast<size_t>(n);
  }
}

bool SerialPort::WaitReadable(int timeout_ms) {
  const size_t before = tail_ - head_;
  Fill(timeout_ms);
  return tail_ - head_ > before;
}

void SimRobot::initialize() {
  const uint8_t enable[2] = {kManagerId, kEnableSensors};
  Serial.write(enable, sizeof(enable));
  while (!(tof_seen_[0] && tof_seen_[1] && tof_seen_[2])) update();
}

void SimRobot::update() {
  // a board spins here; a PC program sharing its cores with the simulator waits for input
  // instead, at most a millisecond, which is how often the simulator sends
  if (Serial.available() == 0) Serial.WaitReadable(1);
  while (Serial.available() > 0) {
    const int id = Serial.read();
    if (id >= kSensorIds) {
      // the original indexed its sensor table with the id unchecked
      std::fprintf(stderr, "firmware: frame id %d, which the original library cannot take\n", id);
      std::abort();
    }
    // the original waited for the rest of a frame it had begun
    while (Serial.available() < 2) Serial.WaitReadable(1);
    const int low = Serial.read();
    const int high = Serial.read();
    const uint16_t value = static_cast<uint16_t>(low | high << 8);
    if (id < 3) {
      tof_[id] = value;
      tof_seen_[id] = true;
    } else {
      int16_t& counts = encoder_[id - 3];
      counts = static_cast<int16_t>(counts + static_cast<int16_t>(value));
    }
  }
}

void SimRobot::delay(unsigned long ms) {
  const unsigned long from = millis();
  while (millis() - from < ms) update();
}

void SimRobot::log(const char* text) {
  const uint8_t id = kLogId;
  Serial.write(&id, 1);
  Serial.write(reinterpret_cast<const uint8_t*>(text), std::strlen(text) + 1);
}

void SimRobot::Motor(int side, int command) {
  const int16_t value = static_cast<int16_t>(command);
  if (value == motor_sent_[side]) return;
  motor_sent_[side] = value;
  const uint16_t bits = static_cast<uint16_t>(value);
  const uint8_t frame[3] = {static_cast<uint8_t>(5 + side), static_cast<uint8_t>(bits & 0xFF),
                            static_cast<uint8_t>(bits >> 8)};
  Serial.write(frame, sizeof(frame));
}

int main(int argc, char** argv) {
  Serial.Open(argc > 1 ? argv[1] : nullptr, 5000);
  setup();
  for (;;) loop();
}
