// SPDX-License-Identifier: GPL-3.0-or-later
// The native link: a firmware program started by the simulator, talking on its stdin and
// stdout, in lock-step. Deterministic; a firmware that stops answering is caught by the timeout
// and its process does not outlive the run.
#include <gtest/gtest.h>
#include <signal.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <regex>

#include "firmware_beliefs.h"
#include "inline_assets.h"
#include "plugin_rig.h"
#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

Maze Corridor() {
  std::string text = "o---o\n";
  for (int i = 0; i < 6; ++i) text += i == 5 ? "| S |\no---o\n" : "|   |\no   o\n";
  return ParseMazeText(text, "corridor.txt");
}

class NativeLinkTest : public ::testing::Test {
 protected:
  std::unique_ptr<Kernel> Make(const std::string& firmware_args, double timeout_s = 5) {
    const std::string yaml =
        testing::ReadBundledRobot() +
        "  - { type: unimouse.link, name: link, params: { transport: 'native:" +
        std::string(UNIMOUSE_TEST_FIRMWARE) + firmware_args +
        "', lockstep_timeout_s: " + std::to_string(timeout_s) + " } }\n";
    KernelOptions options;
    options.trust_robot_file = true;  // the test wrote the robot file
    options.seed = 5;
    options.log_sink = [this](double, int, const std::string&, const std::string& message) {
      std::smatch m;
      if (std::regex_search(message, m, std::regex("pid ([0-9]+)"))) pid_ = std::stoi(m[1]);
      messages_.push_back(message);
    };
    return testing::MakeKernel(yaml, &maze_, options);
  }

  const Maze maze_ = Corridor();
  int pid_ = -1;
  std::vector<std::string> messages_;
};

TEST_F(NativeLinkTest, AFirmwareProcessDrivesTheRobotDeterministically) {
  std::vector<mjtNum> first;
  for (int run = 0; run < 2; ++run) {
    auto kernel = Make("");
    for (int i = 0; i < 1500; ++i) kernel->Step();
    const mjData& d = kernel->state().data();
    std::vector<mjtNum> q(d.qpos, d.qpos + kernel->mj_model().nq);
    // it drove up the corridor and stopped short of the end wall (face at y = 1.074)
    EXPECT_GT(q[1], 0.5);
    EXPECT_LT(q[1] + 0.06, 1.074 - 0.2);
    if (run == 0) first = q;
  }
  EXPECT_NE(std::find(messages_.begin(), messages_.end(), "test firmware ready"), messages_.end());
  EXPECT_NE(std::find(messages_.begin(), messages_.end(),
                      "lock-step on: the simulation waits for the firmware"),
            messages_.end());
  auto kernel = Make("");
  for (int i = 0; i < 1500; ++i) kernel->Step();
  const mjData& d = kernel->state().data();
  EXPECT_EQ(std::memcmp(first.data(), d.qpos, first.size() * sizeof(mjtNum)), 0);
}

TEST_F(NativeLinkTest, AFirmwareThatStopsAnsweringIsCaughtAndItsProcessEnds) {
  auto kernel = Make(" --hang-at 40", 0.3);
  ASSERT_GT(pid_, 0);
  try {
    for (int i = 0; i < 100; ++i) kernel->Step();
    FAIL() << "the hang went unnoticed";
  } catch (const RuntimeFault& e) {
    EXPECT_NE(std::string(e.what()).find("did not finish its step at t=0.04"), std::string::npos)
        << e.what();
  }
  kernel.reset();
  EXPECT_EQ(::kill(pid_, 0), -1);  // gone, and reaped
  EXPECT_EQ(errno, ESRCH);
}

TEST_F(NativeLinkTest, TheRunCommandReportsAHungFirmwareWithExitCode3) {
  const std::string out = testing::FreshDirectory("native_hang");
  const auto o = testing::Unimouse("run --maze none --duration 1 --out " + out +
                                   " --link 'native:" + std::string(UNIMOUSE_TEST_FIRMWARE) +
                                   " --hang-at 100'");
  std::filesystem::remove_all(out);
  EXPECT_EQ(o.exit_code, 3) << o.output;
  EXPECT_NE(o.output.find("did not finish its step at t=0.100 s"), std::string::npos) << o.output;
}

// a batch tells a crashed submission from a hung one by these words (docs/batch.md)
TEST_F(NativeLinkTest, AFirmwareThatDiesOfASignalOrExitsIsReportedSoAtOnce) {
  for (const auto& [option, expected] :
       {std::pair{" --crash-at 30", "the firmware crashed: SIGABRT"},
        std::pair{" --exit-at 30", "the firmware exited with code 4"}}) {
    // a lock-step timeout far longer than the test: the end is known, not waited for
    auto kernel = Make(option, 60);
    const auto start = std::chrono::steady_clock::now();
    try {
      for (int i = 0; i < 100; ++i) kernel->Step();
      FAIL() << "the firmware's end went unnoticed";
    } catch (const RuntimeFault& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("at t=0.03"), std::string::npos) << e.what();
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
    kernel.reset();
  }
}

TEST_F(NativeLinkTest, WhatTheFirmwareReportsIsKeptAndDrawn) {
  {
    auto kernel = Make("");
    for (int i = 0; i < 10; ++i) kernel->Step();
    kernel->Finish();
  }
  const std::string out = testing::FreshDirectory("native_beliefs");
  const auto o = testing::Unimouse("run --maze japan2018 --duration 0.2 --out " + out +
                                   " --link native:" + std::string(UNIMOUSE_TEST_FIRMWARE));
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string beliefs = ReadTextFile(out + "/firmware_beliefs.json");
  EXPECT_EQ(beliefs,
            "{\"walls\": [[0, 0, 14, 15]],\n \"visited\": [[0, 0]],\n \"path\": [[0, 0], [0, 1], "
            "[0, 2]]}\n");
  EXPECT_TRUE(std::filesystem::exists(out + "/maze.png"));
  EXPECT_NE(ReadTextFile(out + "/maze.svg").find("class='closed-path'"), std::string::npos);
  // the report in the run's log; on the console only with -v
  EXPECT_NE(ReadTextFile(out + "/log.txt").find("debug path (0, 0) (0, 1) (0, 2)"),
            std::string::npos);
  EXPECT_EQ(o.output.find("debug path"), std::string::npos) << o.output;
  std::filesystem::remove_all(out);
}

// the viewer and the pictures gather the firmware's beliefs from the link's typed reports
TEST_F(NativeLinkTest, WhatTheFirmwareReportsReachesTheHostAsTypedReports) {
  auto kernel = Make("");
  FirmwareBeliefs beliefs;
  std::vector<double> values;
  kernel->AddReportListener([&](const std::string& source, int, const unimouse_report& r) {
    EXPECT_EQ(source, "link");
    if (!beliefs.Apply(r)) values.push_back(r.value);
  });
  for (int i = 0; i < 10; ++i) kernel->Step();
  kernel->Finish();
  // what the test firmware sends: walls (0, 0) E S W of N E S W known, visited (0, 0), a path
  ASSERT_EQ(beliefs.walls.size(), 1u);
  EXPECT_EQ(beliefs.walls.begin()->first, std::make_pair(0, 0));
  EXPECT_EQ(beliefs.walls.begin()->second.walls, 14);
  EXPECT_EQ(beliefs.walls.begin()->second.known, 15);
  EXPECT_EQ(beliefs.visited, (std::vector<Cell>{{0, 0}}));
  EXPECT_EQ(beliefs.path, (std::vector<Cell>{{0, 0}, {0, 1}, {0, 2}}));
  // a named value is a report too, though not about the maze
  EXPECT_EQ(values, std::vector<double>{1.5});
}

TEST_F(NativeLinkTest, WhatASketchPrintsIsItsLogAndLeavesTheProtocolAlone) {
  const std::string out = testing::FreshDirectory("native_printf");
  const auto o = testing::Unimouse("run --maze none --duration 0.35 --out " + out +
                                   " --link native:" + std::string(UNIMOUSE_PRINTING_FIRMWARE));
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string log = ReadTextFile(out + "/log.txt");
  // each line at the step the sketch printed it, as a line the firmware logged
  for (const char* line :
       {"0.100000\tlink\tprintf at 100 ms\n", "0.100000\tlink\tcout at 100 ms\n",
        "0.300000\tlink\tprintf at 300 ms\n", "0.300000\tlink\tcout at 300 ms\n"}) {
    EXPECT_NE(log.find(line), std::string::npos) << line << " not in\n" << log;
  }
  EXPECT_EQ(log.find("unknown frame id"), std::string::npos) << log;
  EXPECT_NE(log.find(" frames from the firmware, 0 unknown bytes; 0 bytes dropped"),
            std::string::npos)
      << log;
  EXPECT_EQ(log.find("at 400 ms"), std::string::npos) << log;
}

TEST_F(NativeLinkTest, TheRunCommandRunsLockstepFirmwareFasterThanRealTime) {
  const std::string out = testing::FreshDirectory("native_fast");
  const auto o = testing::Unimouse("run --maze none --duration 3 --out " + out +
                                   " --link native:" + std::string(UNIMOUSE_TEST_FIRMWARE));
  std::filesystem::remove_all(out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(o.output, m, std::regex("([0-9.]+) s wall time"))) << o.output;
  EXPECT_LT(std::stod(m[1]), 3.0);
}

}  // namespace
}  // namespace unimouse
