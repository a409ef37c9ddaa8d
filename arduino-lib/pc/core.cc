// SPDX-License-Identifier: MIT
// The PC Arduino core: Serial on stdin/stdout, the clock, and main() calling setup() and loop().
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "Arduino.h"

HardwareSerial Serial;

namespace {

int link_fd = 1;  // the protocol's way out: the standard output the program started with
std::vector<uint8_t> out;
uint8_t in[4096];
size_t in_pos = 0, in_len = 0;

void WriteOut() {
  size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::write(link_fd, out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) std::exit(0);  // the simulator went away
    done += static_cast<size_t>(n);
  }
  out.clear();
}

}  // namespace

int HardwareSerial::available() {
  WriteOut();
  if (in_pos < in_len) return static_cast<int>(in_len - in_pos);
  pollfd p{0, POLLIN, 0};
  if (::poll(&p, 1, 0) <= 0) return 0;
  const ssize_t n = ::read(0, in, sizeof(in));
  if (n == 0) std::exit(0);  // end of input: the run is over
  if (n < 0) return 0;
  in_pos = 0;
  in_len = static_cast<size_t>(n);
  return static_cast<int>(in_len);
}

void unimousePcAwaitInput() {
  WriteOut();
  if (in_pos < in_len) return;
  pollfd p{0, POLLIN, 0};
  // no timeout: the simulator always answers a step, and its end closes the input
  while (::poll(&p, 1, -1) < 0 && errno == EINTR) {
  }
}

int HardwareSerial::read() {
  if (available() == 0) return -1;
  return in[in_pos++];
}

size_t HardwareSerial::write(uint8_t byte) {
  out.push_back(byte);
  return 1;
}

void HardwareSerial::flush() { WriteOut(); }

// the standard output is the standard error here (main), which the simulator logs line by line
void unimousePcText(const char* text, size_t size) { std::fwrite(text, 1, size, stdout); }

void unimousePcWallWait(unsigned long us) {
  Serial.flush();
  std::this_thread::sleep_for(std::chrono::microseconds(us));
}

int main() {
  // printf and std::cout are the firmware's own text, not the protocol: the protocol keeps the
  // standard output the program started with, and text goes to standard error, which the
  // simulator logs line by line
  link_fd = ::dup(1);
  ::dup2(2, 1);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  setup();
  for (;;) loop();
}
