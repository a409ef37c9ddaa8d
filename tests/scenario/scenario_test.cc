// SPDX-License-Identifier: GPL-3.0-or-later
// Scenarios as users run them: the speed-control challenge passes a correct controller and
// fails wrong ones with the right reason; the sandbox holds; script errors and bad parameters
// give their location and exit code; the same seed gives the same result; what a scenario
// reports keeps its Lua types; the moments it marks (sim.event) reach the recording and the log.
#include "scenario.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

using testing::Unimouse;

const std::string kTests = UNIMOUSE_SOURCE_DIR "/tests/scenarios/";

using ScenarioRun = testing::RunResult;

// a run in an output directory of the test's own
ScenarioRun Scenario(const std::string& arguments) {
  return testing::UnimouseRun(
      arguments, "unimouse_scenario_" +
                     std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
}

TEST(SpeedControlScenarioTest, ACorrectControllerPasses) {
  const ScenarioRun r =
      Scenario("--scenario speed_control --controller " + kTests + "speed_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "passed");
  EXPECT_GE(r.result["scenario"]["scores"]["held_s"].get<double>(), 5.0);
  EXPECT_EQ(r.result["scenario"]["params"]["speed_m_per_s"], 1.0);
}

TEST(SpeedControlScenarioTest, ASlowControllerFailsAsTooSlow) {
  const ScenarioRun r = Scenario("--scenario speed_control --set time_limit_s=6 --controller " +
                                 kTests + "too_slow_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "failed");
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind("too slow", 0), 0u)
      << r.result["scenario"]["reason"];
}

TEST(SpeedControlScenarioTest, TurningClockwiseFailsAsTheWrongWay) {
  const ScenarioRun r = Scenario("--scenario speed_control --set time_limit_s=6 --controller " +
                                 kTests + "wrong_way_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind("turning the wrong way", 0), 0u)
      << r.result["scenario"]["reason"];
}

TEST(SpeedControlScenarioTest, ParametersChangeTheChallenge) {
  // a 2 s hold at the same speeds is passed sooner
  const ScenarioRun r = Scenario("--scenario speed_control --set hold_s=2 --controller " + kTests +
                                 "speed_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_LT(r.result["sim_time_s"].get<double>(), 4.0);
}

TEST(ScenarioSandboxTest, TheFileSystemIsOutOfReach) {
  const ScenarioRun r = Scenario("--scenario " + kTests + "uses_io.lua");
  EXPECT_EQ(r.outcome.exit_code, 3);
  EXPECT_NE(r.outcome.output.find(kTests + "uses_io.lua:6: attempt to index a nil value (global "
                                           "'io')"),
            std::string::npos)
      << r.outcome.output;
}

TEST(ScenarioSandboxTest, AnEndlessLoopIsStoppedWithItsLocation) {
  const ScenarioRun r = Scenario("--scenario " + kTests + "endless_loop.lua");
  EXPECT_EQ(r.outcome.exit_code, 3);
  EXPECT_NE(r.outcome.output.find(kTests + "endless_loop.lua:8: instruction budget exhausted"),
            std::string::npos)
      << r.outcome.output;
}

TEST(ScenarioSandboxTest, CatchingTheBudgetsErrorInAnEndlessLoopStillStopsIt) {
  const ScenarioRun r = Scenario("--scenario " + kTests + "swallow_budget.lua");
  EXPECT_EQ(r.outcome.exit_code, 3);
  EXPECT_NE(r.outcome.output.find(kTests + "swallow_budget.lua:7: instruction budget exhausted"),
            std::string::npos)
      << r.outcome.output;
}

TEST(ScenarioSandboxTest, AScenarioTableWhoseLookupsFailIsAScriptErrorNotACrash) {
  const ScenarioRun r = Scenario("--scenario " + kTests + "failing_index.lua");
  EXPECT_EQ(r.outcome.exit_code, 3) << r.outcome.output;
  EXPECT_NE(r.outcome.output.find("failing_index.lua:5: there is no name\n"), std::string::npos)
      << r.outcome.output;
}

TEST(ScenarioSandboxTest, SyntaxAndRuntimeErrorsGiveFileLineAndExitCode3) {
  ScenarioRun r = Scenario("--scenario " + kTests + "syntax_error.lua");
  EXPECT_EQ(r.outcome.exit_code, 3);
  EXPECT_NE(r.outcome.output.find(kTests + "syntax_error.lua:5: unexpected symbol near 'then'"),
            std::string::npos)
      << r.outcome.output;
  r = Scenario("--scenario " + kTests + "runtime_error.lua");
  EXPECT_EQ(r.outcome.exit_code, 3);
  EXPECT_NE(r.outcome.output.find(kTests + "runtime_error.lua:4: attempt to index a nil value"),
            std::string::npos)
      << r.outcome.output;
  // the run's record survives the error, with the whole Lua traceback: the helper, and run's call
  EXPECT_NEAR(r.result["sim_time_s"].get<double>(), 0.5, 0.002);
  const std::string traceback = r.result["scenario"].value("traceback", "");
  EXPECT_NE(traceback.find("stack traceback:"), std::string::npos) << traceback;
  EXPECT_NE(traceback.find("runtime_error.lua:4: in "), std::string::npos) << traceback;
  EXPECT_NE(traceback.find("runtime_error.lua:11: in "), std::string::npos) << traceback;
}

TEST(ScenarioSandboxTest, BadParametersAreBadInput) {
  ScenarioRun r = Scenario("--scenario speed_control --set hold_s=long");
  EXPECT_EQ(r.outcome.exit_code, 2);
  EXPECT_NE(r.outcome.output.find("--set hold_s=long: 'hold_s' is a number"), std::string::npos);
  r = Scenario("--scenario speed_control --set holds=3");
  EXPECT_EQ(r.outcome.exit_code, 2);
  EXPECT_NE(r.outcome.output.find("has no parameter 'holds'"), std::string::npos);
  r = Scenario("--scenario speed_control --set hold_s");
  EXPECT_EQ(r.outcome.exit_code, 2);
  r = Scenario("--scenario " + kTests + "random_numbers.lua --set enabled=maybe");
  EXPECT_EQ(r.outcome.exit_code, 2);
}

TEST(ScenarioSandboxTest, RandomNumbersComeFromTheSeedAndTheSameSeedGivesTheSameResult) {
  const ScenarioRun a =
      Scenario("--seed 4 --scenario " + kTests + "random_numbers.lua --set label=x");
  const ScenarioRun b =
      Scenario("--seed 4 --scenario " + kTests + "random_numbers.lua --set label=x");
  const ScenarioRun c =
      Scenario("--seed 5 --scenario " + kTests + "random_numbers.lua --set label=x");
  ASSERT_EQ(a.outcome.exit_code, 0) << a.outcome.output;
  EXPECT_EQ(a.result["scenario"], b.result["scenario"]);
  EXPECT_EQ(a.result["robot_pose"], b.result["robot_pose"]);
  EXPECT_NE(a.result["scenario"]["reason"], c.result["scenario"]["reason"]);
  EXPECT_EQ(a.result["scenario"]["reason"].get<std::string>().rfind("x true ", 0), 0u);
}

TEST(ScenarioLifecycleTest, FinishSeesHowTheRunEndedAndMayDecideAnUndecidedOne) {
  const ScenarioRun timed_out = Scenario("--scenario " + kTests + "finish_hook.lua");
  EXPECT_EQ(timed_out.outcome.exit_code, 0) << timed_out.outcome.output;
  EXPECT_EQ(timed_out.result["scenario"]["reason"], "decided in finish");
  EXPECT_EQ(timed_out.result["scenario"]["scores"]["was_decided"], 0);
  // the run lasts time_limit_s plus the second a scenario has to give its own reason
  EXPECT_NEAR(timed_out.result["scenario"]["scores"]["finished_at_s"].get<double>(), 2.0, 0.002);

  const ScenarioRun decided =
      Scenario("--scenario " + kTests + "finish_hook.lua --set decide_in_run=true");
  EXPECT_EQ(decided.outcome.exit_code, 0) << decided.outcome.output;
  EXPECT_EQ(decided.result["scenario"]["reason"], "decided in run");
  EXPECT_EQ(decided.result["scenario"]["scores"]["was_decided"], 1);
  EXPECT_NEAR(decided.result["scenario"]["scores"]["finished_at_s"].get<double>(), 0.25, 0.003);
}

TEST(ScenarioSandboxTest, TheSameSeedGivesTheSameResultJsonButForTheWallClock) {
  // a run with physics, contacts, gates and events: everything but the wall-clock fields repeats
  auto run = [] {
    ScenarioRun r =
        Scenario("--seed 9 --scenario slalom --controller " + kTests + "slalom_controller.lua");
    EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
    EXPECT_GT(r.result.value("wall_time_s", -1.0), 0);
    r.result.erase("wall_time_s");
    r.result.erase("real_time_factor");
    r.result.erase("wall_time_split_s");
    return r.result;
  };
  const nlohmann::json first = run();
  EXPECT_EQ(first, run());
}

TEST(WallDistanceScenarioTest, AProportionalControllerOnTheLeftSensorPasses) {
  const ScenarioRun r =
      Scenario("--scenario wall_distance --controller " + kTests + "wall_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "passed");
  // it ends where it should: within 10 % of 0.5 m from the wall's face at x = 0
  EXPECT_NEAR(r.result["robot_pose"]["x_m"].get<double>(), 0.5, 0.05);
}

TEST(WallDistanceScenarioTest, AimingForTheWrongDistanceFails) {
  const ScenarioRun r = Scenario("--scenario wall_distance --set time_limit_s=15 --controller " +
                                 kTests + "wrong_distance_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind("wrong distance", 0), 0u)
      << r.result["scenario"]["reason"];
}

TEST(WallDistanceScenarioTest, StandingStillAtTheRightDistanceIsNotEnough) {
  const ScenarioRun r = Scenario("--scenario wall_distance --set start_m=0.5 --set time_limit_s=8");
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind("not moving along the wall", 0),
            0u)
      << r.result["scenario"]["reason"];
}

TEST(MicromouseScenarioTest, RunsBetweenStartAndGoalAreTimedAndTheBestCounts) {
  const ScenarioRun r = Scenario("--scenario micromouse --set contest_s=12 --controller " + kTests +
                                 "scripted_mouse.lua");
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  const auto& scores = r.result["scenario"]["scores"];
  EXPECT_EQ(scores["runs"], 2);
  EXPECT_NEAR(scores["best_run_s"].get<double>(), 2.0, 0.002);
  EXPECT_NEAR(scores["time_used_s"].get<double>(), 12.0, 0.002);
  // the contest ended at 1 + 12 s, in the middle of run 3 (the scenario sees the controller's
  // moves a step later, and the run stops the step after the decision)
  EXPECT_NEAR(r.result["sim_time_s"].get<double>(), 13.0, 0.005);
  EXPECT_NE(r.result["scenario"]["reason"].get<std::string>().find("the time ran out during run 3"),
            std::string::npos)
      << r.result["scenario"]["reason"];
}

TEST(MicromouseScenarioTest, MaxRunsEndsTheContestEarly) {
  const ScenarioRun r = Scenario("--scenario micromouse --set max_runs=1 --controller " + kTests +
                                 "scripted_mouse.lua");
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["scores"]["runs"], 1);
  EXPECT_NEAR(r.result["scenario"]["scores"]["best_run_s"].get<double>(), 3.0, 0.002);
}

TEST(MicromouseScenarioTest, ARobotThatNeverLeavesTheStartFails) {
  const ScenarioRun r = Scenario("--scenario micromouse --set start_within_s=2");
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"], "never left the start cell in 2 s");
}

TEST(MicromouseScenarioTest, TheFirmwareCanEndTheContestByLoggingALine) {
  // the test firmware greets at start, before the robot moves: the contest ends with no runs
  const ScenarioRun r =
      Scenario("--scenario micromouse --set 'end_on_log=test firmware ready' --link native:" +
               std::string(UNIMOUSE_TEST_FIRMWARE));
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_LT(r.result["sim_time_s"].get<double>(), 0.1);
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind("no run reached the goal", 0),
            0u)
      << r.result["scenario"]["reason"];
}

// the output directory of Scenario(...) in the test that runs
std::string ScenarioOut() {
  return (std::filesystem::temp_directory_path() /
          ("unimouse_scenario_" +
           std::string(::testing::UnitTest::GetInstance()->current_test_info()->name())))
      .string();
}

// the /events of a run's recording, each with its time, as the tests' own MCAP reader
// (tests/support/mcap_reader.py) reads them, checking each against its channel's schema
std::vector<std::pair<double, nlohmann::json>> RecordedEvents(const std::string& out) {
  const std::string complaint = out + "/reader.err";
  const testing::Outcome o = testing::Shell(
      std::string(UNIMOUSE_PYTHON3) + " " UNIMOUSE_SOURCE_DIR "/tests/support/mcap_reader.py '" +
      out + "/run.mcap' 2>'" + complaint + "'");
  EXPECT_EQ(o.exit_code, 0) << ReadTextFile(complaint);
  std::vector<std::pair<double, nlohmann::json>> events;
  if (o.exit_code != 0) return events;
  const nlohmann::json recording = nlohmann::json::parse(o.output);
  int channel = -1;
  for (const nlohmann::json& c : recording["channels"]) {
    if (c["topic"] == "/events") channel = c["id"];
  }
  for (const nlohmann::json& m : recording["messages"]) {
    if (m["channel_id"] == channel) {
      events.emplace_back(m["log_time"].get<double>() * 1e-9, m["data"]);
    }
  }
  return events;
}

// the lines log.txt has from the scenario, each with its time
std::vector<std::pair<double, std::string>> ScenarioLogLines(const std::string& out) {
  std::vector<std::pair<double, std::string>> lines;
  std::istringstream log(ReadTextFile(out + "/log.txt"));
  for (std::string line; std::getline(log, line);) {
    const size_t tab = line.find('\t');
    if (tab == std::string::npos || line.compare(tab, 10, "\tscenario\t") != 0) continue;
    lines.emplace_back(std::stod(line.substr(0, tab)), line.substr(tab + 10));
  }
  return lines;
}

TEST(ScenarioEventTest, MarkedMomentsReachTheRecordingAndTheLogInOrderAtTheirTimes) {
  const ScenarioRun r = Scenario("--scenario " + kTests + "events.lua");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  // the times are the script's waits; a text is cut at 500 bytes, saying how long it was
  const std::string robot = r.result["robots"][0]["name"];
  const struct {
    double time_s;
    std::string kind, robot, text;
  } marked[] = {{0.25, "first", "", "a quarter of a second in"},
                {0.25, "first", "", "at the same moment"},
                {0.75, "about_robot_1", robot, "three quarters of a second in"},
                {1.0, "long", "", std::string(500, 'x') + "... (1500 bytes in all)"}};
  const auto events = RecordedEvents(ScenarioOut());
  ASSERT_EQ(events.size(), std::size(marked));
  for (size_t i = 0; i < events.size(); ++i) {
    const nlohmann::json& e = events[i].second;
    EXPECT_NEAR(events[i].first, marked[i].time_s, 1e-6) << i;
    EXPECT_EQ(e["kind"], marked[i].kind) << i;
    EXPECT_EQ(e["robot"], marked[i].robot) << i;
    EXPECT_EQ(e["text"], marked[i].text) << i;
    EXPECT_EQ(e["data"], nlohmann::json::object()) << i;
  }
  // and each a line of the log at the same time, as print writes one, before the verdict
  const auto lines = ScenarioLogLines(ScenarioOut());
  ASSERT_EQ(lines.size(), std::size(marked) + 1);
  for (size_t i = 0; i < std::size(marked); ++i) {
    EXPECT_NEAR(lines[i].first, events[i].first, 1e-6) << i;
    EXPECT_EQ(lines[i].second, marked[i].text) << i;
  }
  EXPECT_EQ(lines.back().second, "passed: marked");
}

TEST(ScenarioEventTest, BadArgumentsAreOneScriptErrorAtTheScenariosLine) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "unimouse_bad_event.lua").string();
  const std::string not_a_word = "' is not a word of lowercase letters, digits and _ (at most 32)";
  const std::pair<std::string, std::string> misuses[] = {
      {"sim.event('Goal', 'x')", "sim.event: kind 'Goal" + not_a_word},
      {"sim.event('', 'x')", "sim.event: kind '" + not_a_word},
      {"sim.event('run start', 'x')", "sim.event: kind 'run start" + not_a_word},
      {"sim.event(string.rep('a', 33), 'x')",
       "sim.event: kind '" + std::string(33, 'a') + not_a_word},
      {"sim.event('contact', 'x')", "sim.event: kind 'contact' is the run's own; give another"},
      {"sim.event('goal')", "bad argument #2 to 'sim.event' (string expected, got no value)"},
      {"sim.event('goal', {})", "bad argument #2 to 'sim.event' (string expected, got table)"},
      {"sim.event('goal', 'x', 'nobody')", "no robot named 'nobody' (the run has: unimouse)"},
  };
  for (const auto& [misuse, message] : misuses) {
    WriteTextFile(path,
                  "return sim.scenario { name = 'bad_event', run = function()\n"
                  "  sim.wait(0.01)\n  " +
                      misuse + "\n  sim.pass('went on')\nend }\n");
    const ScenarioRun r = Scenario("--scenario " + path);
    EXPECT_EQ(r.outcome.exit_code, 3) << misuse << "\n" << r.outcome.output;
    // the message names the stage the script was in
    EXPECT_EQ(r.result.value("error", ""), path + ":3: " + message + " (in run)") << misuse;
    EXPECT_EQ(RecordedEvents(ScenarioOut()).size(), 0u) << misuse;
  }
  // a kind of 32 is a word still
  WriteTextFile(path, "return sim.scenario { name = 'event32', run = function()\n  sim.event('" +
                          std::string(32, 'a') + "', 'x')\n  sim.pass('marked')\nend }\n");
  EXPECT_EQ(Scenario("--scenario " + path).outcome.exit_code, 0);
  EXPECT_EQ(RecordedEvents(ScenarioOut()).size(), 1u);
}

TEST(ScenarioEventTest, ARunKeeps10000EventsAndCountsTheRest) {
  // 4 events, then 10,000 more in two ticks: the last 4 are left out of the recording and the log
  const ScenarioRun r = Scenario("--scenario " + kTests + "events.lua --set flood=10000");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  const auto events = RecordedEvents(ScenarioOut());
  ASSERT_EQ(events.size(), 10'000u);
  EXPECT_EQ(events.back().second["text"], "flood 9996");
  EXPECT_NEAR(events.back().first, 1.5, 1e-6);
  const std::string warning =
      "sim.event: more than 10000 events in a run: later ones are counted, not recorded";
  int warned = 0;
  for (const nlohmann::json& w : r.result["warnings"]) warned += w == "scenario: " + warning;
  EXPECT_EQ(warned, 1) << r.result["warnings"];
  const auto lines = ScenarioLogLines(ScenarioOut());
  int floods = 0;
  for (const auto& [time_s, text] : lines) floods += text.rfind("flood ", 0) == 0;
  EXPECT_EQ(floods, 10'000 - 4);
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[lines.size() - 3].second, "warning: " + warning);
  EXPECT_EQ(lines[lines.size() - 2].second, "passed: marked");
  EXPECT_EQ(lines.back().second,
            "sim.event: 4 events after the first 10000 were counted, not recorded");
}

TEST(ScenarioEventTest, FirmwareLogLinesArriveAsEvents) {
  const ScenarioRun r = Scenario("--scenario " + kTests + "firmware_hello.lua --link native:" +
                                 std::string(UNIMOUSE_TEST_FIRMWARE));
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind(
                "heard 'test firmware ready' at 0.0", 0),
            0u)
      << r.result["scenario"]["reason"];
  // and a line that is not what the scenario expects fails it
  const ScenarioRun wrong =
      Scenario("--scenario " + kTests + "firmware_hello.lua --set expect=hello --link native:" +
               std::string(UNIMOUSE_TEST_FIRMWARE));
  EXPECT_EQ(wrong.outcome.exit_code, 1) << wrong.outcome.output;
}

TEST(MicromouseScenarioTest, NeverReachingTheGoalFails) {
  const ScenarioRun r = Scenario("--scenario micromouse --set contest_s=2.5 --controller " +
                                 kTests + "scripted_mouse.lua");
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind("no run reached the goal", 0),
            0u)
      << r.result["scenario"]["reason"];
}

TEST(TimeTrialScenarioTest, LapsCountedCounterClockwiseWithTheirTimes) {
  const ScenarioRun r =
      Scenario("--scenario time_trial --set laps=2 --controller " + kTests + "lap_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  const auto& scores = r.result["scenario"]["scores"];
  // a 0.8 m lane round a 1.9 m centre radius: 2 x 2.5 m + 2 pi 1.9 m = 16.9 m a lap at ~0.6 m/s
  EXPECT_GT(scores["lap_1_s"].get<double>(), 20);
  EXPECT_LT(scores["lap_1_s"].get<double>(), 40);
  EXPECT_DOUBLE_EQ(scores["best_lap_s"].get<double>(),
                   std::min(scores["lap_1_s"].get<double>(), scores["lap_2_s"].get<double>()));
  EXPECT_FALSE(scores.contains("lap_3_s"));
}

TEST(TimeTrialScenarioTest, DrivingClockwiseFailsAsTheWrongDirection) {
  // the same controller, turned round
  std::string controller = ReadTextFile(kTests + "lap_controller.lua");
  controller.replace(controller.find("local direction = 1"), 19, "local direction = -1");
  const std::string path =
      (std::filesystem::temp_directory_path() / "unimouse_wrong_way_laps.lua").string();
  WriteTextFile(path, controller);
  const ScenarioRun r = Scenario("--scenario time_trial --controller " + path);
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind("wrong direction", 0), 0u)
      << r.result["scenario"]["reason"];
}

TEST(TimeTrialScenarioTest, TooFewLapsInTheTimeFails) {
  const ScenarioRun r = Scenario(
      "--scenario time_trial --set laps=3 --set time_limit_s=40 "
      "--controller " +
      kTests + "lap_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"], "1 of 3 laps in 40 s");
}

TEST(ScenarioApiTest, TheApiMatchesItsGoldenListing) {
  // an API change is deliberate: update tests/golden/scenario_api.txt, and the level for
  // removals or changed signatures
  const auto o = Unimouse("scenario-api");
  ASSERT_EQ(o.exit_code, 0);
  EXPECT_EQ(o.output, ReadTextFile(UNIMOUSE_SOURCE_DIR "/tests/golden/scenario_api.txt"));
}

TEST(ScenarioApiTest, ArcAndPolylineWallsStopTheRobotAndResetReturnsItToItsStart) {
  const ScenarioRun r = Scenario("--scenario " + kTests + "pen.lua");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  double touched_y = 0, back_x = 1, back_y = 1;
  ASSERT_EQ(std::sscanf(r.result["scenario"]["reason"].get<std::string>().c_str(),
                        "touched at y=%lf; reset to x=%lf y=%lf", &touched_y, &back_x, &back_y),
            3)
      << r.result["scenario"]["reason"];
  // the arc's inner face is at 0.294 m: the robot's front touches it with its centre short of it
  EXPECT_GT(touched_y, 0.15);
  EXPECT_LT(touched_y, 0.294);
  // reset: the start pose given in world
  EXPECT_NEAR(back_x, 0, 1e-3);
  EXPECT_NEAR(back_y, -0.1, 1e-3);
  // without the walls it drives on untouched
  const ScenarioRun open = Scenario("--scenario " + kTests + "pen.lua --set pen=false");
  EXPECT_EQ(open.outcome.exit_code, 1) << open.outcome.output;
  EXPECT_EQ(open.result["scenario"]["reason"], "drove 3 s without touching a wall");
}

TEST(ScenarioApiTest, FileAppendWritesInsideTheOutputDirectoryAndNowhereElse) {
  const ScenarioRun r = Scenario("--scenario " + kTests + "file_append.lua --duration 1");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  const std::string out =
      (std::filesystem::temp_directory_path() /
       "unimouse_scenario_FileAppendWritesInsideTheOutputDirectoryAndNowhereElse")
          .string();
  EXPECT_EQ(ReadTextFile(out + "/lines.csv"), "a,b\n1,2\n");
  for (const char* name : {"../escape.csv", "sub/dir.csv", "lines.lua", ".hidden.csv"}) {
    const ScenarioRun bad =
        Scenario("--scenario " + kTests + "file_append.lua --duration 1 --set name=" + name);
    EXPECT_EQ(bad.outcome.exit_code, 3) << name << "\n" << bad.outcome.output;
    EXPECT_NE(bad.outcome.output.find("is not a plain file name ending in .csv or .txt"),
              std::string::npos)
        << bad.outcome.output;
  }
}

TEST(ScenarioApiTest, EveryListedFunctionExistsInTheSandbox) {
  const std::string listing = ReadTextFile(UNIMOUSE_SOURCE_DIR "/tests/golden/scenario_api.txt");
  std::string checks;
  int count = 0;
  for (size_t at = listing.find("sim."); at != std::string::npos;
       at = listing.find("\nsim.", at + 1)) {
    const size_t begin = listing.find("sim.", at) + 4;
    const size_t end = listing.find_first_of("({", begin);
    checks += "  assert(type(sim." + listing.substr(begin, end - begin) + ") == 'function', '" +
              listing.substr(begin, end - begin) + "')\n";
    ++count;
  }
  EXPECT_EQ(count, 33);
  const std::string path =
      (std::filesystem::temp_directory_path() / "unimouse_api_complete.lua").string();
  WriteTextFile(path, "return sim.scenario { name = 'api_complete', run = function()\n" + checks +
                          "  sim.pass('all there')\nend }\n");
  const ScenarioRun r = Scenario("--scenario " + path);
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
}

TEST(ScenarioApiTest, AnUnknownKeyWhileRunningIsAScriptErrorAtTheScenariosLine) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "unimouse_late_typo.lua").string();
  WriteTextFile(path,
                "return sim.scenario { name = 'late_typo', run = function()\n"
                "  sim.wait(0.01)\n"
                "  sim.robot_place { x_m = 0, y_m = 0, yaw = 0 }\n"
                "end }\n");
  const ScenarioRun r = Scenario("--scenario " + path);
  EXPECT_EQ(r.outcome.exit_code, 3) << r.outcome.output;
  EXPECT_NE(
      r.outcome.output.find(path + ":3: unknown key yaw in sim.robot_place, did you mean yaw_deg?"),
      std::string::npos)
      << r.outcome.output;
}

TEST(SlalomScenarioTest, WeavingThroughPasses) {
  const ScenarioRun r =
      Scenario("--scenario slalom --controller " + kTests + "slalom_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["scores"]["posts_passed"], 4);
}

TEST(SlalomScenarioTest, DrivingIntoAPostFailsOnTheWallContactEvent) {
  const ScenarioRun r =
      Scenario("--scenario slalom --controller " + kTests + "straight_controller.lua");
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"].get<std::string>().rfind("touched a post", 0), 0u)
      << r.result["scenario"]["reason"];
}

TEST(SlalomScenarioTest, PassingAPostOnTheWrongSideFailsOnTheGateEvent) {
  // the first post is passed on its right: the gate of post 2 comes first
  std::string controller = ReadTextFile(kTests + "slalom_controller.lua");
  controller.replace(controller.find("{ -0.3, 0.6 }"), 13, "{ 0.3, 0.6 }, { 0.3, 1.0 }");
  const std::string path =
      (std::filesystem::temp_directory_path() / "unimouse_wrong_side.lua").string();
  WriteTextFile(path, controller);
  const ScenarioRun r = Scenario("--scenario slalom --controller " + path);
  EXPECT_EQ(r.outcome.exit_code, 1) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["reason"], "passed post 1 on the wrong side");
}

// a scenario whose world runs `body` from line 2, loaded and built in this process
std::unique_ptr<unimouse::Scenario> ReportingScenario(const std::string& body) {
  const std::string file = testing::FreshDirectory("reporting") + "/reporting.lua";
  WriteTextFile(file,
                "return sim.scenario { name = 'reporting', run = function() end, world = "
                "function()\n" +
                    body + "\nend }\n");
  auto scenario = unimouse::Scenario::Load(file, {}, 1);
  scenario->BuildWorld();
  return scenario;
}

// the script error of a world that runs `body`, from its line on
std::string ReportingError(const std::string& body) {
  try {
    ReportingScenario(body);
  } catch (const RuntimeFault& e) {
    const std::string message = e.what();
    const size_t from = message.find(".lua:") + 5;
    return message.substr(from, message.rfind(" (in world)") - from);
  }
  return "";
}

TEST(ScenarioRecordTest, RecordsKeepTheirFieldsTypesAndOrder) {
  const auto s = ReportingScenario(
      "sim.record_add('runs', { run = 1, time_s = 2.5, done = true, note = 'first' })\n"
      "sim.record_add('laps', { lap = 1 })\n"
      "sim.record_add('runs', { run = 2, time_s = 3.0 })");
  const auto& records = s->outcome().records;
  ASSERT_EQ(records.at("runs").size(), 2u);
  const ScenarioRecord& first = records.at("runs")[0];
  EXPECT_EQ(std::get<int64_t>(first.at("run")), 1);
  EXPECT_EQ(std::get<double>(first.at("time_s")), 2.5);
  EXPECT_EQ(std::get<bool>(first.at("done")), true);
  EXPECT_EQ(std::get<std::string>(first.at("note")), "first");
  // 3.0 is a float in Lua, and stays one; a field left out is absent
  const ScenarioRecord& second = records.at("runs")[1];
  EXPECT_EQ(std::get<double>(second.at("time_s")), 3.0);
  EXPECT_FALSE(second.contains("note"));
  EXPECT_EQ(records.at("laps").size(), 1u);
}

TEST(ScenarioRecordTest, AFieldThatChangesTypeFromRecordToRecordIsRefusedAtItsLine) {
  EXPECT_EQ(ReportingError("sim.record_add('runs', { time_s = 1.5 })\n"
                           "sim.record_add('runs', { time_s = 'slow' })"),
            "3: sim.record_add: field 'time_s' of list 'runs' is a number in earlier records, "
            "not a string");
}

TEST(ScenarioRecordTest, ARecordRefusedUnderPcallLeavesNoTrace) {
  // 33 fields: refused at the last one read, after the others (time_s among them) were
  const auto s = ReportingScenario(
      "local r = { time_s = 'slow' } for i = 1, 32 do r['f' .. i] = i end\n"
      "assert(not pcall(sim.record_add, 'runs', r))\n"
      "sim.record_add('runs', { time_s = 1.5 })");
  ASSERT_EQ(s->outcome().records.at("runs").size(), 1u);
  EXPECT_EQ(std::get<double>(s->outcome().records.at("runs")[0].at("time_s")), 1.5);
}

TEST(ScenarioRecordTest, AFieldIsANumberABooleanOrAString) {
  EXPECT_EQ(ReportingError("sim.record_add('runs', { cells = { 1, 2 } })"),
            "2: sim.record_add: field 'cells' is a table; a field is a number, a boolean or a "
            "string");
  EXPECT_EQ(ReportingError("sim.record_add('runs', { time_s = 1 / 0 })"),
            "2: sim.record_add: field 'time_s' is not finite");
  EXPECT_EQ(ReportingError("sim.record_add('runs', { [1] = 5 })"),
            "2: sim.record_add: a field name is a string, not a number");
}

TEST(ScenarioRecordTest, ListAndFieldNamesAreWords) {
  EXPECT_EQ(ReportingError("sim.record_add('my runs', { n = 1 })"),
            "2: sim.record_add: list name 'my runs' is not a word of letters, digits and _ (at "
            "most 64, not starting with a digit)");
  EXPECT_EQ(ReportingError("sim.record_add('runs', { ['2nd'] = 1 })"),
            "2: sim.record_add: field name '2nd' is not a word of letters, digits and _ (at most "
            "64, not starting with a digit)");
}

TEST(ScenarioRecordTest, ARunHoldsAtMostTenThousandRecords) {
  EXPECT_EQ(ReportingError("for i = 1, 10000 do sim.record_add('runs', { n = i }) end\n"
                           "sim.record_add('laps', { n = 1 })"),
            "3: sim.record_add: more than 10000 records in a run (docs/limits.md)");
}

TEST(ScenarioRecordTest, AScoreSetToAnIntegerIsAnIntegerAndAFloatAFloat) {
  const auto s = ReportingScenario("sim.score_set('runs', 3)\nsim.score_set('time_s', 3.0)");
  EXPECT_EQ(std::get<int64_t>(s->outcome().scores.at("runs")), 3);
  EXPECT_EQ(std::get<double>(s->outcome().scores.at("time_s")), 3.0);
  EXPECT_EQ(ReportingError("sim.score_set('time_s', 0 / 0)"),
            "2: sim.score_set: score 'time_s' is not finite");
}

}  // namespace
}  // namespace unimouse
