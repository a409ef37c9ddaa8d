// SPDX-License-Identifier: GPL-3.0-or-later
// Paces a simulation to the wall clock, one step after another, and measures how late each
// step was released. Sleeps until just before a step is due, then spins: the OS's sleep alone
// wakes up tens of microseconds late.
#ifndef UNIMOUSE_RUN_REAL_TIME_PACER_H_
#define UNIMOUSE_RUN_REAL_TIME_PACER_H_

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

namespace unimouse {

class RealTimePacer {
 public:
  using Clock = std::chrono::steady_clock;

  explicit RealTimePacer(double timestep_s) : step_(std::chrono::duration<double>(timestep_s)) {}

  /// Waits until `steps` steps' worth of wall time has passed since the first call.
  void Wait(int64_t steps) {
    const Clock::time_point now = Clock::now();
    if (!started_) {
      started_ = true;
      start_ = now - std::chrono::duration_cast<Clock::duration>(step_ * steps);
    }
    const Clock::time_point due =
        start_ + std::chrono::duration_cast<Clock::duration>(step_ * steps);
    if (now < due) {
      std::this_thread::sleep_until(due - std::chrono::microseconds(500));
      while (Clock::now() < due) {
      }
    }
    const double late_us = std::chrono::duration<double, std::micro>(Clock::now() - due).count();
    lateness_us_.push_back(late_us);
    // behind by more than 100 ms: say so once, instead of drifting silently
    if (late_us > 100000 && !warned_) {
      warned_ = true;
      std::fprintf(stderr,
                   "unimouse: warning: this host cannot keep up with real time (%.0f ms behind at "
                   "step %lld)\n",
                   late_us / 1000, static_cast<long long>(steps));
    }
  }

  /// Returns lateness percentiles (us), late steps (over one step) and whether it fell behind.
  nlohmann::json Report() const {
    std::vector<double> v = lateness_us_;
    std::sort(v.begin(), v.end());
    auto at = [&](double q) {
      return v.empty() ? 0.0 : v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
    };
    const double step_us = std::chrono::duration<double, std::micro>(step_).count();
    const auto late = std::count_if(v.begin(), v.end(), [&](double x) { return x > step_us; });
    return {{"steps", v.size()},           {"lateness_p50_us", at(0.5)},
            {"lateness_p99_us", at(0.99)}, {"lateness_max_us", v.empty() ? 0.0 : v.back()},
            {"late_steps", late},          {"fell_behind", warned_}};
  }

 private:
  std::chrono::duration<double> step_;
  bool started_ = false;
  bool warned_ = false;
  Clock::time_point start_;
  std::vector<double> lateness_us_;
};

}  // namespace unimouse

#endif  // UNIMOUSE_RUN_REAL_TIME_PACER_H_
