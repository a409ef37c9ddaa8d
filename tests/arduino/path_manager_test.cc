// SPDX-License-Identifier: GPL-3.0-or-later
// The firmware library's PathManager, logic-level on the PC: a mouse that senses the four walls
// of every cell it enters, fed from the true maze, explores by Adachi method 0 in as many trips as
// the simulator's explorer (dissertation table 5.1: 3 trips for All Japan 2018), then returns and
// does a speed run along a path of turn-aware cost 108 (japan2018) and 118 (japan2019), the
// costs of table 5.4.
#include <gtest/gtest.h>

#include "FFSolver.h"
#include "Maze.h"
#include "PathManager.h"
#include "headings.h"
#include "maze.h"
#include "maze_explorer.h"

namespace unimouse {
namespace {

using FirmwareMaze = ::Maze<16, 16>;

struct Outcome {
  int exploring_trips = 0;
  int speed_run_cost = -1;
};

Outcome Explore(const std::string& file) {
  const unimouse::Maze truth = LoadMaze(file);
  FirmwareMaze maze;
  FFSolver<16, 16> solver(maze);
  PathManager<16, 16> manager(solver, 0, 0, Direction::North, 7, 7, 8, 8);
  using Phase = PathManager<16, 16>::Phase;
  auto sense = [&](uint8_t x, uint8_t y) {
    for (uint8_t d = 0; d < 4; ++d) {
      const Direction side = static_cast<Direction>(d);
      if (truth.HasWall({x, y}, ToHeading(side))) {
        maze.placeWall(x, y, side);
      } else {
        maze.removeWall(x, y, side);
      }
    }
  };
  Outcome out;
  uint8_t x = 0, y = 0;
  Direction d = Direction::North;
  sense(x, y);
  int speed_run_actions = -1;
  for (int step = 0; step < 20000; ++step) {
    const uint16_t trips = manager.trips();
    const Action a = manager.nextAction(x, y, d);
    if (manager.phase() != Phase::Exploring && out.exploring_trips == 0) {
      out.exploring_trips = manager.trips();
    }
    // the first speed run, counted by actions from the start state to the goal
    if (manager.phase() == Phase::SpeedRun && manager.towardsGoal() && speed_run_actions < 0 &&
        x == 0 && y == 0 && d == Direction::North) {
      speed_run_actions = 0;
    }
    if (speed_run_actions >= 0 && manager.trips() != trips) {
      out.speed_run_cost = speed_run_actions;
      break;
    }
    if (a == Action::None) break;
    if (speed_run_actions >= 0) ++speed_run_actions;
    if (a == Action::Forward) {
      x = static_cast<uint8_t>(x + stepX(d));
      y = static_cast<uint8_t>(y + stepY(d));
      sense(x, y);
    } else {
      d = a == Action::TurnLeft ? turnLeft(d) : turnRight(d);
    }
  }
  return out;
}

TEST(FirmwarePathManagerTest, ExploresJapan2018InTheSimulatorsTripsAndSpeedRunsAtCost108) {
  const Outcome o = Explore(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  const Exploration reference = ExploreAdachi(LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt"));
  EXPECT_EQ(o.exploring_trips, 3);
  EXPECT_EQ(o.exploring_trips, static_cast<int>(reference.trips.size()));
  EXPECT_EQ(o.speed_run_cost, 108);
}

TEST(FirmwarePathManagerTest, ExploresJapan2019AndSpeedRunsAtCost118) {
  const Outcome o = Explore(UNIMOUSE_SOURCE_DIR "/mazes/japan2019.txt");
  const Exploration reference = ExploreAdachi(LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2019.txt"));
  EXPECT_EQ(o.exploring_trips, static_cast<int>(reference.trips.size()));
  EXPECT_EQ(o.speed_run_cost, 118);
}

}  // namespace
}  // namespace unimouse
