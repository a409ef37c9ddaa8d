// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse firmware build`: a student's sketch, written here outside the tree, built by the
// documented command from the build tree and from an installed prefix, passes its challenge.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;
using testing::Unimouse;
using testing::UnimouseRun;

// A student's wall follower for the wall distance challenge (0.50 m from the wall on the left):
// a proportional-derivative law on the left sensor's reading, written from the challenge's text
// alone, with a printf to the standard output as a student would debug.
constexpr char kSketch[] = R"(#include <UnimouseSim.h>
#include <stdio.h>

SimulationRobot robot(Serial);
float previous = 0;
unsigned long printed = 0;

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
}

void loop() {
  robot.update();
  // the left sensor looks 45 degrees left from 0.048 m left of the centre
  const float goal = (0.50f - 0.048f) * 1.41421356f;
  const float error = robot.leftDistance() - goal;
  const float change = error - previous;
  previous = error;
  int turn = (int)(800 * error + 4000 * change);
  if (turn > 250) turn = 250;
  if (turn < -250) turn = -250;
  robot.motorLeft(450 - turn);
  robot.motorRight(450 + turn);
  if (millis() - printed >= 1000) {
    printed = millis();
    printf("my follower: error %d mm\n", (int)(error * 1000));
  }
}
)";

// Writes the sketch as the Arduino IDE lays it out, FOLDER/my_follower/my_follower.ino, and
// returns the sketch folder.
std::string WriteSketch(const std::string& folder, const std::string& text = kSketch) {
  const fs::path sketch = fs::path(folder) / "my_follower";
  fs::create_directories(sketch);
  std::ofstream(sketch / "my_follower.ino") << text;
  return sketch.string();
}

// Builds the sketch with `unimouse` (the build tree's or an installed one), then runs the
// challenge over the native link and in-process; both pass, the printf in the log.
void BuildAndPass(const std::string& unimouse, const std::string& stem) {
  const std::string work = FreshDirectory(stem);
  const std::string sketch = WriteSketch(work);
  const std::string out = work + "/bin";
  const std::string build = unimouse + " firmware build " + sketch + " --out " + out + " 2>&1";
  FILE* pipe = popen(build.c_str(), "r");
  std::string said;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof(buffer), pipe)) > 0;) said.append(buffer, n);
  ASSERT_EQ(pclose(pipe), 0) << said;
  EXPECT_NE(said.find("--link native:" + out + "/my_follower"), std::string::npos) << said;
  ASSERT_TRUE(fs::is_regular_file(out + "/my_follower"));
  ASSERT_TRUE(fs::is_regular_file(out + "/my_follower.so"));

  for (const std::string& link :
       {"native:" + out + "/my_follower", "inproc:" + out + "/my_follower.so"}) {
    const std::string run_out = work + "/run-" + link.substr(0, link.find(':'));
    const int code = std::system((unimouse + " run --scenario wall_distance --link " + link +
                                  " --no-pictures --out " + run_out + " >/dev/null 2>&1")
                                     .c_str());
    EXPECT_EQ(WEXITSTATUS(code), 0) << link << ": " << ReadTextFile(run_out + "/result.json");
    if (link.rfind("native:", 0) == 0) {
      EXPECT_NE(ReadTextFile(run_out + "/log.txt").find("my follower: error"), std::string::npos)
          << "the sketch's printf is in the run's log";
    }
  }
}

TEST(FirmwareBuildTest, ASketchOutsideTheTreeBuildsAndPassesItsChallenge) {
  BuildAndPass(UNIMOUSE_BINARY, "fw_build");
}

TEST(FirmwareBuildTest, ASketchOutsideTheTreeBuildsAgainstAnInstallAndPassesItsChallenge) {
  const std::string prefix = FreshDirectory("fw_prefix");
  ASSERT_EQ(
      std::system(
          ("cmake --install " UNIMOUSE_BINARY_DIR " --prefix " + prefix + " >/dev/null").c_str()),
      0);
  BuildAndPass(prefix + "/bin/unimouse", "fw_build_installed");
}

TEST(FirmwareBuildTest, ASketchOutsideTheTreeBuildsForTheEmulatedBoardAndPassesItsChallenge) {
  if (std::system("command -v avr-g++ >/dev/null") != 0) {
    GTEST_SKIP() << "no avr-g++ (gcc-avr): no board builds";
  }
  const std::string work = FreshDirectory("fw_avr");
  const std::string sketch = WriteSketch(work);
  const auto build = Unimouse("firmware build " + sketch + " --board mega2560 --out " + work);
  ASSERT_EQ(build.exit_code, 0) << build.output;
  ASSERT_TRUE(fs::is_regular_file(work + "/my_follower.elf"));
  const auto run =
      UnimouseRun("--scenario wall_distance --no-pictures --link avr:" + work + "/my_follower.elf",
                  "fw_avr_run");
  if (run.outcome.output.find("this build has no emulated board") != std::string::npos) {
    GTEST_SKIP() << "this build has no emulated board (libsimavr-dev)";
  }
  EXPECT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
}

// The commands of docs/firmware.md's "Build your own sketch", word for word, in the layout it
// describes: the sketch folder my_follower/ in the working directory.
TEST(FirmwareBuildTest, TheDocumentedCommandsBuildAndRunASketchFolderBesideThem) {
  // the first block of commands in the section, one per line
  const std::vector<std::string> commands =
      testing::DocumentedCommands("docs/firmware.md", "## Build your own sketch");
  ASSERT_EQ(commands.size(), 2u);
  ASSERT_EQ(commands[0], "unimouse firmware build my_follower");
  const std::string work = FreshDirectory("fw_documented");
  WriteSketch(work);
  for (const std::string& command : commands) {
    const auto outcome = testing::RunDocumented(command, work);
    ASSERT_EQ(outcome.exit_code, 0) << command << ": " << outcome.output;
  }
  EXPECT_TRUE(fs::is_regular_file(work + "/my_follower/my_follower"));
  EXPECT_TRUE(fs::is_regular_file(work + "/my_follower/my_follower.so"));
  EXPECT_TRUE(fs::is_regular_file(work + "/my_follower/my_follower.ino")) << "the sketch is kept";
}

// The same page's commands for the emulated board, word for word, in the same layout.
TEST(FirmwareBuildTest, TheDocumentedCommandsBuildAndRunASketchFolderOnTheEmulatedBoard) {
  if (std::system("command -v avr-g++ >/dev/null") != 0) {
    GTEST_SKIP() << "no avr-g++ (gcc-avr): no board builds";
  }
  const std::vector<std::string> commands =
      testing::DocumentedCommands("docs/firmware.md", "For the emulated board (an");
  ASSERT_EQ(commands.size(), 2u);
  ASSERT_EQ(commands[0], "unimouse firmware build my_follower --board mega2560");
  const std::string work = FreshDirectory("fw_documented_board");
  WriteSketch(work);
  for (const std::string& command : commands) {
    const auto outcome = testing::RunDocumented(command, work);
    if (outcome.output.find("this build has no emulated board") != std::string::npos) {
      GTEST_SKIP() << "this build has no emulated board (libsimavr-dev)";
    }
    ASSERT_EQ(outcome.exit_code, 0) << command << ": " << outcome.output;
  }
  EXPECT_TRUE(fs::is_regular_file(work + "/my_follower/my_follower.elf"));
}

// The lines tests/arduino/habits prints with the word "habit", in order, from a run's log.
std::vector<std::string> HabitLines(const std::string& log) {
  std::vector<std::string> lines;
  for (size_t at = log.find("\thabit "); at != std::string::npos;
       at = log.find("\thabit ", at + 1)) {
    lines.push_back(log.substr(at + 1, log.find('\n', at) - at - 1));
  }
  return lines;
}

// A student's habits (tests/arduino/habits): the core's helpers, PROGMEM, EEPROM, random(),
// pins, String, printed numbers, a tab and a .cpp, a delay() before the robot begins and a wait on
// millis() alone. Built for the PC and for the board, each prints what the board's own Arduino
// core computes: hand-computed values (random() is the minimal standard generator, 16807 x mod
// 2^31 - 1, from the seed 42), the same on both.
TEST(FirmwareBuildTest, AStudentsArduinoHabitsGiveTheBoardsAnswersOnThePcAndOnTheBoard) {
  const std::vector<std::string> expected = {
      "habit map 127 7050",  // 512 * 255 / 1023; 5e9 wraps to 705032704 in 32 bits
      "habit constrain 300",
      "habit min max -2 7",
      "habit bits 1 9 8",
      "habit word 513",
      "habit progmem 20",
      "habit eeprom 255 1234",  // an erased cell, then what was put
      "habit random 94 23 9 13",
      "habit pin 1 1",
      "habit hex FFFFFFFF",                             // a 32-bit long
      "habit numbers 3 ovf inf 3.1416 -123456 13 400",  // 2.5 half up; past 32 bits; -inf
      "habit string V42 FF 3.1427 13 4 13",  // a String's numbers in lower case, then upper
      "habit parts 42 7",
      "habit clock on yes",  // millis() never went back once the robot began
      "habit spun 50 ms",
  };
  const std::string work = FreshDirectory("fw_habits");
  const std::string sketch = UNIMOUSE_SOURCE_DIR "/tests/arduino/habits";
  std::vector<std::string> links;
  auto build = Unimouse("firmware build " + sketch + " --out " + work + "/pc");
  ASSERT_EQ(build.exit_code, 0) << build.output;
  links.push_back("native:" + work + "/pc/habits");
  links.push_back("inproc:" + work + "/pc/habits.so");
  if (std::system("command -v avr-g++ >/dev/null") == 0) {
    build = Unimouse("firmware build " + sketch + " --board mega2560 --out " + work + "/board");
    ASSERT_EQ(build.exit_code, 0) << build.output;
    links.push_back("avr:" + work + "/board/habits.elf");
  }
  for (const std::string& link : links) {
    const auto run = UnimouseRun(
        "--scenario speed_control --duration 0.5 --no-pictures --record off --link " + link,
        "fw_habits_run");
    if (run.outcome.output.find("this build has no emulated board") != std::string::npos) {
      continue;
    }
    std::vector<std::string> lines = HabitLines(
        ReadTextFile((fs::temp_directory_path() / "fw_habits_run" / "log.txt").string()));
    ASSERT_FALSE(lines.empty()) << link << ": " << run.outcome.output;
    // 0 at the start; after delay(200) the PC counts the delay asked for, the board's timer a
    // tick behind
    EXPECT_TRUE(lines[0] == "habit start 0 200" ||
                (link.rfind("avr:", 0) == 0 && lines[0] == "habit start 0 199"))
        << link << ": " << lines[0];
    lines.erase(lines.begin());
    EXPECT_EQ(lines, expected) << link;
  }
}

// A String of a number longer than any fixed buffer: the whole text, as printf writes it (the
// lengths are Python's: len(f"{1e100:.2f}"), len(f"{1.0:.80f}"))
TEST(FirmwareBuildTest, AStringOfALongNumberHoldsAllOfIt) {
  const std::string sketch =
      WriteSketch(FreshDirectory("fw_long_string"), R"(#include <UnimouseSim.h>
SimulationRobot robot(Serial);
void setup() {
  robot.begin();
  printf("long %u %u\n", String(1e100).length(), String(1.0, 80).length());
}
void loop() { robot.update(); }
)");
  const auto build = Unimouse("firmware build " + sketch + " --out " + sketch + "/bin");
  ASSERT_EQ(build.exit_code, 0) << build.output;
  for (const std::string& link :
       {"native:" + sketch + "/bin/my_follower", "inproc:" + sketch + "/bin/my_follower.so"}) {
    const auto run = UnimouseRun(
        "--scenario speed_control --duration 0.01 --no-pictures "
        "--record off --link " +
            link,
        "fw_long_string_run");
    const std::string log =
        ReadTextFile((fs::temp_directory_path() / "fw_long_string_run" / "log.txt").string());
    EXPECT_NE(log.find("\tlong 104 82\n"), std::string::npos) << link << ": " << log;
  }
}

// The README's words for a sketch of one's own: the folder my_sketch/my_sketch.ino, built by
// `unimouse firmware build my_sketch`, run with `--link native:my_sketch/my_sketch`.
TEST(FirmwareBuildTest, TheReadmesCommandsBuildAndRunASketchOfOnesOwn) {
  const std::string readme = ReadTextFile(UNIMOUSE_SOURCE_DIR "/README.md");
  const std::string build = "unimouse firmware build my_sketch",
                    link = "--link native:my_sketch/my_sketch";
  ASSERT_NE(readme.find("`" + build + "`, then `" + link + "`"), std::string::npos);
  const std::string work = FreshDirectory("fw_readme");
  fs::create_directories(work + "/my_sketch");
  WriteTextFile(work + "/my_sketch/my_sketch.ino", kSketch);
  const auto built = testing::RunDocumented(build, work);
  ASSERT_EQ(built.exit_code, 0) << built.output;
  const auto ran = testing::RunDocumented("unimouse run --scenario wall_distance " + link, work);
  EXPECT_EQ(ran.exit_code, 0) << ran.output;
}

// docs/robots.md's recipe for an extra sensor, in its layout: the robot file my_robot.yaml (the
// bundled robot with the recipe's site and component) and the sketch folder my_follower (the
// follower above with the recipe's library call) beside each other; the page's run command
// word for word.
TEST(FirmwareBuildTest, TheExtraSensorRecipeRunsAsRobotsMdShows) {
  const std::vector<std::string> run =
      testing::DocumentedCommands("docs/robots.md", "2. **The `send` entry.**");
  ASSERT_EQ(run.size(), 1u);
  const std::string work = FreshDirectory("fw_extra_sensor");
  std::string robot = ReadTextFile(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml");
  const std::string sites = "  sites:\n";
  ASSERT_NE(robot.find(sites), std::string::npos);
  robot.insert(robot.find(sites) + sites.size(),
               "    - { name: tof_rear, pos_m: [-0.060, 0, 0], euler_deg: [0, 0, 180] }\n");
  robot +=
      "  - type: unimouse.tof_sensor\n"
      "    name: tof.rear\n"
      "    params: { site: tof_rear, range_out: tof.rear_m }\n";
  WriteTextFile(work + "/my_robot.yaml", robot);
  std::string sketch = kSketch;
  const std::string setup = "  robot.begin();";
  sketch.replace(sketch.find(setup), setup.size(), "  robot.addSensor(rear);\n  robot.begin();");
  sketch.replace(sketch.find("float previous"), 0, "DistanceSensor rear(17);\n");
  WriteSketch(work, sketch);
  const auto build = testing::RunDocumented("unimouse firmware build my_follower", work);
  ASSERT_EQ(build.exit_code, 0) << build.output;
  const auto outcome = testing::RunDocumented(run[0], work);
  EXPECT_EQ(outcome.exit_code, 0) << run[0] << ": " << outcome.output;
  EXPECT_NE(outcome.output.find("scenario wall_distance: passed"), std::string::npos)
      << outcome.output;
}

TEST(FirmwareBuildTest, AProgramThatWouldTakeAFoldersPlaceIsRefusedWithoutBlamingTheSketch) {
  const std::string work = FreshDirectory("fw_collision");
  const std::string sketch = WriteSketch(work);
  const auto outcome =
      testing::Shell("cd " + work + " && " UNIMOUSE_BINARY " firmware build my_follower --out .");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(sketch + " is a directory, so the built program cannot go there"),
            std::string::npos)
      << outcome.output;
  EXPECT_EQ(outcome.output.find("did not build"), std::string::npos) << outcome.output;
}

TEST(FirmwareBuildTest, ASketchThatDoesNotCompileIsBadInputNamingTheSketch) {
  const std::string sketch = WriteSketch(FreshDirectory("fw_broken"), "void setup() { oops; }\n");
  const auto outcome = Unimouse("firmware build " + sketch + " --out " + sketch + "/bin");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_NE(outcome.output.find("oops"), std::string::npos) << "the compiler's message is shown";
  // once: not again for the module built of the same source
  const std::string error = "my_follower.ino:1:16: error:";
  const size_t first = outcome.output.find(error);
  EXPECT_NE(first, std::string::npos) << outcome.output;
  EXPECT_EQ(outcome.output.find(error, first + 1), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find(sketch + ": the sketch did not build"), std::string::npos)
      << outcome.output;
}

TEST(FirmwareBuildTest, AFolderWithoutASketchOfItsNameIsBadInput) {
  const std::string folder = FreshDirectory("fw_empty");
  const auto outcome = Unimouse("firmware build " + folder);
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_NE(outcome.output.find("a sketch folder holds a sketch of its name"), std::string::npos)
      << outcome.output;
}

TEST(FirmwareBuildTest, BundledFirmwareIsNamedLikeBundledRobotsAndMazes) {
  // from a directory with no file of that name, native:wall_distance is the bundled example
  const std::string empty = FreshDirectory("fw_bundled");
  for (const char* link : {"native:wall_distance", "inproc:wall_distance"}) {
    const std::string out = empty + "/" + std::string(link).substr(0, 6);
    const int code =
        std::system(("cd " + empty +
                     " && " UNIMOUSE_BINARY " run --scenario wall_distance --no-pictures --link " +
                     link + " --out " + out + " >/dev/null 2>&1")
                        .c_str());
    EXPECT_EQ(WEXITSTATUS(code), 0) << link;
  }
}

}  // namespace
}  // namespace unimouse
