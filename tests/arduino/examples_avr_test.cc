// SPDX-License-Identifier: GPL-3.0-or-later
// The library's examples built for an Arduino Mega 2560 (arduino-lib/avr), the very images one
// would flash, run on the emulated board (--link avr:) and pass their scenarios; the same image
// twice gives the same run, since the board keeps its own, emulated, time.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "maze.h"
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
    run.result.erase("wall_time_split_s");
    run.result.erase("real_time_pacing");
    // a run that ended early has no board figures: its exit code and output say why
    if (const auto board = run.result.find("measurements");
        board != run.result.end() && board->contains("link")) {
      (*board)["link"].erase("avr.host_cpu_s");
      (*board)["link"].erase("avr.host_emulated_mhz");
    }
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
  // the board's figures, typed, in the record: a Mega 2560 at 16 MHz, well within its RAM
  const nlohmann::json& board = a.result["measurements"]["link"];
  EXPECT_EQ(board["avr.f_cpu_hz"], 16000000.0);
  // each step its share of cycles, and not one instruction more in the end
  EXPECT_NEAR(board["avr.cycles"].get<double>(), 16000000.0 * a.result["sim_time_s"].get<double>(),
              4.0);
  EXPECT_EQ(board["avr.sram_bytes"], 8192.0);
  EXPECT_LT(board["avr.ram_high_water_bytes"].get<double>(), 1024.0);
  EXPECT_EQ(board["avr.rx_overruns"], 0.0);
  EXPECT_GT(board["avr.latency_p50_s"].get<double>(), 0.0);
  EXPECT_LT(board["avr.latency_p99_s"].get<double>(), 0.001);
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

// the image one would flash, in the contest's first run: it explores All Japan 2018 from the
// start to the goal. Lock-step makes the run the same every time, to the emulated cycle: the
// figures below are this run's when it was written (about 40 s on this machine, so it runs once
// and meets its earlier run's figures rather than running twice; the whole contest on the board
// is the racer's test below). A change of the example, the robot or the physics changes them:
// run the test and copy them. Every wall it reports is the maze's (a receive ring too small for
// its 19 ms flood fill garbled frames, and walls went wrong within the first minute)
TEST(ArduinoExamplesOnBoardTest, MicromouseExploresToTheGoalTheSameWayEveryTimeSeeingTrueWalls) {
  IMAGE_OR_SKIP(image, "micromouse");
  const ExampleRun a = RunOnBoard(image, "micromouse --set max_runs=1 --no-pictures --record off",
                                  "unimouse_avr_example_first_run");
  ASSERT_EQ(a.outcome.exit_code, 0) << a.outcome.output;
  const nlohmann::json& scenario = a.result["scenario"];
  EXPECT_EQ(scenario["status"], "passed") << scenario["reason"];
  const nlohmann::json& scores = scenario["scores"];
  EXPECT_EQ(scores["best_run_path_cost"], 196) << scenario.dump();
  EXPECT_EQ(scores["runs"], 1);
  EXPECT_EQ(scores["wall_contacts"], 2);
  EXPECT_NEAR(scores["best_run_s"].get<double>(), 134.392, 1e-6);
  const nlohmann::json& board = a.result["measurements"]["link"];
  EXPECT_EQ(board["avr.cycles"].get<double>(), 2156656000.0);
  EXPECT_EQ(board["avr.instructions"].get<double>(), 1507522883.0);
  EXPECT_EQ(board["avr.bytes_to_mcu"].get<double>(), 849174.0);
  EXPECT_EQ(board["avr.bytes_from_mcu"].get<double>(), 177379.0);
  const nlohmann::json beliefs = nlohmann::json::parse(
      ReadTextFile((std::filesystem::temp_directory_path() / "unimouse_avr_example_first_run" /
                    "firmware_beliefs.json")
                       .string()));
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  ASSERT_GT(beliefs["walls"].size(), 100u);
  const Heading sides[] = {Heading::kNorth, Heading::kEast, Heading::kSouth, Heading::kWest};
  for (const auto& w : beliefs["walls"]) {
    const Cell c{w[0].get<int>(), w[1].get<int>()};
    for (int bit = 0; bit < 4; ++bit) {
      if ((w[3].get<int>() >> bit & 1) == 0) continue;
      EXPECT_EQ((w[2].get<int>() >> bit & 1) != 0, maze.HasWall(c, sides[bit]))
          << "cell (" << c.x << ", " << c.y << ") side " << bit;
    }
  }
}

// the racer's image, the main job's firmware, in the main job's contest, as docs/firmware.md
// shows it from a source build: on a board its loops run every 3 ms, not every millisecond (a
// pass takes some 2.2 ms of the Mega 2560's software floating point), so its run is its own, the
// same every time; the in-process racer races the same path in 24.774 s, with half turns the board
// does not take (docs/firmware.md). Its figures are this contest's when it was written (about 50 s
// of emulation on this machine)
TEST(ArduinoExamplesOnBoardTest, RacerPassesTheMainJobsContestAsFirmwareMdShows) {
  IMAGE_OR_SKIP(image, "racer");
  const std::vector<std::string> commands =
      testing::DocumentedCommands("docs/firmware.md", "**On the emulated board.**");
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_NE(commands[0].find("--link avr:build/avr/racer.elf"), std::string::npos) << commands[0];
  // a source build's layout: the board images in build/avr
  const std::string dir = testing::FreshDirectory("documented_avr_racer");
  std::filesystem::create_directory(dir + "/build");
  std::filesystem::create_directory_symlink(UNIMOUSE_BINARY_DIR "/avr", dir + "/build/avr");
  const testing::Outcome o = testing::RunDocumented(commands[0], dir);
  ASSERT_EQ(o.exit_code, 0) << commands[0] << "\n" << o.output;
  const nlohmann::json result = nlohmann::json::parse(ReadTextFile(dir + "/out/result.json"));
  const nlohmann::json& scenario = result["scenario"];
  EXPECT_EQ(scenario["status"], "passed") << scenario["reason"];
  const nlohmann::json& scores = scenario["scores"];
  EXPECT_EQ(scores["best_run_path_cost"], 108) << scenario.dump();
  EXPECT_EQ(scores["runs"], 3);
  EXPECT_EQ(scores["wall_contacts"], 0);
  EXPECT_NEAR(scores["best_run_s"].get<double>(), 25.380, 1e-6);
  EXPECT_NEAR(scores["time_used_s"].get<double>(), 213.012, 1e-6);
  // within the board's 8 KiB: the maze, the flood fill's 4 KiB, the segment queue and the stack
  const nlohmann::json& board = result["measurements"]["link"];
  EXPECT_EQ(board["avr.ram_high_water_bytes"].get<double>(), 7208.0);
  EXPECT_EQ(board["avr.rx_overruns"], 0.0);
}

// the reset button pressed 5 s into the first run, in a small maze: the board boots again, the
// contest ends that run as a touched mouse's and puts the mouse back at the start, and the next
// run reaches the goal; the same inputs give the same run, reset included
TEST(ArduinoExamplesOnBoardTest, MicromouseResetInItsFirstRunRestartsAndStillFinishesTheContest) {
  IMAGE_OR_SKIP(image, "micromouse");
  const std::string dir = testing::FreshDirectory("avr_reset_maze");
  WriteTextFile(dir + "/small.txt",
                "o---o---o---o---o\n"
                "|           | G |\n"
                "o   o---o   o   o\n"
                "|   |       |   |\n"
                "o   o   o---o   o\n"
                "|   |           |\n"
                "o   o---o---o   o\n"
                "| S |           |\n"
                "o---o---o---o---o\n");
  const std::string scenario =
      "micromouse --maze " + dir + "/small.txt --set max_runs=1 --link-set reset_at_s=5";
  const ExampleRun a = RunOnBoard(image, scenario, "unimouse_avr_example_reset");
  ASSERT_EQ(a.outcome.exit_code, 0) << a.outcome.output;
  for (const char* line :
       {"[    4.999 s] link: the emulated board was reset by its reset pin before t=5.000 s: the "
        "firmware boots again, motors stopped\n",
        "[    5.002 s] link: the firmware restarted at t=5.002 s (its first frame after the link "
        "came back): motors stopped until it commands them; restart 1\n",
        "[    5.003 s] scenario: the firmware restarted: run 1 ends without a time, the mouse "
        "goes back to the start\n"}) {
    EXPECT_NE(a.outcome.output.find(line), std::string::npos) << line << a.outcome.output;
  }
  EXPECT_EQ(a.result["restarts"], 1);
  const nlohmann::json& scores = a.result["scenario"]["scores"];
  EXPECT_EQ(a.result["scenario"]["status"], "passed") << a.result["scenario"]["reason"];
  EXPECT_EQ(scores["firmware_restarts"], 1);
  EXPECT_EQ(scores["runs"], 1);
  EXPECT_EQ(scores["best_run_path_cost"], 18);
  // the run that counts started after the reset, from the start cell
  EXPECT_GT(a.result["sim_time_s"].get<double>() - scores["best_run_s"].get<double>(), 5.0);
  const ExampleRun b = RunOnBoard(image, scenario, "unimouse_avr_example_reset");
  EXPECT_EQ(a.result, b.result);
}

}  // namespace
}  // namespace unimouse
