// SPDX-License-Identifier: GPL-3.0-or-later
// The physics tier: single moves and turns of the controller checked against the robot's true
// pose in MuJoCo, what its sensors say of the walls, and `unimouse mms --physical` as a user
// runs it, up to the test clients driving classic mazes of the collection on the robot.
#include "mms_physical.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "inline_assets.h"
#include "mms_clients.h"
#include "plugin_rig.h"
#include "png_file.h"
#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;

constexpr double kPi = std::numbers::pi;
constexpr double kCell_m = 0.18;

// the robot in the 5 x 5 open maze (one wall, east of the start), driven from this test
class MmsRobotTest : public ::testing::Test {
 protected:
  MmsRobotTest() : registry_(testing::BundledComponents()) {
    const std::string dir = FreshDirectory("mms_robot");
    WriteTextFile(dir + "/open.txt", testing::kOpenMaze5x5);
    options_.registry = &registry_;
    options_.maze = dir + "/open.txt";
    options_.out_dir = dir + "/out";
    options_.duration_s = 60;
    options_.duration_given = true;
    options_.only_asked_pictures = true;  // no picture: this is about the motion
    options_.console = false;
    options_.driven_by_caller = true;
    session_ = Session::Open(options_);
    robot_ = std::make_unique<MmsRobot>(*session_);
  }
  ~MmsRobotTest() override { session_->Finish(); }

  Pose2D TruePose() const {
    return session_->kernel().world().RobotPose(session_->kernel().state().data());
  }

  // the robot at rest at the centre of cell (x, y), facing yaw_deg, within 15 mm and 3 degrees
  void ExpectAtRest(int x, int y, double yaw_deg) const {
    const Pose2D p = TruePose();
    EXPECT_NEAR(p.x_m, (x + 0.5) * kCell_m, 0.015);
    EXPECT_NEAR(p.y_m, (y + 0.5) * kCell_m, 0.015);
    EXPECT_NEAR(std::remainder(p.yaw_rad - yaw_deg * kPi / 180, 2 * kPi), 0, 3 * kPi / 180);
  }

  // the move finished, touched no wall, and took a plausible time for 300 / 1023 of 6 V
  static void ExpectClean(const MmsMotion& motion, double min_s, double max_s) {
    EXPECT_EQ(motion.failure, "") << motion.why;
    EXPECT_FALSE(motion.contact);
    EXPECT_GT(motion.time_s, min_s);
    EXPECT_LT(motion.time_s, max_s);
  }

  PluginRegistry registry_;
  SessionOptions options_;
  std::unique_ptr<Session> session_;
  std::unique_ptr<MmsRobot> robot_;
};

TEST_F(MmsRobotTest, OneCellForwardStopsAtTheNextCellsCentre) {
  ExpectAtRest(0, 0, 90);
  ExpectClean(robot_->Drive(1), 0.2, 2);
  ExpectAtRest(0, 1, 90);
  EXPECT_EQ(robot_->wall_contacts(), 0);
}

TEST_F(MmsRobotTest, ThreeCellsForwardStopOnceAtTheThirdCellsCentre) {
  const MmsMotion one = robot_->Drive(1);
  const MmsMotion three = robot_->Drive(3);
  ExpectClean(three, 0.5, 5);
  ExpectAtRest(0, 4, 90);
  // one move of three cells starts and stops once: faster than three moves of one
  EXPECT_LT(three.time_s, 3 * one.time_s);
}

TEST_F(MmsRobotTest, QuarterTurnsTurnInPlace) {
  ASSERT_EQ(robot_->Drive(1).failure, "");
  ExpectClean(robot_->Turn(-1), 0.1, 2);
  ExpectAtRest(0, 1, 0);
  ExpectClean(robot_->Turn(1), 0.1, 2);
  ExpectAtRest(0, 1, 90);
  ExpectClean(robot_->Turn(1), 0.1, 2);
  ExpectAtRest(0, 1, 180);
  // and on, east along row 1 after turning back twice
  ExpectClean(robot_->Turn(-1), 0.1, 2);
  ExpectClean(robot_->Turn(-1), 0.1, 2);
  ExpectClean(robot_->Drive(2), 0.3, 4);
  ExpectAtRest(2, 1, 0);
}

TEST_F(MmsRobotTest, SensorsSeeTheWallsOfTheCellTheRobotDroveInto) {
  // nothing seen yet in the start cell: the sensors read while crossing into a cell
  for (int side = 0; side < 4; ++side) EXPECT_FALSE(robot_->SensedWall(side).has_value());
  ASSERT_EQ(robot_->Drive(1).failure, "");
  // (0, 1): the outer wall on the left (west), open ahead, to the right and behind
  EXPECT_EQ(robot_->SensedWall(0), false);
  EXPECT_EQ(robot_->SensedWall(1), true);
  EXPECT_EQ(robot_->SensedWall(2), false);
  EXPECT_EQ(robot_->SensedWall(3), false);
  ASSERT_EQ(robot_->Drive(3).failure, "");
  // (0, 4), the north-west corner: walls ahead and on the left
  EXPECT_EQ(robot_->SensedWall(0), true);
  EXPECT_EQ(robot_->SensedWall(1), true);
  EXPECT_EQ(robot_->SensedWall(3), false);
  // turned right, the walls seen turn with the robot: the north wall is now on the left
  ASSERT_EQ(robot_->Turn(-1).failure, "");
  EXPECT_EQ(robot_->SensedWall(0), false);
  EXPECT_EQ(robot_->SensedWall(1), true);
  EXPECT_EQ(robot_->SensedWall(2), true);
}

TEST_F(MmsRobotTest, ResetPutsTheRobotBackAtTheStart) {
  ASSERT_EQ(robot_->Drive(2).failure, "");
  robot_->Reset();
  ExpectAtRest(0, 0, 90);
  ExpectClean(robot_->Drive(1), 0.2, 2);
  ExpectAtRest(0, 1, 90);
}

// `unimouse mms --physical` with programs in mms style
class MmsPhysicalRunTest : public ::testing::Test {
 protected:
  nlohmann::json Mms(const std::string& arguments, int expected_exit_code) {
    const testing::Outcome outcome =
        testing::Unimouse("mms --physical --out " + out_ + " " + arguments);
    EXPECT_EQ(outcome.exit_code, expected_exit_code) << outcome.output;
    output_ = outcome.output;
    if (!fs::exists(out_ + "/result.json")) return nullptr;
    return nlohmann::json::parse(ReadTextFile(out_ + "/result.json"));
  }

  // a shell client: `ask` sends a line, reads the reply and writes it to replies.txt
  std::string Client(const std::string& body) {
    const std::string path = dir_ + "/client.sh";
    WriteTextFile(path, "#!/bin/sh\nask() { echo \"$1\"; read -r reply; echo \"$1 $reply\" >> " +
                            dir_ + "/replies.txt; }\n" + body);
    fs::permissions(path, fs::perms::owner_exec, fs::perm_options::add);
    return path;
  }
  std::string Replies() const { return ReadTextFile(dir_ + "/replies.txt"); }

  std::string dir_ = FreshDirectory("mms_physical");
  std::string out_ = dir_ + "/out";
  std::string open_maze_ = [this] {
    WriteTextFile(dir_ + "/open.txt", testing::kOpenMaze5x5);
    return dir_ + "/open.txt";
  }();
  std::string output_;
};

TEST_F(MmsPhysicalRunTest, FloodFillClientReachesTheGoalOfAllJapan2018OnTheRobot) {
  const nlohmann::json result = Mms("--maze japan2018 -- " + testing::kFloodFillClient, 0);
  ASSERT_TRUE(result.is_object()) << output_;
  EXPECT_EQ(result["mode"], "mms-physical");
  EXPECT_EQ(result["status"], "goal_reached") << result["reason"];
  EXPECT_EQ(result["crashes"], 0);
  EXPECT_EQ(result["physical"]["wall_contacts"], 0);
  EXPECT_EQ(result["physical"]["wall_readings"]["wrong"], 0) << output_;
  // at least the 14 cells of the shortest way in, each more than 0.3 s; far less than the
  // contest's 10 minutes; the simulation ran as long as the moves took
  const double contest_s = result["contest_time_s"].get<double>();
  EXPECT_GT(contest_s, 14 * 0.3);
  EXPECT_LT(contest_s, 600);
  EXPECT_NEAR(result["physical"]["sim_time_s"].get<double>(), contest_s, 0.01);
  EXPECT_LT(result["physical"]["worst_offset_m"].get<double>(), 0.03);
}

// issue 30's bounds for the physics tier, on eight solvable classic mazes of the collection drawn
// with seed 30 (bench/mms_physical_sweep.py runs a sample of 50): the flood-fill client reaches
// every goal, and neither it nor the left-wall follower (a minute of contest time each) touches
// a wall or comes to rest more than 3 degrees off its heading
TEST_F(MmsPhysicalRunTest, TestClientsDriveEightClassicMazesWithoutAContactAndWithin3Degrees) {
  const std::string shared = testing::SharedMazesDir();
  if (shared.empty())
    GTEST_SKIP() << "the maze collection (../shared/mazes) is not beside the project";
  if (!testing::HavePython()) GTEST_SKIP() << "no python3";
  const char* mazes[] = {"alljapan-009-1988-pre",
                         "alljapan-016-1995-frsh",
                         "eastjapan-017-1999",
                         "jcf01",
                         "map-v1",
                         "minos24-b",
                         "sundo-1",
                         "test-3paths"};
  const std::string left_wall = "--time-limit-s 60 -- " + testing::kLeftWallClient;
  for (const char* name : mazes) {
    const std::string maze = "--no-pictures --maze " + shared + "/classic/" + name + ".txt ";
    for (const std::string& client : {"-- " + testing::kFloodFillClient, left_wall}) {
      const bool flood_fill = client.find("left_wall") == std::string::npos;
      SCOPED_TRACE(std::string(name) + (flood_fill ? ", flood fill" : ", left wall"));
      const testing::Outcome outcome =
          testing::Unimouse("mms --physical --out " + out_ + " " + maze + client);
      ASSERT_TRUE(fs::exists(out_ + "/result.json")) << outcome.output;
      const nlohmann::json result = nlohmann::json::parse(ReadTextFile(out_ + "/result.json"));
      const std::string status = result["status"];
      // the left-wall follower drives until the contest clock stops it, or onto the goal
      if (flood_fill) {
        EXPECT_EQ(status, "goal_reached") << result["reason"];
      } else {
        EXPECT_TRUE(status == "time_out" || status == "goal_reached") << status;
      }
      EXPECT_EQ(result["crashes"], 0);
      EXPECT_EQ(result["physical"]["wall_contacts"], 0);
      EXPECT_LT(result["physical"]["worst_yaw_error_deg"].get<double>(), 3);
    }
  }
}

// docs/mms.md: --maze-class as the micromouse scenario's maze_class, and a robot too wide for the
// class's corridors is warned about
TEST_F(MmsPhysicalRunTest, AHalfSizeMazeIsBuiltAtHalfSizeAndARobotTooWideForItIsWarnedAbout) {
  // the bundled robot, 128 mm across its wheels, in a 16 x 16 maze built with 90 mm cells
  const std::string client = Client("ask mazeWidth\n");
  nlohmann::json result = Mms("--maze-class half --maze japan2018 -- " + client, 3);
  ASSERT_TRUE(result.is_object()) << output_;
  EXPECT_NE(result["physical"]["warnings"].dump().find(
                "the robot is 128 mm wide and this half-size maze's corridors are 84 mm: it does "
                "not fit"),
            std::string::npos)
      << result["physical"].dump(1);
  // the half-size robot fits the half-size maze, the bundled robot the classic one
  result = Mms("--maze-class half --robot unimouse-half --maze japan2018 -- " + client, 3);
  EXPECT_EQ(result["physical"]["warnings"].dump().find("does not fit"), std::string::npos)
      << result["physical"].dump(1);
  result = Mms("--maze japan2018 -- " + client, 3);
  EXPECT_EQ(result["physical"]["warnings"].dump().find("does not fit"), std::string::npos)
      << result["physical"].dump(1);
  // the class goes with the physics tier only
  const testing::Outcome logic =
      testing::Unimouse("mms --maze-class half --out " + out_ + " -- " + client);
  EXPECT_EQ(logic.exit_code, 2) << logic.output;
}

TEST_F(MmsPhysicalRunTest, WallQueriesAreAnsweredFromTheSensors) {
  // up the west side to the north-west corner (0, 4)
  const std::string client =
      Client("ask 'moveForward 4'\nask wallFront\nask wallLeft\nask wallRight\nask wallBack\n");
  const nlohmann::json result = Mms("--maze " + open_maze_ + " -- " + client, 3);
  ASSERT_TRUE(result.is_object()) << output_;
  EXPECT_EQ(Replies(),
            "moveForward 4 ack\nwallFront true\nwallLeft true\nwallRight false\nwallBack false\n");
  EXPECT_EQ(result["physical"]["wall_readings"],
            nlohmann::json::parse(
                R"({"sensed": 4, "wrong": 0, "from_the_maze": 0, "true_walls": false})"));
  EXPECT_EQ(result["contest_time_s"], result["physical"]["sim_time_s"]);
}

TEST_F(MmsPhysicalRunTest, WhatTheSensorsCannotSeeIsAnsweredFromTheMaze) {
  // in the start cell before any move, and two half-cells ahead: no reading
  const std::string client = Client("ask wallRight\nask 'wallFront 2'\nask wallFrontLeft\n");
  const nlohmann::json result = Mms("--maze " + open_maze_ + " -- " + client, 3);
  ASSERT_TRUE(result.is_object()) << output_;
  EXPECT_EQ(Replies(), "wallRight true\nwallFront 2 false\nwallFrontLeft true\n");
  EXPECT_EQ(result["physical"]["wall_readings"]["from_the_maze"], 3);
  EXPECT_EQ(result["physical"]["wall_readings"]["sensed"], 0);
}

TEST_F(MmsPhysicalRunTest, WrongReadingsOfANoisySensorAreAnsweredLoggedAndCounted) {
  // the bundled robot with a right sensor 32 times noisier than the part: along the open east
  // side of column 0 it sometimes reads a wall
  std::string robot = ReadTextFile(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml");
  const std::string right = "params: { site: tof_right, range_out: tof.right_m }";
  ASSERT_NE(robot.find(right), std::string::npos);
  robot.replace(robot.find(right), right.size(),
                "params: { site: tof_right, range_out: tof.right_m, noise_cv: 0.9 }");
  WriteTextFile(dir_ + "/noisy.yaml", robot);
  const std::string client =
      Client("for i in 1 2 3 4; do ask 'moveForward 1'; ask wallRight; ask wallLeft; done\n");
  const nlohmann::json result =
      Mms("--robot " + dir_ + "/noisy.yaml --maze " + open_maze_ + " -- " + client, 3);
  ASSERT_TRUE(result.is_object()) << output_;
  const std::string replies = Replies();
  auto count = [](const std::string& text, const std::string& part) {
    long n = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
  };
  // every wrong reading is the answer the program got, a log line and a count
  const long wrong = result["physical"]["wall_readings"]["wrong"].get<long>();
  EXPECT_GE(wrong, 1);
  EXPECT_EQ(count(replies, "wallRight true"), wrong);
  EXPECT_EQ(count(replies, "wallLeft true"), 4);  // the left sensor is the part's
  EXPECT_EQ(count(output_, "wrong wall reading: the sensors see a wall east of cell (0, "), wrong);
  EXPECT_EQ(result["physical"]["wall_readings"]["sensed"], 8);
}

TEST_F(MmsPhysicalRunTest, TrueWallsAnswersFromTheMaze) {
  const std::string client = Client("ask 'moveForward 1'\nask wallLeft\n");
  const nlohmann::json result = Mms("--true-walls --maze " + open_maze_ + " -- " + client, 3);
  ASSERT_TRUE(result.is_object()) << output_;
  EXPECT_EQ(Replies(), "moveForward 1 ack\nwallLeft true\n");
  EXPECT_EQ(result["physical"]["wall_readings"],
            nlohmann::json::parse(
                R"({"sensed": 0, "wrong": 0, "from_the_maze": 0, "true_walls": true})"));
}

TEST_F(MmsPhysicalRunTest, HalfCellsAnd45DegreeTurnsAreImpossibleMoves) {
  // replied as a move into a wall, and the robot stays: the next cell is still ahead
  const std::string client = Client(
      "ask turnLeft45\nask turnRight45\nask moveForwardHalf\nask 'moveForward 1'\nask wallLeft\n");
  const nlohmann::json result = Mms("--maze " + open_maze_ + " -- " + client, 3);
  ASSERT_TRUE(result.is_object()) << output_;
  EXPECT_EQ(Replies(),
            "turnLeft45 crash\nturnRight45 crash\nmoveForwardHalf crash\nmoveForward 1 ack\n"
            "wallLeft true\n");
  EXPECT_EQ(result["crashes"], 3);
  EXPECT_EQ(result["physical"]["wall_contacts"], 0);
}

TEST_F(MmsPhysicalRunTest, AMoveIntoAWallIsRepliedCrashAndTheRobotStops) {
  // the start cell's east wall: the robot does not drive into it
  const std::string client = Client("ask turnRight\nask 'moveForward 1'\n");
  const nlohmann::json result = Mms("--maze " + open_maze_ + " -- " + client, 3);
  ASSERT_TRUE(result.is_object()) << output_;
  EXPECT_EQ(Replies(), "turnRight ack\nmoveForward 1 crash\n");
  EXPECT_EQ(result["crashes"], 1);
  EXPECT_EQ(result["physical"]["wall_contacts"], 0);
}

TEST_F(MmsPhysicalRunTest, WhatTheProgramDisplayedIsOnTheFloorOfFinalPng) {
  // the same move twice, once with every cell of the 5 x 5 maze coloured red first
  const std::string move = Client("ask 'moveForward 1'\n");
  const nlohmann::json plain = Mms("--maze " + open_maze_ + " -- " + move, 3);
  ASSERT_TRUE(plain.is_object()) << output_;
  if (!plain["physical"]["pictures"].contains("renderer")) {
    GTEST_SKIP() << "no offscreen rendering on this machine: " << plain["physical"]["pictures"];
  }
  int width = 0, height = 0;
  const std::vector<uint8_t> without = ReadPng(out_ + "/final.png", &width, &height);
  const std::string painter = Client(
      "for x in 0 1 2 3 4; do for y in 0 1 2 3 4; do echo \"setColor $x $y r\"; done; "
      "done\nask 'moveForward 1'\n");
  const nlohmann::json painted = Mms("--maze " + open_maze_ + " -- " + painter, 3);
  ASSERT_TRUE(painted.is_object()) << output_;
  EXPECT_EQ(painted["display"]["colors"].size(), 25u);
  const std::vector<uint8_t> with = ReadPng(out_ + "/final.png", &width, &height);
  ASSERT_EQ(with.size(), without.size());
  auto red = [](const std::vector<uint8_t>& rgb) {
    long n = 0;
    for (size_t i = 0; i < rgb.size(); i += 3)
      n += rgb[i] > rgb[i + 1] + 60 && rgb[i] > rgb[i + 2] + 60;
    return n;
  };
  // the floor of 25 cells: a large share of the picture, where there was next to no red before
  EXPECT_GT(red(with), long(with.size() / 3 / 10));
  EXPECT_LT(red(without), red(with) / 10);
}

TEST_F(MmsPhysicalRunTest, TheSameSeedGivesTheSameRun) {
  // north to (0, 2), east into the centre (2, 2) with a turn there and back on the way
  const std::string client = Client(
      "ask 'moveForward 2'\nask turnRight\nask 'moveForward 1'\nask turnLeft\nask turnRight\n"
      "ask 'moveForward 1'\n");
  const nlohmann::json first = Mms("--maze " + open_maze_ + " -- " + client, 0);
  const nlohmann::json second = Mms("--maze " + open_maze_ + " -- " + client, 0);
  ASSERT_TRUE(first.is_object() && second.is_object()) << output_;
  EXPECT_EQ(first["moves"], second["moves"]);
  EXPECT_EQ(first["contest_time_s"], second["contest_time_s"]);
  EXPECT_EQ(first["physical"]["robot_pose"], second["physical"]["robot_pose"]);
  EXPECT_EQ(first["physical"]["wall_readings"], second["physical"]["wall_readings"]);
}

}  // namespace
}  // namespace unimouse
