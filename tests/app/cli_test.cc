// SPDX-License-Identifier: GPL-3.0-or-later
// The `unimouse` program as a user meets it: exit codes, messages and files written.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "inline_assets.h"
#include "run_program.h"

namespace {

namespace fs = std::filesystem;

using unimouse::testing::Outcome;
using unimouse::testing::Unimouse;

class CliTest : public ::testing::Test {
 protected:
  // no TearDown: the process's temporary directory goes at its end, once every result.json
  // in it has been collected for the schema check (result_records.h)
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("unimouse_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }

  std::string Write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }

  fs::path dir_;
};

// a bundled maze's text
std::string ReadMaze(const std::string& name) {
  std::ifstream in(fs::path(UNIMOUSE_SOURCE_DIR) / "mazes" / (name + ".txt"));
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST_F(CliTest, RunWritesAResultWithPoseTimeAndSpeed) {
  const Outcome o = Unimouse("run --scenario none --duration 0.5 --seed 3 --out " + dir_.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("in maze japan2018 (16x16)"), std::string::npos) << o.output;
  std::ifstream in(dir_ / "result.json");
  const nlohmann::json result = nlohmann::json::parse(in);
  EXPECT_EQ(result["status"], "completed");
  EXPECT_EQ(result["steps"], 500);
  EXPECT_EQ(result["seed"], 3);
  EXPECT_NEAR(result["sim_time_s"].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(result["robot_pose"]["x_m"].get<double>(), 0.09, 1e-3);
  EXPECT_GT(result["real_time_factor"].get<double>(), 0);
  EXPECT_GT(result["wall_time_s"].get<double>(), 0);
}

TEST_F(CliTest, LinkParametersComeFromTheCommandLineAndAreCheckedLikeARobotFiles) {
  const std::string run = "run --maze none --duration 0.05 --no-pictures --out " + dir_.string() +
                          " --link pty --link-set ";
  Outcome o = Unimouse(run + "failsafe_s=0");
  EXPECT_EQ(o.exit_code, 0) << o.output;

  o = Unimouse(run + "failsafe=0");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("unimouse: error: --link-set failsafe=0: component 'link' "
                          "(unimouse.link): unknown parameter 'failsafe' (did you mean "
                          "'failsafe_s'?)"),
            std::string::npos)
      << o.output;

  o = Unimouse(run + "failsafe_s=-1");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--link-set failsafe_s=-1: component 'link' (unimouse.link): "
                          "failsafe_s must be at least 0, not -1"),
            std::string::npos)
      << o.output;

  o = Unimouse(run + "tof_full_scale_m=wide");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  o = Unimouse("run --maze none --duration 0.05 --out " + dir_.string() +
               " --link-set failsafe_s=0 --robot unimouse");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--link-set and --firmware-profile go with --link"), std::string::npos)
      << o.output;

  o = Unimouse("run --maze none --duration 0.05 --out " + dir_.string() +
               " --link pty --firmware-profile unimousesim-9");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--firmware-profile unimousesim-9: component 'link' (unimouse.link): "
                          "profile must be one of unimouse|unimousesim-0.1"),
            std::string::npos)
      << o.output;
}

TEST_F(CliTest, TheContestRunsInTheMazeThatMazeNames) {
  const Outcome o =
      Unimouse("run --scenario micromouse --maze japan2019 --duration 0.2 --out " + dir_.string());
  ASSERT_EQ(o.exit_code, 1) << o.output;  // undecided after 0.2 s
  std::ifstream in(dir_ / "result.json");
  const nlohmann::json result = nlohmann::json::parse(in);
  EXPECT_EQ(result["scenario"]["params"]["maze"], "japan2019");
  EXPECT_TRUE(result["maze"].get<std::string>().ends_with("mazes/japan2019.txt")) << result["maze"];
  EXPECT_EQ(result["scenario"]["reason"], "not decided when the run ended at 0.200 s");
}

TEST_F(CliTest, AMissingMazeNamedOnTheCommandLineIsBadInputWithAResult) {
  for (const std::string option : {"--set maze=no_such_maze", "--maze no_such_maze"}) {
    const Outcome o = Unimouse("run --scenario micromouse " + option + " --out " + dir_.string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find("parameter maze = no_such_maze (from the command line): "),
              std::string::npos)
        << o.output;
    std::ifstream in(dir_ / "result.json");
    EXPECT_EQ(nlohmann::json::parse(in)["exit_code"], 2);
  }
}

TEST_F(CliTest, MazeIsRefusedForAScenarioThatBuildsItsOwnWorld) {
  const Outcome o =
      Unimouse("run --scenario speed_control --maze japan2019 --out " + dir_.string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--maze japan2019: scenario 'speed_control' builds its own world and "
                          "has no maze parameter"),
            std::string::npos)
      << o.output;
}

TEST_F(CliTest, MazeAndSetMazeNamingDifferentMazesAreRefused) {
  const Outcome o = Unimouse("run --scenario micromouse --maze japan2019 --set maze=japan2018");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("name different mazes"), std::string::npos) << o.output;
}

TEST_F(CliTest, ARunInWhichNothingDrivesTheRobotSaysSo) {
  const Outcome o = Unimouse("run --maze none --duration 0.05 --out " + dir_.string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("warning: nothing drives the robot"), std::string::npos) << o.output;
}

TEST_F(CliTest, NoPictureOfTheFirmwaresMazeWhenNoFirmwareReportedOne) {
  const Outcome o = Unimouse("run --duration 0.05 --link pty --out " + dir_.string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(o.output.find("maze as the firmware saw it"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "maze.png"));
  EXPECT_TRUE(fs::exists(dir_ / "result.json"));
}

TEST_F(CliTest, ANegativeSeedIsRefused) {
  const Outcome o = Unimouse("run --seed -1 --out " + dir_.string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("the seed is a whole number, 0 or more"), std::string::npos) << o.output;
}

// the generated block of a document, between "<!-- unimouse ARGUMENTS -->" and "<!-- end -->",
// must be what `unimouse ARGUMENTS` prints now; returns that output
std::string ExpectCurrentBlock(const std::string& doc, const std::string& arguments) {
  const Outcome o = Unimouse(arguments);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  std::ifstream in(fs::path(UNIMOUSE_SOURCE_DIR) / doc);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string begin = "<!-- unimouse " + arguments + " -->\n", end = "<!-- end -->";
  const size_t from = text.find(begin), to = text.find(end, from);
  if (from == std::string::npos || to == std::string::npos) {
    ADD_FAILURE() << doc << " lacks the block " << begin;
    return o.output;
  }
  EXPECT_EQ(text.substr(from + begin.size(), to - from - begin.size()), o.output)
      << doc << " is stale: paste the output of `unimouse " << arguments << "`";
  return o.output;
}

TEST_F(CliTest, TheScenarioParameterTableOfTheDocsIsWhatTheScenariosDeclare) {
  const std::string table = ExpectCurrentBlock("docs/scenarios.md", "scenarios --markdown");
  EXPECT_NE(table.find("| `micromouse` | `maze` | string | `\"japan2018\"` |"), std::string::npos);
}

TEST_F(CliTest, TheRobotFileReferenceOfTheDocsIsTheSchemaTheLoaderEnforces) {
  const std::string reference = ExpectCurrentBlock("docs/robots.md", "robot-schema --markdown");
  // by hand, from the loader and the motor's parameters
  EXPECT_NE(reference.find("| `timestep_s` | number | s | 0.001 | [0.0001, 0.01] |"),
            std::string::npos)
      << reference;
  EXPECT_NE(reference.find("| `resistance_ohm` | number | ohm | 16.66667 |"), std::string::npos)
      << reference;
  EXPECT_NE(reference.find("#### `unimouse.link`"), std::string::npos);
}

TEST_F(CliTest, RunOnAnOpenFloor) {
  const Outcome o = Unimouse("run --maze none --duration 0.1 --out " + dir_.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("on an open floor"), std::string::npos) << o.output;
}

TEST_F(CliTest, CheckAcceptsTheBundledRobot) {
  const Outcome o = Unimouse("check unimouse");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("ok: robot 'unimouse', 4 bodies"), std::string::npos) << o.output;
}

TEST_F(CliTest, CheckAcceptsTheBundledHalfSizeRobot) {
  const Outcome o = Unimouse("check unimouse-half");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("ok: robot 'unimouse-half', 4 bodies"), std::string::npos) << o.output;
}

TEST_F(CliTest, CheckAcceptsTheBundledRobotsOfOtherLayouts) {
  Outcome o = Unimouse("check unimouse-skid");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("ok: robot 'unimouse-skid', 5 bodies, 5 joints, 4 actuators"),
            std::string::npos)
      << o.output;
  o = Unimouse("check unimouse-six");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(
      o.output.find("ok: robot 'unimouse-six', 4 bodies, 4 joints, 2 actuators, 14 components"),
      std::string::npos)
      << o.output;
}

TEST_F(CliTest, BadRobotFileExitsWithCode2AndOneLocatedLine) {
  const std::string path = Write("bad.yaml", "name: x\nchassis:\n  name: c\n  mass: 1\n");
  const Outcome o = Unimouse("check " + path);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.output, "unimouse: error: " + path + ":4:3: chassis: unknown key 'mass'\n");
}

TEST_F(CliTest, CheckLoadsAScenarioAndBuildsItsWorldWithoutRunningIt) {
  const Outcome o = Unimouse("check micromouse --set maze=japan2019");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("ok: scenario 'micromouse', "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("mazes/japan2019.txt (16x16)"), std::string::npos) << o.output;
}

TEST_F(CliTest, CheckReportsAScenariosMistakeAtItsLineWithExitCode2) {
  const std::string path =
      Write("typo.lua",
            "return sim.scenario { name = 'typo', run = function() end, world = function()\n"
            "  sim.robot_place { x_m = 0, y_m = 0, yaw = 0 }\n"
            "end }\n");
  const Outcome o = Unimouse("check " + path);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(":2: unknown key yaw in sim.robot_place, did you mean yaw_deg?"),
            std::string::npos)
      << o.output;
  // a missing maze named by --set is bad input too
  EXPECT_EQ(Unimouse("check micromouse --set maze=no_such_maze").exit_code, 2);
}

TEST_F(CliTest, CheckTakesDirectoriesReportingEveryFileAndExitingWithTheWorstCode) {
  fs::create_directories(dir_ / "class" / "lab2");
  const std::string robot = Write("class/good.yaml", unimouse::testing::ReadBundledRobot());
  const std::string bad = Write("class/lab2/bad.yaml", "name: x\nchassis:\n  name: c\n  mass: 1\n");
  const std::string scenario =
      Write("class/lab2/open.lua", "return sim.scenario { name = 'open', run = function() end }\n");
  Write("class/notes.txt", "not checked");
  const Outcome o = Unimouse("check " + (dir_ / "class").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(robot + ": ok: robot 'unimouse'"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(bad + ":4:3: chassis: unknown key 'mass'"), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find(scenario + ": ok: scenario 'open', 0 parameters, world: an open floor"),
            std::string::npos)
      << o.output;
  EXPECT_EQ(o.output.find("notes.txt"), std::string::npos) << o.output;
  EXPECT_EQ(Unimouse("check " + robot + " " + scenario).exit_code, 0);
}

TEST_F(CliTest, ARobotFileWhoseAliasHoldsItselfIsBadInputForCheckRunAndADirectory) {
  fs::create_directories(dir_ / "class");
  const std::string robot = Write("class/cycle.yaml", "a: &b [*b]\n");
  const std::string expected = robot +
                               ":1:4: this list or map holds an alias of itself (a cycle); a "
                               "value cannot contain itself";
  const Outcome check = Unimouse("check " + robot);
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_EQ(check.output, "unimouse: error: " + expected + "\n");

  const Outcome directory = Unimouse("check " + (dir_ / "class").string());
  EXPECT_EQ(directory.exit_code, 2) << directory.output;
  EXPECT_NE(directory.output.find(expected), std::string::npos) << directory.output;

  const fs::path out = dir_ / "out";
  const Outcome run = Unimouse("run --duration 0.1 --robot " + robot + " --out " + out.string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  std::ifstream in(out / "result.json");
  const nlohmann::json result = nlohmann::json::parse(in);
  EXPECT_EQ(result["status"], "error");
  EXPECT_EQ(result["exit_code"], 2);
  EXPECT_EQ(result["error"], expected);
}

// docs/robots.md: `unimouse check DIR` checks "a class's submissions", which are controllers
TEST_F(CliTest, CheckRecognisesTheLuaControllersOfAClassBesideItsScenarios) {
  fs::create_directories(dir_ / "class");
  std::ifstream speed(fs::path(UNIMOUSE_SOURCE_DIR) / "tests/scenarios/speed_controller.lua");
  const std::string good =
      Write("class/alice.lua", std::string(std::istreambuf_iterator<char>(speed), {}));
  Write("class/bob.lua", "return function(time_s)\n  sim.motor(\nend\n");
  const std::string scenario =
      Write("class/open.lua", "return sim.scenario { name = 'open', run = function() end }\n");
  const Outcome o = Unimouse("check " + (dir_ / "class").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(good + ": ok: controller"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("bob.lua:3: unexpected symbol"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(scenario + ": ok: scenario 'open'"), std::string::npos) << o.output;
  EXPECT_EQ(Unimouse("check " + good).exit_code, 0);
}

TEST_F(CliTest, CheckStartsNothingAndWritesNothing) {
  // the test process's own TMPDIR, which the program inherits, and the directory checked
  const fs::path tmp = fs::temp_directory_path();
  const auto entries = [](const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir)) names.push_back(e.path().string());
    std::sort(names.begin(), names.end());
    return names;
  };
  const std::vector<std::string> before = entries(tmp);
  const Outcome o = Unimouse("check " + std::string(UNIMOUSE_SOURCE_DIR) + "/scenarios " +
                             std::string(UNIMOUSE_SOURCE_DIR) + "/robots");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(entries(tmp), before);
}

// the bundled robot with one line changed
std::string BundledRobotWith(const std::string& line, const std::string& instead) {
  std::string robot = unimouse::testing::ReadBundledRobot();
  const size_t at = robot.find(line);
  EXPECT_NE(at, std::string::npos) << line;
  if (at != std::string::npos) robot.replace(at, line.size(), instead);
  return robot;
}

TEST_F(CliTest, CheckWarnsAboutARobotThatCannotStandAsBuilt) {
  Outcome o = Unimouse("check unimouse");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(o.output.find("warning"), std::string::npos) << o.output;

  // the caster 6 mm higher than the floor the wheels stand on (its centre 11 mm below the axle)
  const std::string lifted = Write(
      "lifted.yaml", BundledRobotWith("pos_m: [-0.055, 0, -0.011]", "pos_m: [-0.055, 0, -0.005]"));
  o = Unimouse("check " + lifted);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("warning: 'caster' is 6.0 mm above the floor at rest: only the wheels "
                          "touch it"),
            std::string::npos)
      << o.output;

  // the left wheel 3 mm higher than the right one
  const std::string wheel =
      Write("wheel.yaml", BundledRobotWith("pos_m: [0, 0.048, 0]", "pos_m: [0, 0.048, 0.003]"));
  o = Unimouse("check " + wheel);
  EXPECT_NE(o.output.find("warning: wheel 'left_wheel' is 3.0 mm above the floor at rest"),
            std::string::npos)
      << o.output;
}

TEST_F(CliTest, CheckRefusesAMotorOnABallJointAtTheActuatorsLine) {
  const std::string path =
      Write("ball.yaml",
            "name: ball\n"
            "chassis:\n"
            "  name: plate\n"
            "  geoms: [{ type: box, size_m: [0.1, 0.1, 0.02], mass_kg: 0.1 }]\n"
            "  bodies:\n"
            "    - name: caster\n"
            "      joint: { name: caster, type: ball }\n"
            "      geoms: [{ type: sphere, radius_m: 0.005, mass_kg: 0.01 }]\n"
            "actuators:\n"
            "  - { name: motor, joint: caster }\n");
  const Outcome o = Unimouse("check " + path);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output, "unimouse: error: " + path +
                          ":10:27: actuator 'motor': joint 'caster' is a ball joint; a motor "
                          "turns a hinge\n");
}

TEST_F(CliTest, CheckRefusesAMovingBodyWithoutMassAtItsGeoms) {
  const std::string path =
      Write("light.yaml",
            "name: light\n"
            "chassis:\n"
            "  name: plate\n"
            "  geoms: [{ type: box, size_m: [0.1, 0.1, 0.02], mass_kg: 0.1 }]\n"
            "  bodies:\n"
            "    - name: wheel\n"
            "      joint: { name: axle, type: hinge, axis: [0, 1, 0] }\n"
            "      geoms: [{ type: sphere, radius_m: 0.016 }]\n");
  const Outcome o = Unimouse("check " + path);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output, "unimouse: error: " + path +
                          ":8:14: body 'wheel': its geoms weigh 0 kg in all; give one a mass_kg\n");
}

TEST_F(CliTest, BadMazeFileExitsWithCode2) {
  const std::string path = Write("bad.txt", "o---o\n| X |\no---o\n");
  const Outcome o = Unimouse("run --maze " + path + " --out " + dir_.string());
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find(path + ":2:3: unexpected 'X'"), std::string::npos) << o.output;
}

TEST_F(CliTest, AnInterruptedRunStopsBetweenStepsWritesItsResultAndExitsWithCode3) {
  for (const std::string signal : {"INT", "TERM"}) {
    const std::string out = (dir_ / signal).string();
    // once the run has started (its log exists), the signal; the shell prints the exit code
    const Outcome o = Unimouse("run --maze none --duration 100000 --no-pictures --out " + out +
                               " >/dev/null 2>&1 & " + "pid=$!; while [ ! -e " + out +
                               "/log.txt ]; do sleep 0.05; done; sleep 0.3; kill -" + signal +
                               " $pid; wait $pid; echo exit=$?; true");
    EXPECT_NE(o.output.find("exit=3"), std::string::npos) << signal << ": " << o.output;
    std::ifstream in(fs::path(out) / "result.json");
    ASSERT_TRUE(in.good()) << signal;
    const nlohmann::json r = nlohmann::json::parse(in);
    EXPECT_EQ(r["status"], "interrupted");
    EXPECT_EQ(r["exit_code"], 3);
    EXPECT_EQ(r["error"].get<std::string>().rfind("interrupted by SIG" + signal + " at ", 0), 0u)
        << r.dump();
    EXPECT_LT(r["sim_time_s"].get<double>(), 100000);
  }
}

TEST_F(CliTest, AScenarioStuckInsideOneCCallEndsWithExitCode3AndAResultSayingWhy) {
  // comparing two long equal strings again and again: one instruction each, 60 MB of work
  const std::string scenario =
      Write("stuck.lua",
            "return sim.scenario { name = 'stuck', run = function() end, world = function()\n"
            "  local a, b = string.rep('x', 6e7), string.rep('x', 6e7)\n"
            "  while true do local same = a == b end\n"
            "end }\n");
  const auto start = std::chrono::steady_clock::now();
  const Outcome o = Unimouse("run --scenario " + scenario + " --out " + dir_.string());
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_EQ(o.exit_code, 3) << o.output;
  std::ifstream in(dir_ / "result.json");
  ASSERT_TRUE(in.good()) << o.output;
  const nlohmann::json r = nlohmann::json::parse(in);
  EXPECT_EQ(r["status"], "error");
  EXPECT_EQ(r["error"],
            "the scenario's world ran longer than 10 s of wall time in one call (work inside "
            "Lua's library that no count sees)");
}

TEST_F(CliTest, AReaderThatClosesItsPipeIsNotTheEndOfTheProcess) {
  // the summary is printed once the reader is gone: that used to end the process with SIGPIPE
  // (exit 141 through the pipeline); now the run ends as it would, with its result
  const std::string command = "bash -c 'set -o pipefail; " UNIMOUSE_BINARY
                              " run --maze none --duration 0.2 --no-pictures --out " +
                              dir_.string() + " 2>/dev/null | true; echo exit=$?'";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char said[64] = {};
  const size_t n = fread(said, 1, sizeof(said) - 1, pipe);
  pclose(pipe);
  EXPECT_EQ(std::string(said, n), "exit=0\n");
  EXPECT_TRUE(fs::exists(dir_ / "result.json"));
}

TEST_F(CliTest, AMazeFileNameThatIsNotUtf8IsReplacedInJson) {
  const std::string latin1 = Write("caf\xe9.txt", ReadMaze("japan2018"));
  const Outcome o = Unimouse("maze show --json " + latin1);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("caf\xef\xbf\xbd.txt"), std::string::npos) << o.output;
}

TEST_F(CliTest, MissingFilesAndBadOptionsExitWithCode2) {
  EXPECT_EQ(Unimouse("run --maze no_such_maze").exit_code, 2);
  EXPECT_EQ(Unimouse("run --duration -1").exit_code, 2);
  EXPECT_EQ(Unimouse("run --duration abc").exit_code, 2);
  EXPECT_EQ(Unimouse("frobnicate").exit_code, 2);
}

TEST_F(CliTest, AMisspeltCommandIsNamedWithTheNearestCommandAndExitCode2) {
  Outcome o = Unimouse("rnu");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("unimouse: error: unknown command 'rnu'; did you mean 'run'?"),
            std::string::npos)
      << o.output;
  // an option's value before it is not taken for the command
  o = Unimouse("--plugin-path /nowhere chekc robots");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("unknown command 'chekc'; did you mean 'check'?"), std::string::npos)
      << o.output;
  o = Unimouse("maze shwo japan2018");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("unknown command 'shwo' of 'maze'; did you mean 'show'?"),
            std::string::npos)
      << o.output;
}

TEST_F(CliTest, HelpForAnUnknownCommandIsBadInputNotTheProgramsHelp) {
  for (const char* command : {"rnu --help", "frobnicate --help", "maze shwo --help"}) {
    const Outcome o = Unimouse(command);
    EXPECT_EQ(o.exit_code, 2) << command << ": " << o.output;
    EXPECT_NE(o.output.find("unknown command"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("Usage"), std::string::npos) << o.output;
  }
}

// README: "`unimouse run` with no options is this job"; the robot, the maze and the duration
// change how the contest runs, not whether it runs
TEST_F(CliTest, MazeRobotAndDurationAloneKeepTheContestWithTheBundledFirmware) {
  const std::vector<std::string> runs = {"--maze japan2019 --duration 3", "--duration 3",
                                         "--robot unimouse --duration 3"};
  for (size_t i = 0; i < runs.size(); ++i) {
    const fs::path out = dir_ / std::to_string(i);
    const Outcome o = Unimouse("run " + runs[i] + " --no-pictures --out " + out.string());
    // the contest is not decided in 3 s
    EXPECT_EQ(o.exit_code, 1) << runs[i] << ": " << o.output;
    std::ifstream in(out / "result.json");
    const nlohmann::json result = nlohmann::json::parse(in);
    EXPECT_EQ(result["scenario"]["name"], "micromouse") << runs[i];
    EXPECT_EQ(result["driver"]["link"]["transport"], "inproc") << runs[i];
    EXPECT_NEAR(result["sim_time_s"].get<double>(), 3, 1e-9) << runs[i];
    // the firmware has set off from the start cell, (0.09, 0.09) facing north
    const double moved = std::hypot(result["robot_pose"]["x_m"].get<double>() - 0.09,
                                    result["robot_pose"]["y_m"].get<double>() - 0.09);
    EXPECT_GT(moved, 0.09) << runs[i] << ": " << result["robot_pose"].dump();
    EXPECT_EQ(o.output.find("nothing drives the robot"), std::string::npos) << o.output;
  }
  std::ifstream in(dir_ / "0" / "result.json");
  EXPECT_NE(nlohmann::json::parse(in)["maze"].get<std::string>().find("japan2019.txt"),
            std::string::npos);
}

TEST_F(CliTest, ScenarioNoneRunsTheRobotAlone) {
  const Outcome o =
      Unimouse("run --scenario none --duration 0.05 --no-pictures --out " + dir_.string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("warning: nothing drives the robot"), std::string::npos) << o.output;
  std::ifstream in(dir_ / "result.json");
  EXPECT_FALSE(nlohmann::json::parse(in).contains("scenario"));
}

TEST_F(CliTest, TheTracesRateAndChannelsAreRunOptionsAndZeroIsNoTrace) {
  const std::string run = "run --scenario none --maze none --duration 0.2 --no-pictures --out ";
  Outcome o = Unimouse(run + (dir_ / "none").string() + " --trace-period 0");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "none" / "trace.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "none" / "result.json"));

  o = Unimouse(run + (dir_ / "some").string() +
               " --trace-period 0.05 --trace-signals tof.front_m,left.command");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  std::ifstream in(dir_ / "some" / "trace.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_NE(header.find("tof.front_m"), std::string::npos) << header;
  EXPECT_NE(header.find("left.command"), std::string::npos) << header;
  EXPECT_EQ(header.find("battery.voltage_v"), std::string::npos) << header;
  std::vector<double> times;
  for (std::string row; std::getline(in, row);) times.push_back(std::stod(row));
  // a row every 0.05 s of the 0.2 s, not every 10 ms
  ASSERT_GE(times.size(), 4u);
  ASSERT_LE(times.size(), 5u);
  EXPECT_NEAR(times[1] - times[0], 0.05, 1e-9);

  o = Unimouse(run + (dir_ / "bad").string() + " --trace-signals no.such_signal");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("no.such_signal"), std::string::npos) << o.output;
}

TEST_F(CliTest, EverySubcommandHasHelp) {
  for (const char* command : {"--help", "run --help", "check --help", "plugins --help"}) {
    const Outcome o = Unimouse(command);
    EXPECT_EQ(o.exit_code, 0) << command;
    EXPECT_NE(o.output.find("Usage"), std::string::npos) << command;
  }
}

TEST_F(CliTest, PluginsListsTypesFromThePluginPath) {
  const Outcome o = Unimouse("--plugin-path " + std::string(FAKE_PLUGIN_DIR) + "/good plugins");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("fake.widget"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("- speed_m_per_s (number), default 1.5, [0, 10]: how fast"),
            std::string::npos)
      << o.output;
}

TEST_F(CliTest, PluginPathFromTheEnvironmentIsSearchedToo) {
  const Outcome o =
      Unimouse("plugins", "UNIMOUSE_PLUGIN_PATH=" + std::string(FAKE_PLUGIN_DIR) + "/good ");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("fake.widget"), std::string::npos) << o.output;
}

TEST_F(CliTest, ABadPluginIsRefusedInOneSentence) {
  const Outcome o =
      Unimouse("--plugin-path " + std::string(FAKE_PLUGIN_DIR) + "/wrong_abi plugins");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("was built for plugin ABI version 2"), std::string::npos) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
}

// lines of `text` that contain `part`
int LinesWith(const std::string& text, const std::string& part) {
  int n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST_F(CliTest, TheMainJobSaysLittleOnAPipeAndTheLogKeepsEveryReport) {
  const Outcome o = Unimouse("run --out " + dir_.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_LE(std::count(o.output.begin(), o.output.end(), '\n'), 30) << o.output;
  EXPECT_EQ(LinesWith(o.output, "debug walls"), 0) << o.output;
  EXPECT_NE(o.output.find("scenario micromouse: passed"), std::string::npos) << o.output;
  // no progress line on a pipe: nothing rewrites itself
  EXPECT_EQ(o.output.find('\r'), std::string::npos);
  // the firmware reported every cell it explored (japan2018 has 256); the log has each report
  EXPECT_GT(LinesWith(ReadFile(dir_ / "log.txt"), "debug walls"), 200);
}

TEST_F(CliTest, VerboseShowsTheFirmwaresReportsAsTheLogHasThem) {
  const Outcome o = Unimouse("run -v --duration 20 --out " + dir_.string());
  ASSERT_EQ(o.exit_code, 1) << o.output;  // the contest is not over in 20 s
  const int reports = LinesWith(ReadFile(dir_ / "log.txt"), "debug walls");
  EXPECT_GT(reports, 10);
  EXPECT_EQ(LinesWith(o.output, "debug walls"), reports) << o.output;
}

TEST_F(CliTest, OnATerminalAProgressLineShowsTimeSpeedAndTheHudAndGivesWayToLogLines) {
  // `script` gives the run a terminal, as a person at a console has
  const Outcome o =
      unimouse::testing::Shell("script -qec '" + std::string(UNIMOUSE_BINARY) +
                               " run --duration 60 --out " + dir_.string() + "' /dev/null");
  ASSERT_EQ(o.exit_code, 1) << o.output;
  const std::string erase = "\r\033[K";
  // a minute of contest takes more than a quarter of a second of wall time: shown at least
  // once, with the contest's HUD
  const size_t progress = o.output.find(erase + "[");
  ASSERT_NE(progress, std::string::npos) << o.output;
  const std::string line = o.output.substr(progress, o.output.find('\r', progress + 2) - progress);
  EXPECT_NE(line.find("x real time | time "), std::string::npos) << line;
  EXPECT_NE(line.find("of 600 s"), std::string::npos) << line;
  // the link's last line, at the end, starts on a cleared line
  EXPECT_NE(o.output.find(erase + "[   60.000 s] link: "), std::string::npos) << o.output;
  // the summary is on lines of its own
  EXPECT_NE(o.output.find("\n  result: "), std::string::npos) << o.output;
}

}  // namespace
