// SPDX-License-Identifier: GPL-3.0-or-later
// Paces a simulation to the wall clock, one step after another, and measures how late each
// step was released. Sleeps until just before a step is due, then spins: the OS's sleep alone
// wakes up tens of microseconds late.
#ifndef UNIMOUSE_RUN_REAL_TIME_PACER_H_
#define UNIMOUSE_RUN_REAL_TIME_PACER_H_

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <thread>
#include <vector>

namespace unimouse {

/// How closely the wall clock followed simulated time.
struct PacingReport {
  int64_t steps = 0;
  double lateness_p50_us = 0;
  double lateness_p99_us = 0;
  double lateness_max_us = 0;
  int64_t late_steps = 0;  ///< more than one step late
  bool fell_behind = false;
};

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
    Count(late_us);
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
  PacingReport Report() const {
    // the lateness of the step at rank q * (steps - 1), to 0.1 us below 1 ms
    auto at = [&](double q) {
      if (steps_ == 0) return 0.0;
      const auto rank = static_cast<uint64_t>(q * static_cast<double>(steps_ - 1));
      uint64_t seen = 0;
      for (size_t i = 0; i < counts_.size(); ++i) {
        seen += counts_[i];
        if (seen > rank) return BinUs(i);
      }
      return max_us_;
    };
    return {static_cast<int64_t>(steps_),      at(0.5), at(0.99), max_us_,
            static_cast<int64_t>(late_steps_), warned_};
  }

 private:
  // lateness is counted in bins, 0.1 us wide below 1 ms, 10 us below 100 ms and 1 ms below 10 s,
  // so that an hour of steps takes no more memory than a second (a list of every step's
  // lateness grew 29 MB an hour, docs/performance.md)
  static constexpr double kFineUs = 0.1, kMidUs = 10, kCoarseUs = 1000;
  static constexpr size_t kFine = 10000, kMid = 9900, kCoarse = 9900;
  static double BinUs(size_t i) {
    if (i < kFine) return kFineUs * static_cast<double>(i);
    if (i < kFine + kMid) return 1e3 + kMidUs * static_cast<double>(i - kFine);
    return 1e5 + kCoarseUs * static_cast<double>(i - kFine - kMid);
  }
  void Count(double late_us) {
    const double us = std::max(0.0, late_us);
    const size_t i = us < 1e3   ? static_cast<size_t>(us / kFineUs)
                     : us < 1e5 ? kFine + static_cast<size_t>((us - 1e3) / kMidUs)
                                : kFine + kMid + static_cast<size_t>((us - 1e5) / kCoarseUs);
    counts_[std::min(i, counts_.size() - 1)] += 1;
    ++steps_;
    max_us_ = steps_ == 1 ? late_us : std::max(max_us_, late_us);
    if (late_us > std::chrono::duration<double, std::micro>(step_).count()) ++late_steps_;
  }

  std::chrono::duration<double> step_;
  bool started_ = false;
  bool warned_ = false;
  Clock::time_point start_;
  std::vector<uint64_t> counts_ = std::vector<uint64_t>(kFine + kMid + kCoarse + 1);
  uint64_t steps_ = 0;
  uint64_t late_steps_ = 0;
  double max_us_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_RUN_REAL_TIME_PACER_H_
