// SPDX-License-Identifier: GPL-3.0-or-later
// A wall-clock watchdog for work no count can see: an instruction that runs long in C (comparing
// two long strings, one library call over a large table) returns to the instruction hook only
// after it, and a loop of them can run for hours under the budget; C code cannot be stopped
// but by the end of the process. The watchdog is armed around each
// call into Lua; when one runs longer than its limit, it calls its expiry function (which
// writes what it can, e.g. a result saying why) from its own thread and ends the process with
// exit code 3.
#ifndef UNIMOUSE_SCENARIO_WATCHDOG_H_
#define UNIMOUSE_SCENARIO_WATCHDOG_H_

#include <chrono>
#include <condition_variable>
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
  /// Starts a stretch of work named `what` ("world", "run").
  void Arm(const char* what);
  /// Ends the stretch.
  void Disarm();

 private:
  void Watch();

  std::mutex mutex_;
  std::condition_variable changed_;
  std::chrono::duration<double> limit_;
  Expiry expiry_;
  bool armed_ = false;
  const char* what_ = "";
  std::chrono::steady_clock::time_point deadline_;
  bool stop_ = false;
  std::thread thread_;  // last: it starts once everything above exists
};

}  // namespace unimouse

#endif  // UNIMOUSE_SCENARIO_WATCHDOG_H_
