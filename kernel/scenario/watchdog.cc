// SPDX-License-Identifier: GPL-3.0-or-later
#include "watchdog.h"

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
  changed_.notify_one();
  thread_.join();
}

void Watchdog::Configure(double limit_s, Expiry expiry) {
  const std::lock_guard<std::mutex> lock(mutex_);
  limit_ = std::chrono::duration<double>(limit_s);
  expiry_ = std::move(expiry);
}

void Watchdog::Arm(const char* what) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    armed_ = true;
    what_ = what;
    deadline_ = std::chrono::steady_clock::now() +
                std::chrono::duration_cast<std::chrono::steady_clock::duration>(limit_);
  }
  changed_.notify_one();
}

void Watchdog::Disarm() {
  const std::lock_guard<std::mutex> lock(mutex_);
  armed_ = false;
}

void Watchdog::Watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (stop_) return;
    if (!armed_) {
      changed_.wait(lock);
    } else if (changed_.wait_until(lock, deadline_) == std::cv_status::timeout && armed_ &&
               std::chrono::steady_clock::now() >= deadline_) {
      break;
    }
  }
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%g", limit_.count());
  const std::string reason =
      std::string("the scenario's ") + what_ + " ran longer than " + seconds +
      " s of wall time in one call (work inside Lua's library that no count sees)";
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
