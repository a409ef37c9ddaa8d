// SPDX-License-Identifier: MIT
// The PC Arduino core for a firmware loaded into the simulator (a module, not a program):
// Serial reads and writes the simulator's queues, and waiting for input hands control back to
// the simulator, which resumes the firmware at the next step. exit() and its kin end the
// firmware, not the simulator.
#include <chrono>
#include <thread>

#include "Arduino.h"
#include "unimouse_inproc.h"
#include "unimouse_protocol.h"

HardwareSerial Serial;

namespace {

const unimouse_inproc_host* host = nullptr;
uint8_t in[4096];
size_t in_pos = 0, in_len = 0;

// the line being printed (printf, Serial.print), sent as a log frame at its end
char line[UNIMOUSE_LOG_MAX];
size_t line_length = 0;

void SendLine() {
  const uint8_t id = UNIMOUSE_ID_LOG, end = 0;
  host->write(host->self, &id, 1);
  host->write(host->self, reinterpret_cast<const uint8_t*>(line), line_length);
  host->write(host->self, &end, 1);
  line_length = 0;
}

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

// the simulator runs on this thread: hand it control until the time has passed
void unimousePcWallWait(unsigned long us) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::microseconds(us);
  while (std::chrono::steady_clock::now() < end) host->suspend(host->self, 0);
}

void unimousePcText(const char* text, size_t size) { unimouse_inproc_text(text, size); }

extern "C" {
// a module shares the simulator's standard output: what the firmware prints (inproc_stdio.c's
// printf and its kin, Serial.print) goes into its log instead, as log frames on the link, which
// time them as the robot's log() lines
void unimouse_inproc_text(const char* text, size_t size) {
  for (size_t i = 0; i < size; ++i) {
    if (text[i] == '\n') {
      SendLine();
    } else if (text[i] != '\0' && text[i] != '\r') {
      line[line_length++] = text[i];
      // a line longer than a log frame takes goes on in the next one
      if (line_length == sizeof(line)) SendLine();
    }
  }
}

// inproc_exit.c's exit() and its kin end here, with what was printed
[[noreturn]] void unimouse_inproc_exit(int code) {
  if (line_length > 0) SendLine();
  host->exit(host->self, code);
  __builtin_unreachable();
}

__attribute__((visibility("default"))) void unimouse_inproc_main_v1(const unimouse_inproc_host* h) {
  host = h;
  setup();
  for (;;) loop();
}
}
