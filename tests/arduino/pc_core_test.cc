// SPDX-License-Identifier: GPL-3.0-or-later
// The library's PC cores (arduino-lib/pc) as a student's sketch meets them: Arduino's own calls
// keep their meaning in a firmware built for the PC, as a program and as a module.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

// the sim times (s) of the log lines that match `pattern`, and their first group
struct Lines {
  std::vector<double> times_s;
  std::vector<std::string> values;
};

Lines Find(const std::string& log, const std::string& pattern) {
  Lines found;
  const std::regex line("([0-9.]+)\tlink\t" + pattern);
  for (std::sregex_iterator i(log.begin(), log.end(), line), end; i != end; ++i) {
    found.times_s.push_back(std::stod((*i)[1]));
    found.values.push_back((*i)[2]);
  }
  return found;
}

// the sanitizer build links its runtime ahead of a firmware module's core, and the runtime's
// printf then satisfies the sketch's before the core's own is taken from its archive: a module's
// printf goes to the terminal there, so its checks run in the normal build only
#ifdef __SANITIZE_ADDRESS__
constexpr bool kModulePrintfIsTheCores = false;
#else
constexpr bool kModulePrintfIsTheCores = true;
#endif

// the sketch's loop: update() waits one step (1 ms), delayMicroseconds(2500) ends at the third
// step boundary after it began, delay(50) at the fiftieth, so a loop takes 54 steps of sim time
TEST(PcCoreTest, DelayAndDelayMicrosecondsWaitInSimTimeWhileTheSimulationRunsOn) {
  for (const std::string link :
       {"native:" UNIMOUSE_WAITING_FIRMWARE, "inproc:" UNIMOUSE_WAITING_FIRMWARE_MODULE}) {
    const std::string out = "pc_core_waiting_" + link.substr(0, link.find(':'));
    const testing::RunResult run =
        testing::UnimouseRun("--maze none --duration 0.5 --no-pictures --link " + link, out);
    ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
    const std::string log =
        ReadTextFile((std::filesystem::temp_directory_path() / out / "log.txt").string());
    const Lines delays = Find(log, "delay\\(50\\) took ([0-9]+) ms");
    const Lines micro = Find(log, "delayMicroseconds\\(2500\\) took ([0-9]+) us");
    // 0.5 s hold 9 whole loops
    ASSERT_GE(delays.values.size(), 9u) << link << "\n" << log;
    ASSERT_LE(delays.values.size(), 10u) << link << "\n" << log;
    for (size_t i = 0; i < delays.values.size(); ++i) {
      EXPECT_EQ(delays.values[i], "50") << link;
      EXPECT_EQ(micro.values[i], "3000") << link;
      if (i > 0) {
        EXPECT_NEAR(delays.times_s[i] - delays.times_s[i - 1], 0.054, 1e-9) << link;
      }
    }
    // the motors ran all along: 0.5 s at 400/1023 of 6 V carries the robot north of the origin,
    // where an open floor starts it
    EXPECT_GT(run.result["robot_pose"]["y_m"].get<double>(), 0.05)
        << run.result["robot_pose"].dump();
  }
}

// what the sketch prints at 100, 200 and 300 ms, each line logged at the step it was printed in
TEST(PcCoreTest, SerialPrintAndPrintfAreTheFirmwaresLogAtTheirStepAndLeaveTheProtocolAlone) {
  for (const std::string link : {"native:" UNIMOUSE_SERIAL_PRINT_FIRMWARE,
                                 "inproc:" UNIMOUSE_SERIAL_PRINT_FIRMWARE_MODULE}) {
    if (link.starts_with("inproc:") && !kModulePrintfIsTheCores) continue;
    const std::string out = "pc_core_print_" + link.substr(0, link.find(':'));
    const testing::RunResult run =
        testing::UnimouseRun("--maze none --duration 0.35 --no-pictures --link " + link, out);
    ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
    const std::string log =
        ReadTextFile((std::filesystem::temp_directory_path() / out / "log.txt").string());
    for (const char* line :
         {"0.100000\tlink\tprint at 100 ms, 1.500 -42 FF\n", "0.100000\tlink\tprintf at 100 ms\n",
          "0.300000\tlink\tprint at 300 ms, 1.500 -42 FF\n",
          "0.300000\tlink\tprintf at 300 ms\n"}) {
      EXPECT_NE(log.find(line), std::string::npos) << link << ": " << line << " not in\n" << log;
    }
    EXPECT_EQ(log.find("unknown frame id"), std::string::npos) << log;
    EXPECT_NE(log.find(", 0 unknown bytes"), std::string::npos) << log;
    // on the terminal only as the run's log lines, never as the raw text
    EXPECT_EQ(("\n" + run.outcome.output).find("\nprintf at"), std::string::npos)
        << "printed on the terminal: " << run.outcome.output;
  }
}

// a firmware that crashes, hangs, exits or aborts at 0.2 s just after printing a line
TEST(PcCoreTest, TheLastLineAFirmwarePrintsBeforeItFailsIsInTheLog) {
  for (const char* failure : {"null_pointer", "hang", "exit", "abort"}) {
    for (const std::string suffix : {"", ".so"}) {
      if (suffix == ".so" && !kModulePrintfIsTheCores) continue;
      const std::string firmware = std::string(failure) + "_firmware" + suffix;
      const std::string link = (suffix.empty() ? "native:" : "inproc:") +
                               std::string(UNIMOUSE_TEST_BINARY_DIR) + "/" + firmware;
      const std::string out = "pc_core_last_" + firmware;
      const testing::RunResult run = testing::UnimouseRun(
          "--maze none --duration 1 --no-pictures --link-set lockstep_timeout_s=1 --link " + link,
          out);
      EXPECT_EQ(run.outcome.exit_code, 3) << run.outcome.output;
      const std::string log =
          ReadTextFile((std::filesystem::temp_directory_path() / out / "log.txt").string());
      EXPECT_NE(log.find("0.200000\tlink\tfailing at 200 ms\n"), std::string::npos)
          << firmware << ":\n"
          << log;
    }
  }
}

}  // namespace
}  // namespace unimouse
