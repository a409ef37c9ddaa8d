// SPDX-License-Identifier: MIT
// The PC cores' clock: millis() and micros() follow the simulator's clock frames once they come
// (lock-step), the wall clock before that.
#include <chrono>
#include <cstdint>

#include "Arduino.h"

namespace {

bool clock_seen = false;
uint64_t sim_us = 0;  // unwrapped from the frames' 32 bits
const auto started = std::chrono::steady_clock::now();

}  // namespace

void unimousePcClock(uint32_t us) {
  if (!clock_seen) {
    sim_us = us;
    clock_seen = true;
  } else {
    sim_us += static_cast<uint32_t>(us - static_cast<uint32_t>(sim_us));
  }
}

unsigned long micros() {
  if (clock_seen) return static_cast<unsigned long>(sim_us);
  return static_cast<unsigned long>(std::chrono::duration_cast<std::chrono::microseconds>(
                                        std::chrono::steady_clock::now() - started)
                                        .count());
}

unsigned long millis() { return micros() / 1000; }
