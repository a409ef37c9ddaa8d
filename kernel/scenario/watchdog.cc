// SPDX-License-Identifier: GPL-3.0-or-later
#include "watchdog.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "unimouse/errors.h"

namespace unimouse {

Watchdog::Watchdog(double limit_s) : limit_(limit_s), thread_([this] { Watch(); }) {}

Watchdog::~Watchdog() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  stopping_.notify_one();
  thread_.join();
}

void Watchdog::Configure(double limit_s, Expiry expiry) {
  const std::lock_guard<std::mutex> lock(mutex_);
  limit_ = std::chrono::duration<double>(limit_s);
  expiry_ = std::move(expiry);
}

void Watchdog::Watch() {
  using Clock = std::chrono::steady_clock;
  std::unique_lock<std::mutex> lock(mutex_);
  uint64_t seen = 0;  // the armed stretch last looked at, 0 for none
  Clock::time_point seen_since;
  for (;;) {
    const auto period = std::clamp<std::chrono::duration<double>>(
        limit_ / 20, std::chrono::milliseconds(10), std::chrono::milliseconds(100));
    stopping_.wait_for(lock, period, [this] { return stop_; });
    if (stop_) return;
    const uint64_t stretch = stretch_.load(std::memory_order_acquire);
    const Clock::time_point now = Clock::now();
    if (stretch % 2 == 0) {
      seen = 0;
    } else if (stretch != seen) {
      // a stretch began since the last look: counted from now, it is never cut short
      seen = stretch;
      seen_since = now;
    } else if (now - seen_since >= limit_) {
      break;
    }
  }
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%g", limit_.count());
  const std::string reason =
      std::string("the scenario's ") + what_.load(std::memory_order_relaxed) + " ran longer than " +
      seconds + " s of wall time in one call (work inside Lua's library that no count sees)";
  if (expiry_) {
    expiry_(reason);
  } else {
    std::fprintf(stderr, "unimouse: error: %s\n", reason.c_str());
  }
  // the script is still running in C on the main thread: only the end of the process stops it
  std::fflush(nullptr);
  std::_Exit(kExitRuntimeFault);
}

}  // namespace unimouse
