// SPDX-License-Identifier: GPL-3.0-or-later
// The library's examples built for an Arduino Mega 2560 (arduino-lib/avr), the very images one
// would flash, run on the emulated board (--link avr:) and pass their scenarios; the same image
// twice gives the same run, since the board keeps its own, emulated, time.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

using ExampleRun = testing::RunResult;

std::string Image(const std::string& example) {
  const std::string path = UNIMOUSE_BINARY_DIR "/avr/" + example + ".elf";
  return std::filesystem::exists(path) ? path : "";
}

// the example's board image driving the robot in the scenario; the wall-clock figures left out
ExampleRun RunOnBoard(const std::string& image, const std::string& scenario,
                      const std::string& out_name) {
  ExampleRun run =
      testing::UnimouseRun("--scenario " + scenario + " --link avr:" + image, out_name);
  if (run.result.is_object()) {
    run.result.erase("wall_time_s");
    run.result.erase("real_time_factor");
    run.result.erase("real_time_pacing");
  }
  return run;
}

#define IMAGE_OR_SKIP(var, example)                                                 \
  const std::string var = Image(example);                                           \
  if (var.empty()) {                                                                \
    GTEST_SKIP() << "no AVR build of the examples: gcc-avr or arduino-core-avr is " \
                    "missing";                                                      \
  }

TEST(ArduinoExamplesOnBoardTest, WallDistancePassesItsScenarioTheSameWayEveryTime) {
  IMAGE_OR_SKIP(image, "wall_distance");
  const ExampleRun a = RunOnBoard(image, "wall_distance", "unimouse_avr_example_wd");
  ASSERT_EQ(a.outcome.exit_code, 0) << a.outcome.output;
  EXPECT_EQ(a.result["scenario"]["status"], "passed") << a.result["scenario"]["reason"];
  const std::string log = ReadTextFile(
      (std::filesystem::temp_directory_path() / "unimouse_avr_example_wd" / "log.txt").string());
  EXPECT_NE(log.find("emulated atmega2560 at 16 MHz"), std::string::npos) << log;
  EXPECT_NE(log.find("UART 1000000 baud"), std::string::npos) << log;
  EXPECT_NE(log.find(" 0 RX overruns, 0 lost in, 0 lost out"), std::string::npos) << log;
  const ExampleRun b = RunOnBoard(image, "wall_distance", "unimouse_avr_example_wd");
  EXPECT_EQ(a.result, b.result);
}

TEST(ArduinoExamplesOnBoardTest, SpeedControlPassesItsScenario) {
  IMAGE_OR_SKIP(image, "speed_control");
  const ExampleRun r = RunOnBoard(image, "speed_control", "unimouse_avr_example_sc");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "passed") << r.result["scenario"]["reason"];
}

TEST(ArduinoExamplesOnBoardTest, TimeTrialDrivesThreeLaps) {
  IMAGE_OR_SKIP(image, "time_trial");
  const ExampleRun r = RunOnBoard(image, "time_trial", "unimouse_avr_example_tt");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["scenario"]["status"], "passed") << r.result["scenario"]["reason"];
  EXPECT_EQ(r.result["scenario"]["scores"].count("lap_3_s"), 1u);
}

}  // namespace
}  // namespace unimouse
