// SPDX-License-Identifier: GPL-3.0-or-later
// Several robots in one run: `unimouse run --robot A [--link ...] --robot B ...`, the race, the
// robots list of result.json, and the mistakes a command line with several robots can make.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

const std::string kModule = std::string(UNIMOUSE_FIRMWARE_DIR) + "/micromouse.so";
const std::string kJumper = UNIMOUSE_SOURCE_DIR "/tests/scenarios/race_jumping_controller.lua";

// what a run with several robots decided, and where each robot ended
std::string Summary(const nlohmann::json& r) {
  std::string out =
      r["scenario"]["reason"].get<std::string>() + " " + r["scenario"]["records"].dump();
  for (const auto& robot : r["robots"]) out += " " + robot["pose"].dump();
  return out + " " + r["sim_time_s"].dump();
}

TEST(SeveralRobotsTest, TwoCopiesOfTheBundledFirmwareRaceInAllJapan2018TheSameWayEveryTime) {
  const std::string args =
      "--scenario race --no-pictures --robot unimouse --link inproc:" + kModule +
      " --robot unimouse --link inproc:" + kModule;
  std::string first;
  for (int run = 0; run < 2; ++run) {
    const testing::RunResult r = testing::UnimouseRun(args, "race_two_firmwares");
    ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
    // the two robots of one file are told apart by name; each reaches the goal from its corner
    ASSERT_EQ(r.result["robots"].size(), 2u);
    EXPECT_EQ(r.result["robots"][0]["name"], "unimouse");
    EXPECT_EQ(r.result["robots"][1]["name"], "unimouse-2");
    const auto& records = r.result["scenario"]["records"]["robots"];
    ASSERT_EQ(records.size(), 2u);
    EXPECT_TRUE(records[0].contains("arrived_s")) << records;
    EXPECT_TRUE(records[1].contains("arrived_s")) << records;
    for (const auto& robot : r.result["robots"]) {
      EXPECT_EQ(robot["driver"]["link"]["transport"], "inproc");
    }
    if (run == 0) {
      first = Summary(r.result);
    } else {
      EXPECT_EQ(Summary(r.result), first) << "run " << run;
    }
  }  // the same firmware as two programs in lock-step runs the same race to the bit
  const std::string native = std::string(UNIMOUSE_FIRMWARE_DIR) + "/micromouse";
  const testing::RunResult r = testing::UnimouseRun(
      "--scenario race --no-pictures --robot unimouse --link native:" + native +
          " --robot unimouse --link native:" + native,
      "race_two_programs");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(Summary(r.result), first);
}

TEST(SeveralRobotsTest, AFirmwareRacesALuaControllerThatDrivesOnlyItsOwnRobot) {
  // the controller jumps its robot 14 cells, one each 0.1 s: in a goal cell at 1.4 s, and the
  // firmware's robot, which has not arrived by then, loses
  const testing::RunResult r = testing::UnimouseRun(
      "--scenario race --no-pictures --set time_limit_s=20 --robot unimouse --link inproc:" +
          kModule + " --robot unimouse --name jumper --controller " + kJumper,
      "race_controller");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "passed");
  const std::string reason = r.result["scenario"]["reason"];
  EXPECT_EQ(reason.rfind("jumper wins in 1.4", 0), 0u) << reason;
  EXPECT_NEAR(r.result["scenario"]["scores"]["winning_time_s"].get<double>(), 1.4, 0.002);
  EXPECT_EQ(r.result["robots"][1]["name"], "jumper");
  EXPECT_NE(r.result["robots"][1]["driver"]["controller"], nullptr);
  EXPECT_EQ(r.result["robots"][1]["driver"]["link"], nullptr);
  // the jumper stands in the goal cell (8, 8), placed there by its controller alone
  EXPECT_NEAR(r.result["robots"][1]["pose"]["x_m"].get<double>(), 0.09 + 0.18 * 8, 1e-3);
  EXPECT_NEAR(r.result["robots"][1]["pose"]["y_m"].get<double>(), 0.09 + 0.18 * 8, 1e-3);
}

TEST(SeveralRobotsTest, OneRobotsFirmwareCrashingEndsTheRunWithExitCode3NamingThatRobot) {
  const testing::RunResult r = testing::UnimouseRun(
      "--maze japan2018 --scenario none --duration 1 --no-pictures --robot unimouse --link "
      "inproc:" +
          kModule + " --robot unimouse --name crasher --start 15,15,S --link inproc:" +
          UNIMOUSE_TEST_BINARY_DIR "/null_pointer_firmware.so",
      "crash_one_of_two");
  EXPECT_EQ(r.outcome.exit_code, 3) << r.outcome.output;
  ASSERT_TRUE(r.result.is_object()) << r.outcome.output;
  EXPECT_EQ(r.result["status"], "fault");
  const std::string error = r.result["error"];
  EXPECT_NE(error.find("component 'crasher/link'"), std::string::npos) << error;
}

TEST(SeveralRobotsTest, MistakesOfACommandLineWithSeveralRobotsAreBadInputWithAResult) {
  const struct {
    std::string args;
    std::string error;
  } cases[] = {
      {"--robot unimouse --robot unimouse --scenario none --maze japan2018",
       "robots 'unimouse' and 'unimouse-2' both start in cell (0, 0): give one of them --start "
       "X,Y,H"},
      {"--link pty --robot unimouse --robot unimouse --start 1,1,N",
       "--link pty comes before the first --robot: with several robots, each robot's options "
       "follow its --robot"},
      {"--robot unimouse --name a --robot unimouse --name a --start 3,3,N",
       "--name a is given to two robots; names must differ"},
      {"--scenario race --robot unimouse",
       "scenario 'race' needs at least 2 robots, and the run has 1: give --robot FILE once for "
       "each (docs/scenarios.md)"},
      {"--robot unimouse --robot unimouse --start 1,1,Q",
       "--start 1,1,Q: write a cell and a heading, X,Y,H, e.g. 15,15,S (H one of N, E, S, W)"},
  };
  for (const auto& c : cases) {
    const testing::RunResult r = testing::UnimouseRun(c.args + " --no-pictures", "bad_robots");
    EXPECT_EQ(r.outcome.exit_code, 2) << c.args << "\n" << r.outcome.output;
    EXPECT_NE(r.outcome.output.find("unimouse: error: " + c.error + "\n"), std::string::npos)
        << c.args << "\n"
        << r.outcome.output;
    ASSERT_TRUE(r.result.is_object()) << c.args;
    EXPECT_EQ(r.result["status"], "error");
    EXPECT_EQ(r.result["error"], c.error);
  }
}

TEST(SeveralRobotsTest, TheCommandsTheDocsShowRunAsWritten) {
  for (const auto& [doc, after] : {std::pair{"docs/robots.md", "### Several robots in one world"},
                                   std::pair{"docs/scenarios.md", "### The race"}}) {
    const std::vector<std::string> commands = testing::DocumentedCommands(doc, after);
    ASSERT_EQ(commands.size(), 1u) << doc;
    const std::string dir = testing::FreshDirectory("documented_robots");
    const testing::Outcome o = testing::RunDocumented(commands[0], dir);
    EXPECT_EQ(o.exit_code, 0) << doc << "\n" << commands[0] << "\n" << o.output;
    const nlohmann::json r = nlohmann::json::parse(ReadTextFile(dir + "/out/result.json"));
    EXPECT_EQ(r["robots"].size(), 2u) << doc;
  }
}

}  // namespace
}  // namespace unimouse
