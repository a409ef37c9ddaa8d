// SPDX-License-Identifier: MIT
// The PC cores' clock: millis() and micros() follow the simulator's clock frames once they come
// (lock-step), counted on from the delays asked for before them; the wall clock before the
// library's robot begins. delay() and delayMicroseconds() wait in the same time.
#include <chrono>
#include <cstdint>

#include "Arduino.h"

namespace {

bool clock_seen = false;
uint64_t sim_us = 0;  // unwrapped from the frames' 32 bits
// the waits asked for before the simulator's clock came (setup's delay(1000)): its time counts
// on from there, so that millis() never goes back, and the same in every run
uint64_t before_us = 0;
const auto started = std::chrono::steady_clock::now();
void (*idle_step)(void*) = nullptr;
void* idle_context = nullptr;
// reads of the clock since it last moved: a sketch that waits on millis() in a loop of its own
// (`while (millis() - t < 500) {}`) would never let the simulation run on; past this many, a
// read lets one step go by, as time goes by on a board while it spins
constexpr int kReadsPerStep = 1000;
int reads_unmoved = 0;

// in lock-step the simulator waits for the firmware, so a wait on the wall clock would stop
// the simulation: wait in sim time, stepping it
void Wait(uint64_t us) {
  if (!clock_seen || idle_step == nullptr) {
    if (!clock_seen) before_us += us;
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
    reads_unmoved = 0;
  } else {
    const uint64_t was = sim_us;
    sim_us += static_cast<uint32_t>(us - static_cast<uint32_t>(sim_us));
    if (sim_us != was) reads_unmoved = 0;
  }
}

unsigned long micros() {
  if (idle_step != nullptr && ++reads_unmoved >= kReadsPerStep) {
    reads_unmoved = 0;
    idle_step(idle_context);
  }
  if (clock_seen) return static_cast<unsigned long>(before_us + sim_us);
  // the library's robot has begun: the clock holds until the simulator's first frame
  if (idle_step != nullptr) return static_cast<unsigned long>(before_us);
  return static_cast<unsigned long>(std::chrono::duration_cast<std::chrono::microseconds>(
                                        std::chrono::steady_clock::now() - started)
                                        .count());
}

unsigned long millis() { return micros() / 1000; }
