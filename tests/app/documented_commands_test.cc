// SPDX-License-Identifier: GPL-3.0-or-later
// The commands the docs show a user, run word for word from the layout their page describes:
// the bundled robots and controllers from a clone of this repository, the bundled gyro example,
// the board image of an IMU driver in the working directory.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using testing::DocumentedCommands;
using testing::FreshDirectory;
using testing::RunDocumented;

// a working directory laid out as a clone of this repository is, for the paths a command names
std::string CloneLikeDirectory(const std::string& stem) {
  const std::string dir = FreshDirectory(stem);
  fs::create_directory_symlink(fs::path(UNIMOUSE_SOURCE_DIR) / "tests", fs::path(dir) / "tests");
  return dir;
}

TEST(DocumentedCommandsTest, TheOtherWheelLayoutsPassTheWallDistanceChallengeAsRobotsMdShows) {
  const std::vector<std::string> commands = DocumentedCommands(
      "docs/robots.md", "(`BundledScenario.IsPassedOrFailedByItsController/wall_distance_*`):");
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(commands[0].rfind("unimouse run --robot unimouse-skid ", 0), 0u) << commands[0];
  EXPECT_EQ(commands[1].rfind("unimouse run --robot unimouse-six ", 0), 0u) << commands[1];
  for (const std::string& command : commands) {
    const std::string dir = CloneLikeDirectory("documented_layouts");
    const testing::Outcome o = RunDocumented(command, dir);
    EXPECT_EQ(o.exit_code, 0) << command << "\n" << o.output;
    EXPECT_NE(o.output.find("scenario wall_distance: passed"), std::string::npos) << o.output;
  }
}

TEST(DocumentedCommandsTest, TheGyroExampleRunsOnTheGyroRobotAsFirmwareMdShows) {
  const std::vector<std::string> commands =
      DocumentedCommands("docs/firmware.md", "The library's `gyro_turn` example");
  ASSERT_EQ(commands.size(), 1u);
  const testing::Outcome o = RunDocumented(commands[0], FreshDirectory("documented_gyro"));
  EXPECT_EQ(o.exit_code, 0) << commands[0] << "\n" << o.output;
}

// the bundled wall_distance example by its name, from anywhere, as a program and on the board
TEST(DocumentedCommandsTest, TheBundledExampleRunsByItsNameTheWaysFirmwareMdShows) {
  std::vector<std::string> commands =
      DocumentedCommands("docs/firmware.md", "**Compiled for the PC**");
#ifdef UNIMOUSE_AVR_TEST_FIRMWARE_DIR
  for (const std::string& command :
       DocumentedCommands("docs/firmware.md", "**On an emulated board**")) {
    commands.push_back(command);
  }
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_NE(commands[1].find("--link avr:wall_distance"), std::string::npos) << commands[1];
#else
  ASSERT_EQ(commands.size(), 1u);  // no AVR toolchain: no board image
#endif
  EXPECT_NE(commands[0].find("--link native:wall_distance"), std::string::npos) << commands[0];
  for (const std::string& command : commands) {
    const testing::Outcome o = RunDocumented(command, FreshDirectory("documented_three_ways"));
    EXPECT_EQ(o.exit_code, 0) << command << "\n" << o.output;
    EXPECT_NE(o.output.find("scenario wall_distance: passed"), std::string::npos) << o.output;
  }
}

TEST(DocumentedCommandsTest, AnImuDriverOnTheEmulatedBoardRunsAsFirmwareMdShows) {
#ifndef UNIMOUSE_AVR_TEST_FIRMWARE_DIR
  GTEST_SKIP() << "no AVR toolchain (gcc-avr, avr-libc, arduino-core-avr): no image to run";
#else
  const std::vector<std::string> commands =
      DocumentedCommands("docs/firmware.md", "`tests/avr/imu_spi.ino` is such a driver");
  ASSERT_EQ(commands.size(), 1u);
  // the driver's image in the working directory, as the command names it
  const std::string dir = FreshDirectory("documented_imu_spi");
  fs::copy_file(UNIMOUSE_AVR_TEST_FIRMWARE_DIR "/imu_spi.elf", dir + "/imu_spi.elf");
  const testing::Outcome o = RunDocumented(commands[0], dir);
  EXPECT_EQ(o.exit_code, 0) << commands[0] << "\n" << o.output;
#endif
}

TEST(DocumentedCommandsTest, TheRacerRunsTheContestAsFirmwareMdShows) {
  const std::vector<std::string> commands =
      DocumentedCommands("docs/firmware.md", "## A fast mouse: the racer example");
  ASSERT_EQ(commands.size(), 1u);
  const std::string dir = FreshDirectory("documented_racer");
  const testing::Outcome o = RunDocumented(commands[0], dir);
  ASSERT_EQ(o.exit_code, 0) << commands[0] << "\n" << o.output;
  // what the page says of it: the optimal path (cost 108) in 24.8 s
  EXPECT_NE(o.output.find("best 24.774 s (path cost 108)"), std::string::npos) << o.output;
}

// the README's result line of the main job, e.g. "scenario micromouse: passed: 3 runs, ..."
std::string ReadmeResultLine() {
  const std::string readme = ReadTextFile(UNIMOUSE_SOURCE_DIR "/README.md");
  const size_t shown = readme.find("\n    scenario micromouse: passed: ");
  if (shown == std::string::npos) return "";
  return readme.substr(shown + 5, readme.find('\n', shown + 1) - shown - 5);
}

// the README names the main job with its options in its text, and the library's README runs the
// same sketch as a program of its own: each as written gives the README's result line
TEST(DocumentedCommandsTest, TheMainJobWithItsOptionsAndAsAProgramGiveTheReadmesResult) {
  const std::string readme = ReadTextFile(UNIMOUSE_SOURCE_DIR "/README.md");
  const size_t from = readme.find("with options is `unimouse run");
  ASSERT_NE(from, std::string::npos);
  std::string inline_command = readme.substr(from + 17, readme.find('`', from + 17) - from - 17);
  std::replace(inline_command.begin(), inline_command.end(), '\n', ' ');
  EXPECT_EQ(inline_command,
            "unimouse run --scenario micromouse --set end_on_log=done --link inproc:racer");
  const std::vector<std::string> program =
      DocumentedCommands("arduino-lib/README.md", "`examples/racer` runs the same contest");
  ASSERT_EQ(program.size(), 1u);
  const std::string line = ReadmeResultLine();
  ASSERT_FALSE(line.empty());
  for (const std::string& command : {inline_command, program[0]}) {
    const testing::Outcome o = RunDocumented(command, FreshDirectory("documented_main_job"));
    EXPECT_EQ(o.exit_code, 0) << command << "\n" << o.output;
    EXPECT_NE(o.output.find("  " + line), std::string::npos) << command << "\n" << o.output;
  }
}

// protocol.md and replay.md name `unimouse run -v` and `unimouse run` in their text: the main job
// with every report of the firmware on the console, and its recording beside its result
TEST(DocumentedCommandsTest, TheMainJobWithVShowsEveryReportAndLeavesItsRecording) {
  const std::string dir = FreshDirectory("documented_verbose");
  const testing::Outcome o = RunDocumented("unimouse run -v", dir);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string log = ReadTextFile(dir + "/out/log.txt");
  size_t reports = 0;
  for (size_t at = log.find("debug walls"); at != std::string::npos;
       at = log.find("debug walls", at + 1)) {
    ++reports;
    EXPECT_NE(o.output.find(log.substr(at, log.find('\n', at) - at)), std::string::npos);
  }
  EXPECT_GT(reports, 200u);
  EXPECT_TRUE(fs::is_regular_file(dir + "/out/run.mcap"));
  // the result line the README shows, to the millisecond
  const std::string line = ReadmeResultLine();
  ASSERT_FALSE(line.empty());
  EXPECT_NE(o.output.find("  " + line), std::string::npos) << line << "\n" << o.output;
}

// replay.md's two runs side by side: the main job and the contest with other sensor noise part
// somewhere, and the page of both is written
TEST(DocumentedCommandsTest, TwoRunsReplayedSideBySideAsReplayMdShows) {
  const std::vector<std::string> commands =
      DocumentedCommands("docs/replay.md", "### Two runs side by side");
  ASSERT_EQ(commands.size(), 3u);
  const std::string dir = FreshDirectory("documented_replay");
  std::string said;
  for (const std::string& command : commands) {
    const testing::Outcome o = RunDocumented(command, dir);
    ASSERT_EQ(o.exit_code, 0) << command << "\n" << o.output;
    said = o.output;
  }
  EXPECT_NE(said.find("the runs first diverge at "), std::string::npos) << said;
  EXPECT_TRUE(fs::is_regular_file(dir + "/both.html"));
}

}  // namespace
}  // namespace unimouse
