// SPDX-License-Identifier: GPL-3.0-or-later
// The library's examples, built for the PC, drive the simulated robot through the native link in
// lock-step and pass their scenarios; the same run twice gives the same result.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

using ExampleRun = testing::RunResult;

// the example's PC build driving the robot in the scenario; the wall-clock figures left out
ExampleRun RunExample(const std::string& example, const std::string& scenario,
                      const std::string& out_name) {
  ExampleRun run = testing::UnimouseRun(
      "--scenario " + scenario + " --link native:" + UNIMOUSE_FIRMWARE_DIR "/" + example, out_name);
  if (run.result.is_object()) {
    run.result.erase("wall_time_s");
    run.result.erase("real_time_factor");
    run.result.erase("wall_time_split_s");
    run.result.erase("real_time_pacing");
    run.result.erase("wall_time_split_s");
  }
  return run;
}

TEST(ArduinoExamplesTest, WallDistancePassesItsScenarioTheSameWayEveryTime) {
  const ExampleRun a = RunExample("wall_distance", "wall_distance", "unimouse_example_wd");
  ASSERT_EQ(a.outcome.exit_code, 0) << a.outcome.output;
  EXPECT_EQ(a.result["scenario"]["status"], "passed") << a.result["scenario"]["reason"];
  const ExampleRun b = RunExample("wall_distance", "wall_distance", "unimouse_example_wd");
  EXPECT_EQ(a.result, b.result);
}

TEST(ArduinoExamplesTest, SpeedControlPassesItsScenario) {
  const ExampleRun r = RunExample("speed_control", "speed_control", "unimouse_example_sc");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "passed") << r.result["scenario"]["reason"];
}

TEST(ArduinoExamplesTest, TimeTrialDrivesThreeLapsTheRightWay) {
  const ExampleRun r = RunExample("time_trial", "time_trial", "unimouse_example_tt");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "passed") << r.result["scenario"]["reason"];
  EXPECT_EQ(r.result["scenario"]["scores"].count("lap_3_s"), 1u);
}

TEST(ArduinoExamplesTest, MicromouseExploresJapan2018AndSpeedRunsThePathOfCost108) {
  const std::string out = (std::filesystem::temp_directory_path() / "unimouse_example_mm").string();
  const ExampleRun r =
      RunExample("micromouse", "micromouse --set end_on_log=done", "unimouse_example_mm");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "passed") << r.result["scenario"]["reason"];
  // within the 10-minute contest, at least one whole run, ended by the firmware's "done"
  EXPECT_GE(r.result["scenario"]["scores"]["runs"].get<int>(), 1);
  EXPECT_LT(r.result["scenario"]["scores"]["time_used_s"].get<double>(), 600);
  // the best run's path as the simulator saw the robot drive it: the optimum of table 5.4
  EXPECT_EQ(r.result["scenario"]["scores"]["best_run_path_cost"], 108);
  const std::string log = ReadTextFile(out + "/log.txt");
  EXPECT_NE(log.find("speed run 1: path cost 108"), std::string::npos) << log;
  EXPECT_NE(log.find("the firmware logged 'done'"), std::string::npos);
  // lock-step: however the two processes are scheduled, the same contest
  const ExampleRun again =
      RunExample("micromouse", "micromouse --set end_on_log=done", "unimouse_example_mm2");
  EXPECT_EQ(r.result["scenario"], again.result["scenario"]);
  EXPECT_EQ(r.result["robot_pose"], again.result["robot_pose"]);
}

}  // namespace
}  // namespace unimouse
