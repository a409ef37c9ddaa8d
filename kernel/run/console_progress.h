// SPDX-License-Identifier: GPL-3.0-or-later
// One line on a terminal that says how far a run is (simulated time, real-time factor, the
// scenario's HUD), rewritten in place a few times a second; log lines printed meanwhile clear
// it first, so it never mixes with them.
#ifndef UNIMOUSE_RUN_CONSOLE_PROGRESS_H_
#define UNIMOUSE_RUN_CONSOLE_PROGRESS_H_

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace unimouse {

class ConsoleProgress {
 public:
  explicit ConsoleProgress(std::FILE* out) : out_(out), start_(Clock::now()) {}
  ~ConsoleProgress() { Clear(); }
  ConsoleProgress(const ConsoleProgress&) = delete;
  ConsoleProgress& operator=(const ConsoleProgress&) = delete;

  /// Shows the run at sim_s with its HUD, at most every 0.25 s of wall time.
  void Update(double sim_s, const std::vector<std::string>& hud) {
    const Clock::time_point now = Clock::now();
    if (now < next_) return;
    next_ = now + std::chrono::milliseconds(250);
    const double wall_s = std::chrono::duration<double>(now - start_).count();
    char head[64];
    std::snprintf(head, sizeof(head), "[%9.3f s] %.0fx real time", sim_s,
                  wall_s > 0 ? sim_s / wall_s : 0.0);
    std::string line = head;
    for (const std::string& text : hud) {
      if (!text.empty()) line += " | " + text;
    }
    // one terminal row: a wrapped line could not be rewritten in place
    if (line.size() > kWidth) line = line.substr(0, kWidth - 3) + "...";
    std::fprintf(out_, "\r\033[K%s", line.c_str());
    std::fflush(out_);
    shown_ = true;
  }

  /// Takes the line away, before a log line or at the end.
  void Clear() {
    if (!shown_) return;
    std::fputs("\r\033[K", out_);
    shown_ = false;
  }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr size_t kWidth = 79;
  std::FILE* out_;
  Clock::time_point start_;
  Clock::time_point next_ = start_ + std::chrono::milliseconds(250);
  bool shown_ = false;
};

}  // namespace unimouse

#endif  // UNIMOUSE_RUN_CONSOLE_PROGRESS_H_
