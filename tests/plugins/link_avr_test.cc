// SPDX-License-Identifier: GPL-3.0-or-later
// The link with the emulated board (avr:): a board image drives the robot, in lock-step when the
// library asks for it, runs repeat exactly, and a firmware that crashes ends the run with its
// reason.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <regex>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

std::string Image(const std::string& name) {
#ifdef UNIMOUSE_AVR_TEST_FIRMWARE_DIR
  const std::string path = std::string(UNIMOUSE_AVR_TEST_FIRMWARE_DIR) + "/" + name + ".elf";
  if (std::filesystem::exists(path)) return path;
#endif
  return "";
}

Maze Corridor() {
  std::string text = "o---o\n";
  for (int i = 0; i < 6; ++i) text += i == 5 ? "| S |\no---o\n" : "|   |\no   o\n";
  return ParseMazeText(text, "corridor.txt");
}

class AvrLinkTest : public ::testing::Test {
 protected:
  std::unique_ptr<Kernel> Make(const std::string& image) {
    const std::string yaml =
        testing::ReadBundledRobot() +
        "  - { type: unimouse.link, name: link, params: { transport: 'avr:" + image + "' } }\n";
    KernelOptions options;
    options.trust_robot_file = true;  // the test wrote the robot file
    options.seed = 5;
    options.log_sink = [this](double, int, const std::string&, const std::string& message) {
      messages_.push_back(message);
    };
    return testing::MakeKernel(yaml, &maze_, options);
  }
  bool Logged(const std::string& pattern) const {
    for (const auto& m : messages_) {
      if (std::regex_search(m, std::regex(pattern))) return true;
    }
    return false;
  }

  const Maze maze_ = Corridor();
  std::vector<std::string> messages_;
};

TEST_F(AvrLinkTest, TheLibrarysLockstepRunsOnTheBoardAndRepeats) {
  const std::string image = Image("lockstep_robot");
  if (image.empty()) GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr missing";
  std::vector<mjtNum> first;
  for (int run = 0; run < 2; ++run) {
    messages_.clear();
    auto kernel = Make(image);
    for (int i = 0; i < 600; ++i) kernel->Step();
    kernel->Finish();
    const mjData& d = kernel->state().data();
    std::vector<mjtNum> q(d.qpos, d.qpos + kernel->mj_model().nq);
    EXPECT_GT(q[1], 0.05) << "it drove north";
    if (run == 0) {
      first = q;
    } else {
      EXPECT_EQ(std::memcmp(first.data(), q.data(), q.size() * sizeof(mjtNum)), 0);
    }
  }
  EXPECT_TRUE(Logged("^lock-step on"));
  EXPECT_TRUE(Logged("^lockstep$"));
  EXPECT_TRUE(Logged("emulated atmega2560 at 16 MHz"));
  // every step finished within its 16 000 cycles, and nothing was lost
  EXPECT_TRUE(Logged("RX overruns.*; 0 lock-step steps late")) << messages_.back();
  EXPECT_TRUE(Logged(" 0 RX overruns, 0 lost in, 0 lost out")) << messages_.back();
  EXPECT_TRUE(Logged("latency p50 0\\.[0-9]+ ms")) << messages_.back();
}

TEST_F(AvrLinkTest, AStackOverflowEndsTheRunWithTheFunction) {
  const std::string image = Image("stack_overflow");
  if (image.empty()) GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr missing";
  auto kernel = Make(image);
  try {
    for (int i = 0; i < 100; ++i) kernel->Step();
    FAIL() << "the overflow went unnoticed";
  } catch (const RuntimeFault& e) {
    EXPECT_NE(std::string(e.what()).find("recurse"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("high-water"), std::string::npos) << e.what();
  }
}

TEST(AvrRunTest, AStackIntoTheDataEndsTheRunWithExitCode3AndItsHighWaterMark) {
  const std::string image = Image("stack_overflow");
  if (image.empty()) GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr missing";
  const testing::RunResult r =
      testing::UnimouseRun("--duration 1 --link avr:" + image, "unimouse_avr_stack");
  EXPECT_EQ(r.outcome.exit_code, 3) << r.outcome.output;
  EXPECT_EQ(r.result["status"], "fault");
  const std::string error = r.result["error"];
  EXPECT_NE(error.find("ran into the data"), std::string::npos) << error;
  EXPECT_NE(error.find("RAM high-water"), std::string::npos) << error;
  EXPECT_NE(error.find("(recurse)"), std::string::npos) << error;
}

// tests/avr/printing_robot.ino: Serial.print, Serial.println and printf every 100 ms
TEST(AvrRunTest, SerialPrintAndPrintfOnTheBoardAreItsLogAndLeaveTheProtocolAlone) {
  const std::string image = Image("printing_robot");
  if (image.empty()) GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr missing";
  const testing::RunResult r = testing::UnimouseRun(
      "--maze none --duration 0.35 --no-pictures --link avr:" + image, "unimouse_avr_print");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  const std::string log = ReadTextFile(
      (std::filesystem::temp_directory_path() / "unimouse_avr_print" / "log.txt").string());
  for (const char* line : {"\tlink\tprint at 100\n", "\tlink\tprintf at 100 ms\n",
                           "\tlink\tprint at 300\n", "\tlink\tprintf at 300 ms\n"}) {
    EXPECT_NE(log.find(line), std::string::npos) << line << " not in\n" << log;
  }
  EXPECT_EQ(log.find("unknown frame id"), std::string::npos) << log;
  EXPECT_EQ(log.find("debug value"), std::string::npos) << log;
  EXPECT_NE(log.find(", 0 unknown bytes"), std::string::npos) << log;
  // said once
  const size_t said = log.find("plain text between its frames");
  ASSERT_NE(said, std::string::npos) << log;
  EXPECT_EQ(log.find("plain text between its frames", said + 1), std::string::npos) << log;
  // the robot was driven all along
  EXPECT_GT(r.result["robot_pose"]["y_m"].get<double>(), 0.02) << r.result["robot_pose"].dump();
}

TEST(AvrRunTest, AFirmwareThatNeverReadsLosesBytesAndTheRunSaysHowMany) {
  const std::string image = Image("rx_overflow");
  if (image.empty()) GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr missing";
  const testing::RunResult r =
      testing::UnimouseRun("--duration 0.2 --link avr:" + image, "unimouse_avr_rx");
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  // 6 bytes of encoder frames a step and 9 of ToF every 30 ms: 1221 bytes, 63 of them fit
  const std::regex counts("([0-9]+) bytes in, [0-9]+ out, ([0-9]+) RX overruns");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.outcome.output, m, counts)) << r.outcome.output;
  EXPECT_EQ(m[1], "63");
  EXPECT_GT(std::stoi(m[2]), 1000);
}

// tests/avr/watchdog.c arms the watchdog for 15 ms and hangs: the board resets every 16 ms or so
TEST(AvrRunTest, AWatchdogResetBootsTheBoardAgainAndTheRunGoesOn) {
  const std::string image = Image("watchdog");
  if (image.empty()) GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr missing";
  const testing::RunResult r = testing::UnimouseRun(
      "--maze none --duration 0.1 --no-pictures --link avr:" + image + " --link-set mcu=atmega328p",
      "unimouse_avr_watchdog");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["status"], "completed");
  EXPECT_EQ(r.result["restarts"], 0);  // a firmware that never spoke cannot start over
  EXPECT_NE(r.outcome.output.find("link: the emulated board was reset by the watchdog before "
                                  "t=0.0"),
            std::string::npos)
      << r.outcome.output;
}

TEST(AvrRunTest, ABoardThatKeepsResettingEndsTheRunAfterMaxRestarts) {
  const std::string image = Image("watchdog");
  if (image.empty()) GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr missing";
  const testing::RunResult r =
      testing::UnimouseRun("--maze none --duration 10 --no-pictures --link avr:" + image +
                               " --link-set mcu=atmega328p --link-set max_restarts=10",
                           "unimouse_avr_reset_storm");
  EXPECT_EQ(r.outcome.exit_code, 3) << r.outcome.output;
  EXPECT_EQ(r.result["status"], "fault");
  const std::string error = r.result["error"];
  EXPECT_NE(error.find(": the emulated board was reset 11 times, more than max_restarts (10)"),
            std::string::npos)
      << error;
}

TEST(AvrRunTest, AResetEndsTheRunWhenTheGraderSaysSo) {
  const std::string image = Image("watchdog");
  if (image.empty()) GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr missing";
  const testing::RunResult r =
      testing::UnimouseRun("--maze none --duration 1 --no-pictures --link avr:" + image +
                               " --link-set mcu=atmega328p --link-set board_reset=fail",
                           "unimouse_avr_reset_fails");
  EXPECT_EQ(r.outcome.exit_code, 3) << r.outcome.output;
  const std::string error = r.result["error"];
  EXPECT_NE(error.find("the emulated atmega328p stopped: the watchdog reset it at pc "),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace unimouse
