// SPDX-License-Identifier: GPL-3.0-or-later
// A wall-clock watchdog for work no count can see: an instruction that runs long in C (comparing
// two long strings, one library call over a large table) returns to the instruction hook only
// after it, and a loop of them can run for hours under the budget; C code cannot be stopped
// but by the end of the process. The watchdog is armed around each
// call into Lua; when one runs longer than its limit, it calls its expiry function (which
// writes what it can, e.g. a result saying why) from its own thread and ends the process with
// exit code 3.
//
// Arming and disarming cost no system call: they bump an atomic stretch number that the
// watchdog's thread looks at on its own period (a twentieth of the limit, within 10-100 ms), so
// a run that calls into Lua every step pays no lock and no wake-up per step. A stretch is timed
// from the first look that sees it, so it expires between its limit and its limit plus two
// periods. Arm and Disarm alternate, on one thread.
#ifndef UNIMOUSE_SCENARIO_WATCHDOG_H_
#define UNIMOUSE_SCENARIO_WATCHDOG_H_

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace unimouse {

class Watchdog {
 public:
  /// Called on the watchdog's thread with the reason, just before the process ends.
  using Expiry = std::function<void(const std::string& reason)>;

  /// A watchdog that allows `limit_s` of wall time per armed stretch; the default expiry
  /// prints the reason to stderr.
  explicit Watchdog(double limit_s);
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;
  ~Watchdog();

  /// Sets the limit and what to do on expiry (before the process ends with exit code 3).
  void Configure(double limit_s, Expiry expiry);
  /// Starts a stretch of work named `what` ("world", "run"); `what` lives for the program.
  void Arm(const char* what) {
    what_.store(what, std::memory_order_relaxed);
    stretch_.store(stretch_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }
  /// Ends the stretch.
  void Disarm() {
    stretch_.store(stretch_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }

 private:
  void Watch();

  // odd while armed; only the armed thread writes it
  std::atomic<uint64_t> stretch_{0};
  std::atomic<const char*> what_{""};

  std::mutex mutex_;  // guards what follows
  std::condition_variable stopping_;
  std::chrono::duration<double> limit_;
  Expiry expiry_;
  bool stop_ = false;
  std::thread thread_;  // last: it starts once everything above exists
};

}  // namespace unimouse

#endif  // UNIMOUSE_SCENARIO_WATCHDOG_H_
