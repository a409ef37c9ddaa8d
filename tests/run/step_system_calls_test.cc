// SPDX-License-Identifier: GPL-3.0-or-later
// The step loop of an in-process lock-step run makes no system call: counted by strace over the
// main job's setup run for two durations, so that everything a run does once (loading, the
// pictures, the record) cancels out and what is left is what 10,000 more steps cost.
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>

#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

// system calls by name of `unimouse run ARGS` and every thread and child it starts
std::map<std::string, long> SystemCalls(const std::string& args, const std::string& name) {
  const std::string out = testing::FreshDirectory(name);
  const std::string counts = out + "/strace.txt";
  // LeakSanitizer's check at exit cannot run under a tracer: the sanitizer build leaves it out
  const testing::Outcome run =
      testing::Shell("ASAN_OPTIONS=detect_leaks=0 strace -f -c -o " + counts + " " +
                     UNIMOUSE_BINARY + " run " + args + " --out " + out + "/run 2>&1");
  EXPECT_EQ(run.exit_code, 1) << run.output;  // the contest is not over in a few seconds
  std::map<std::string, long> calls;
  std::istringstream lines(ReadTextFile(counts));
  for (std::string line; std::getline(lines, line);) {
    // "% time seconds usecs/call calls [errors] syscall": the count is the fourth column
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.size() < 5 || w[0] == "%" || w[0].starts_with("-") || w.back() == "total") continue;
    calls[w.back()] = std::stol(w[3]);
  }
  return calls;
}

TEST(StepSystemCallsTest, TenThousandStepsOfTheMainJobMakeNoSystemCallPerStep) {
  if (testing::Shell("command -v strace > /dev/null").exit_code != 0) {
    GTEST_SKIP() << "strace is not installed (setup.sh installs it)";
  }
#ifdef __SANITIZE_ADDRESS__
  // the sanitizer's runtime asks for the signal stack (sigaltstack) at every switch to the
  // in-process firmware's stack: its own call a step, not the simulator's
  GTEST_SKIP() << "the sanitizer's runtime makes its own system calls; the normal build counts";
#endif
  const std::string main_job =
      "--scenario micromouse --set end_on_log=done --link inproc:micromouse --seed 1";
  const auto shorter = SystemCalls(main_job + " --duration 2", "syscalls_2s");
  const auto longer = SystemCalls(main_job + " --duration 12", "syscalls_12s");
  ASSERT_FALSE(shorter.empty());
  long more = 0;
  std::string which;
  for (const auto& [name, n] : longer) {
    const long extra = n - (shorter.contains(name) ? shorter.at(name) : 0);
    more += extra;
    if (extra > 0) which += " " + name + " +" + std::to_string(extra);
  }
  // what 10,000 more steps cost: the trace's and log's buffered writes, a few lines of the
  // firmware's log, and the calls that come with wall time rather than steps (the watchdog's
  // look every 100 ms, some 20 a second with the in-process firmware's: the bound leaves room
  // for 10 s more of wall time under a sanitizer on a busy host); one call a step (a lock, a
  // wake-up) would be 10,000
  EXPECT_LT(more, 500) << "system calls in 10,000 more steps:" << which;
}

}  // namespace
}  // namespace unimouse
