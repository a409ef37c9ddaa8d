// SPDX-License-Identifier: MIT
// The PC Arduino core for a firmware loaded into the simulator (a module, not a program):
// Serial reads and writes the simulator's queues, and waiting for input hands control back to
// the simulator, which resumes the firmware at the next step. exit() and its kin end the
// firmware, not the simulator.
#include <chrono>
#include <thread>

#include "Arduino.h"
#include "unimouse_inproc.h"

HardwareSerial Serial;

namespace {

const unimouse_inproc_host* host = nullptr;
uint8_t in[4096];
size_t in_pos = 0, in_len = 0;

bool Fill() {
  if (in_pos < in_len) return true;
  in_pos = 0;
  in_len = host->read(host->self, in, sizeof(in));
  return in_len > 0;
}

}  // namespace

int HardwareSerial::available() {
  // nothing yet: let the simulator run, it may answer what was written
  if (!Fill()) {
    host->suspend(host->self, 0);
    Fill();
  }
  return static_cast<int>(in_len - in_pos);
}

int HardwareSerial::read() {
  if (available() == 0) return -1;
  return in[in_pos++];
}

size_t HardwareSerial::write(uint8_t byte) {
  host->write(host->self, &byte, 1);
  return 1;
}

void HardwareSerial::flush() {}

void unimousePcAwaitInput() {
  while (!Fill()) host->suspend(host->self, 1);
}

void delay(unsigned long ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

extern "C" {
// inproc_exit.c's exit() and its kin end here
[[noreturn]] void unimouse_inproc_exit(int code) {
  host->exit(host->self, code);
  __builtin_unreachable();
}

__attribute__((visibility("default"))) void unimouse_inproc_main_v1(const unimouse_inproc_host* h) {
  host = h;
  setup();
  for (;;) loop();
}
}
