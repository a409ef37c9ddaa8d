// SPDX-License-Identifier: MIT
// The PC cores' clock. Before the library's robot begins, millis() and micros() count the delays
// asked for (each also waited on the wall clock, which the simulator keeps pace with); from
// begin() they hold until the simulator's first clock frame, then count its sim time on from
// there (lock-step). So they never go back, and read the same in every run. delay() and
// delayMicroseconds() wait in the same time.
#include <cstdint>

#include "Arduino.h"

namespace {

bool clock_seen = false;
uint64_t sim_us = 0;     // unwrapped from the frames' 32 bits
uint64_t before_us = 0;  // the delays asked for before the robot began (setup's delay(200))
void (*idle_step)(void*) = nullptr;
void* idle_context = nullptr;
// reads of the clock since it last moved: a sketch that waits on millis() in a loop of its own
// (`while (millis() - t < 500) {}`) would never let time go by; past this many, a read lets
// one step (before the robot begins, 1 ms) go by, as time goes by on a board while it spins
constexpr int kReadsPerStep = 1000;
int reads_unmoved = 0;

// in lock-step the simulator waits for the firmware, so a wait on the wall clock would stop
// the simulation: wait in sim time, stepping it
void Wait(uint64_t us) {
  if (idle_step == nullptr) {
    before_us += us;
    reads_unmoved = 0;
  }
  if (!clock_seen || idle_step == nullptr) {
    unimousePcWallWait(static_cast<unsigned long>(us));
    return;
  }
  const uint64_t start = sim_us;
  while (sim_us - start < us) idle_step(idle_context);
}

uint64_t Now() { return clock_seen ? before_us + sim_us : before_us; }

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
  if (++reads_unmoved >= kReadsPerStep) {
    reads_unmoved = 0;
    if (idle_step != nullptr) {
      idle_step(idle_context);
    } else {
      Wait(1000);
    }
  }
  return static_cast<unsigned long>(Now());
}

unsigned long millis() { return micros() / 1000; }

unsigned long unimousePcLibraryMillis() { return static_cast<unsigned long>(Now() / 1000); }
