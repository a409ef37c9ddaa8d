// SPDX-License-Identifier: MIT
// The PC cores' clock: millis() and micros() follow the simulator's clock frames once they come
// (lock-step), the wall clock before that; delay() and delayMicroseconds() wait in the same time.
#include <chrono>
#include <cstdint>

#include "Arduino.h"

namespace {

bool clock_seen = false;
uint64_t sim_us = 0;  // unwrapped from the frames' 32 bits
const auto started = std::chrono::steady_clock::now();
void (*idle_step)(void*) = nullptr;
void* idle_context = nullptr;

// in lock-step the simulator waits for the firmware, so a wait on the wall clock would stop
// the simulation: wait in sim time, stepping it
void Wait(uint64_t us) {
  if (!clock_seen || idle_step == nullptr) {
    unimousePcWallWait(static_cast<unsigned long>(us));
    return;
  }
  const uint64_t start = sim_us;
  while (sim_us - start < us) idle_step(idle_context);
}

}  // namespace

void unimousePcSetIdle(void (*idle)(void* context), void* context) {
  idle_step = idle;
  idle_context = context;
}

void delay(unsigned long ms) { Wait(static_cast<uint64_t>(ms) * 1000); }

void delayMicroseconds(unsigned int us) { Wait(us); }

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
