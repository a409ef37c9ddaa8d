// SPDX-License-Identifier: GPL-3.0-or-later
// Firmware written for the original UnimouseSim runs unchanged: programs in the style of its
// Arduino examples, built against a stand-in for its library (sim_robot.h), pass the challenges
// in real time over a pseudo-terminal and over the native link, given the link settings such
// firmware needs. Without those settings they fail, and a firmware that dies mid-run has its
// motors stopped by the failsafe.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "run_program.h"
#include "text_file.h"

extern char** environ;

namespace unimouse {
namespace {

namespace fs = std::filesystem;

// what firmware written for the original expects of the link: the 1.0 m full scale its library
// decodes distances with, its commands held while it is silent (it sends a command only when it
// changes), and nothing beyond the original's protocol (no lock-step, even as a native program)
const std::string kOriginalLinkSettings = "--firmware-profile unimousesim-0.1";

// the original challenges' targets (section 5 of its description), in this project's terms;
// the time limits only bound a failing test's wall time
const std::string kWallDistance =
    "--scenario wall_distance --set distance_m=0.5 --set tolerance=0.02 --set hold_s=5 "
    "--set time_limit_s=30";
const std::string kSpeedControl =
    "--scenario speed_control --set speed_m_per_s=0.8 --set turn_rad_per_s=-1.57 "
    "--set tolerance=0.05 --set hold_s=5 --set time_limit_s=30";
const std::string kTimeTrial = "--scenario time_trial --set laps=1 --set time_limit_s=40";
// the micromouse contest in a small maze whose one path needs a right and a left turn
const std::string kTurnsMaze =
    "--scenario micromouse --set maze=" ORIGINAL_STYLE_DIR
    "/turns_maze.txt --set max_runs=1 --set start_within_s=10 --set contest_s=20 "
    "--set time_limit_s=30";

std::string Firmware(const std::string& name) { return ORIGINAL_FIRMWARE_DIR "/" + name; }

std::string TestName() { return ::testing::UnitTest::GetInstance()->current_test_info()->name(); }

struct FirmwareRun {
  testing::RunResult run;
  fs::path out;
  std::string firmware_output;  ///< what the firmware said on stderr (pty runs)
};

// a firmware program on the board's side of a pseudo-terminal, its stderr in a file
class Board {
 public:
  Board(const std::string& firmware, const std::string& device, const fs::path& output) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    std::vector<char*> argv = {const_cast<char*>(firmware.c_str()),
                               const_cast<char*>(device.c_str()), nullptr};
    if (::posix_spawn(&pid_, firmware.c_str(), &actions, nullptr, argv.data(), environ) != 0) {
      ADD_FAILURE() << firmware << ": cannot start it";
      pid_ = -1;
    }
    posix_spawn_file_actions_destroy(&actions);
  }
  Board(const Board&) = delete;  // it owns the process
  Board& operator=(const Board&) = delete;
  ~Board() { Kill(); }
  /// Ends the program at once, as a board losing power would.
  void Kill() {
    if (pid_ <= 0) return;  // already ended, or never started: nothing to signal
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  /// Waits up to `timeout` for the program to end by itself; returns whether it did.
  bool Ended(std::chrono::milliseconds timeout) {
    if (pid_ <= 0) return true;
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < until) {
      if (::waitpid(pid_, nullptr, WNOHANG) == pid_) {
        pid_ = -1;
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

 private:
  pid_t pid_ = -1;
};

// `unimouse run` in the background with a pty link, and the firmware on the pty's slave side;
// `while_running` is called with the run's output directory once the firmware has started
FirmwareRun OverPty(const std::string& firmware, const std::string& arguments,
                    const std::string& link_settings,
                    const std::function<void(Board&, const fs::path&)>& while_running = nullptr) {
  const fs::path temp = fs::temp_directory_path();
  const std::string name = "original_" + TestName() + "_pty";
  const std::string device = (temp / (name + "_board")).string();
  const fs::path firmware_output = temp / (name + "_firmware.txt");
  auto simulator = std::async(std::launch::async, [&] {
    return testing::UnimouseRun(
        arguments + " --no-pictures --link pty:" + device + " " + link_settings, name);
  });
  Board board(Firmware(firmware), device, firmware_output);
  if (while_running) while_running(board, temp / name);
  FirmwareRun r{simulator.get(), temp / name, ""};
  // the simulator gone, the firmware notices and ends
  EXPECT_TRUE(board.Ended(std::chrono::seconds(3))) << "the firmware outlived the simulator";
  if (fs::exists(firmware_output)) r.firmware_output = ReadTextFile(firmware_output.string());
  return r;
}

// `unimouse run` starting the firmware itself, on its stdin and stdout
FirmwareRun OverNativeLink(const std::string& firmware, const std::string& arguments,
                           const std::string& link_settings) {
  const std::string name = "original_" + TestName() + "_native";
  return {testing::UnimouseRun(arguments + " --no-pictures --link native:" + Firmware(firmware) +
                                   " " + link_settings,
                               name),
          fs::temp_directory_path() / name, ""};
}

// the same firmware over a pseudo-terminal and over the native link at once: each is paced by
// the wall clock and takes under half a core, so the two take the time of one (this group of
// tests runs alone, beside no other test)
struct BothRuns {
  FirmwareRun pty, native;
};
BothRuns OverBothLinks(const std::string& firmware, const std::string& arguments,
                       const std::string& link_settings) {
  auto native = std::async(std::launch::async,
                           [&] { return OverNativeLink(firmware, arguments, link_settings); });
  FirmwareRun pty = OverPty(firmware, arguments, link_settings);
  return {std::move(pty), native.get()};
}

std::string Status(const FirmwareRun& r) {
  return r.run.result["scenario"].value("status", "none");
}

std::string Reason(const FirmwareRun& r) { return r.run.result["scenario"].value("reason", ""); }

// everything there is to read when a run went wrong
std::string Story(const FirmwareRun& r) {
  return r.run.outcome.output + (r.firmware_output.empty() ? "" : "firmware: " + r.firmware_output);
}

// the run's log.txt as (sim time, message) pairs
std::vector<std::pair<double, std::string>> Log(const FirmwareRun& r) {
  std::vector<std::pair<double, std::string>> lines;
  if (!fs::exists(r.out / "log.txt")) return lines;
  std::istringstream in(ReadTextFile((r.out / "log.txt").string()));
  std::string line;
  while (std::getline(in, line)) {
    const size_t tab1 = line.find('\t');
    const size_t tab2 = line.find('\t', tab1 + 1);
    if (tab1 == std::string::npos || tab2 == std::string::npos) continue;
    lines.emplace_back(std::stod(line.substr(0, tab1)), line.substr(tab2 + 1));
  }
  return lines;
}

// waits up to `timeout` for a line containing `text` in the log.txt of a run going on in `out`
bool AwaitLogLine(const fs::path& out, const std::string& text, std::chrono::seconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    std::error_code ec;
    if (fs::exists(out / "log.txt", ec)) {
      try {
        if (ReadTextFile((out / "log.txt").string()).find(text) != std::string::npos) return true;
      } catch (const std::exception&) {
        // the run is only starting: its output directory is being made afresh
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// the sim time of the first log line at or after `from_s` that contains `text`; -1 if none
double LoggedAt(const FirmwareRun& r, const std::string& text, double from_s = 0) {
  for (const auto& [time_s, message] : Log(r)) {
    if (time_s >= from_s && message.find(text) != std::string::npos) return time_s;
  }
  return -1;
}

// the run's trace.csv, its columns by name
std::vector<std::map<std::string, double>> Trace(const FirmwareRun& r) {
  if (!fs::exists(r.out / "trace.csv")) return {};
  std::istringstream in(ReadTextFile((r.out / "trace.csv").string()));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::map<std::string, double> row;
    std::string field;
    for (size_t i = 0; i < names.size() && std::getline(fields, field, ','); ++i) {
      row[names[i]] = std::stod(field);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

void ExpectPassed(const FirmwareRun& r) {
  SCOPED_TRACE(r.out.filename().string());  // the run's name says its link
  EXPECT_EQ(r.run.outcome.exit_code, 0) << Story(r);
  EXPECT_EQ(Status(r), "passed") << Reason(r);
  // it said hello over the log frame as the original library sent it, sent nothing the link did
  // not know, and never asked for lock-step
  EXPECT_GE(LoggedAt(r, ": ready"), 0) << Story(r);
  EXPECT_GE(LoggedAt(r, "frames from the firmware, 0 unknown bytes"), 0) << Story(r);
  EXPECT_LT(LoggedAt(r, "lock-step on"), 0) << Story(r);
}

TEST(OriginalFirmwareTest, WallDistancePassesOverAPseudoTerminalAndTheNativeLink) {
  const BothRuns r = OverBothLinks("wall_distance", kWallDistance, kOriginalLinkSettings);
  ExpectPassed(r.pty);
  ExpectPassed(r.native);
}

TEST(OriginalFirmwareTest, SpeedControlPassesOverAPseudoTerminalAndTheNativeLink) {
  const BothRuns r = OverBothLinks("speed_control", kSpeedControl, kOriginalLinkSettings);
  ExpectPassed(r.pty);
  ExpectPassed(r.native);
}

TEST(OriginalFirmwareTest,
     TimeTrialWithTheRightMotorSetOncePassesOverAPseudoTerminalAndTheNativeLink) {
  const BothRuns r = OverBothLinks("time_trial", kTimeTrial, kOriginalLinkSettings);
  for (const FirmwareRun* run : {&r.pty, &r.native}) {
    ExpectPassed(*run);
    EXPECT_GT(run->run.result["scenario"]["scores"].value("best_lap_s", 0.0), 0) << Reason(*run);
  }
}

TEST(OriginalFirmwareTest, BlockingTurnsReachTheGoalOverAPseudoTerminalAndTheNativeLink) {
  const BothRuns r = OverBothLinks("blocking_turns", kTurnsMaze, kOriginalLinkSettings);
  for (const FirmwareRun* run : {&r.pty, &r.native}) {
    ExpectPassed(*run);
    // the path it drove, five cells and two quarter turns, without touching a wall
    EXPECT_EQ(run->run.result["scenario"]["scores"].value("best_run_path_cost", 0), 7)
        << Reason(*run);
    EXPECT_EQ(run->run.result["scenario"]["scores"].value("wall_contacts", -1), 0) << Reason(*run);
  }
}

// the simulator encodes distances with a 1.2 m full scale; the original library decodes them
// with 1.0 m, so every distance it sees is 1/1.2 of the truth: it keeps its sensor's goal at
// 1.2 times the distance, the centre at 0.048 + 1.2 * (0.5 - 0.048) = 0.590 m from the wall
// (where it settles after overshooting to about 0.63 m in 8 s)
TEST(OriginalFirmwareTest, WithTheDefaultLinkSettingsTheWallDistanceFirmwareKeepsTheWrongDistance) {
  const FirmwareRun r = OverPty(
      "wall_distance", "--scenario wall_distance --set tolerance=0.02 --set time_limit_s=15", "");
  EXPECT_EQ(r.run.outcome.exit_code, 1) << Story(r);
  EXPECT_EQ(Status(r), "failed");
  EXPECT_EQ(Reason(r).rfind("wrong distance", 0), 0u) << Reason(r);
  EXPECT_NEAR(r.run.result["robot_pose"]["x_m"].get<double>(), 0.590, 0.02) << Reason(r);
}

// a blocking turn is one command to each motor and then silence until the encoders say the turn
// is done; firmware that never said it repeats its commands keeps them through its silence, even
// with the default failsafe, so the turn ends and the robot reaches the goal
TEST(OriginalFirmwareTest, WithTheDefaultFailsafeABlockingTurnKeepsItsCommandsThroughItsSilence) {
  const FirmwareRun r = OverPty("blocking_turns", kTurnsMaze, "--link-set tof_full_scale_m=1.0");
  ExpectPassed(r);
  EXPECT_LT(LoggedAt(r, "motors stopped"), 0) << Story(r);
}

// the original-firmware settings hold commands through silence, but a firmware that dies mid-run
// (the pty's other side closed) has its motors stopped at once: a lost link always stops them
TEST(OriginalFirmwareTest, AFirmwareKilledMidRunHasItsMotorsStoppedWithinTheFailsafeTime) {
  const FirmwareRun r =
      OverPty("speed_control", "--scenario speed_control --set time_limit_s=3",
              kOriginalLinkSettings, [](Board& board, const fs::path& out) {
                // it speeds up for a second, a new command every 20 ms
                EXPECT_TRUE(AwaitLogLine(out, "speed control: ready", std::chrono::seconds(10)));
                std::this_thread::sleep_for(std::chrono::seconds(1));
                board.Kill();
              });
  // the step that notices the closed pty stops the motors
  const double gone_s = LoggedAt(r, "firmware disconnected: motors stopped");
  ASSERT_GT(gone_s, 0.5) << Story(r);
  EXPECT_LT(LoggedAt(r, "the firmware speaks again", gone_s), 0) << Story(r);
  // it was driving when it died, and came to rest with both commands at 0
  const auto trace = Trace(r);
  ASSERT_FALSE(trace.empty());
  for (const auto& row : trace) {
    if (row.at("time_s") >= gone_s - 0.01) {
      EXPECT_GT(row.at("speed_m_per_s"), 0.1);
      break;
    }
  }
  EXPECT_EQ(trace.back().at("left.command"), 0);
  EXPECT_EQ(trace.back().at("right.command"), 0);
  EXPECT_LT(std::abs(trace.back().at("speed_m_per_s")), 0.01);
}

}  // namespace
}  // namespace unimouse
