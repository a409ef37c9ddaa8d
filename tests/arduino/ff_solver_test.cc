// SPDX-License-Identifier: GPL-3.0-or-later
// The firmware library's Maze and FFSolver, compiled for the PC: the solver's cost of every
// state equals the simulator's modified flood fill on random mazes, and following bestAction
// from the start of the All Japan 2018 and 2019 mazes costs 108 and 118 (dissertation table
// 5.4), with walls fed from the true maze.
#include <gtest/gtest.h>

#include "FFSolver.h"
#include "Maze.h"
#include "headings.h"
#include "maze.h"
#include "maze_generator.h"
#include "maze_solver.h"

namespace unimouse {
namespace {

using FirmwareMaze = ::Maze<16, 16>;
using FirmwareSolver = ::FFSolver<16, 16>;

template <class FirmwareMazeType>
void CopyWalls(const unimouse::Maze& from, FirmwareMazeType* to) {
  for (int x = 0; x < from.width(); ++x) {
    for (int y = 0; y < from.height(); ++y) {
      for (Heading h : {Heading::kEast, Heading::kNorth, Heading::kWest, Heading::kSouth}) {
        if (from.HasWall({x, y}, h)) {
          to->placeWall(static_cast<uint8_t>(x), static_cast<uint8_t>(y), ToDirection(h));
        }
      }
    }
  }
}

TEST(FirmwareMazeTest, WallsAreSharedWithTheNeighbourAndTheOuterWallsStay) {
  FirmwareMaze maze;
  EXPECT_TRUE(maze.hasWall(0, 0, Direction::West));
  EXPECT_TRUE(maze.hasWall(15, 15, Direction::North));
  EXPECT_FALSE(maze.hasWall(3, 3, Direction::North));
  EXPECT_FALSE(maze.isKnown(3, 3, Direction::North));
  maze.placeWall(3, 3, Direction::North);
  EXPECT_TRUE(maze.hasWall(3, 4, Direction::South));
  EXPECT_EQ(maze.cell(3, 4), (UNIMOUSE_SIDE_SOUTH << 4) | UNIMOUSE_SIDE_SOUTH);
  maze.removeWall(3, 4, Direction::South);
  EXPECT_FALSE(maze.hasWall(3, 3, Direction::North));
  EXPECT_TRUE(maze.isKnown(3, 3, Direction::North));
  maze.removeWall(0, 5, Direction::West);
  EXPECT_TRUE(maze.hasWall(0, 5, Direction::West));
  static_assert(sizeof(FirmwareMaze) == 256 + 2, "one byte a cell, and the size in use");
}

// a side forgotten is unseen again from both cells; an outer wall is never forgotten
TEST(FirmwareMazeTest, AForgottenSideIsUnseenFromBothCellsAndTheOuterWallsStay) {
  FirmwareMaze maze;
  maze.placeWall(3, 3, Direction::East);
  maze.removeWall(3, 3, Direction::North);
  maze.forget(4, 3, Direction::West);
  EXPECT_FALSE(maze.isKnown(3, 3, Direction::East));
  EXPECT_FALSE(maze.hasWall(3, 3, Direction::East));
  EXPECT_EQ(maze.cell(4, 3), 0);
  EXPECT_EQ(maze.cell(3, 3), UNIMOUSE_SIDE_NORTH << 4);  // the other side stays known open
  maze.forget(0, 5, Direction::West);
  EXPECT_TRUE(maze.hasWall(0, 5, Direction::West));
  EXPECT_TRUE(maze.isKnown(0, 5, Direction::West));
}

TEST(FirmwareSolverTest, CostsEqualTheSimulatorsModifiedFloodFillOnRandomMazes) {
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const unimouse::Maze truth = GenerateMaze({16, 16, seed, seed % 2 ? 0.0 : 0.3});
    FirmwareMaze maze;
    CopyWalls(truth, &maze);
    FirmwareSolver solver(maze);
    solver.calculateCosts(7, 7, 8, 8);
    StateFloodFill reference;
    reference.Compute(OpenSides(truth), truth.goals());
    for (int x = 0; x < 16; ++x) {
      for (int y = 0; y < 16; ++y) {
        for (Heading h : {Heading::kEast, Heading::kNorth, Heading::kWest, Heading::kSouth}) {
          ASSERT_EQ(solver.cost(static_cast<uint8_t>(x), static_cast<uint8_t>(y), ToDirection(h)),
                    reference.Cost({x, y}, h))
              << "seed " << seed << " cell " << x << "," << y << " heading " << static_cast<int>(h);
        }
      }
    }
  }
}

TEST(FirmwareMazeTest, AMazeResizedWithinItsRoomHasItsOuterWallsAtItsSize) {
  ::Maze<32, 32> maze;
  EXPECT_EQ(maze.width(), 32);
  ASSERT_TRUE(maze.resize(5, 3));
  EXPECT_FALSE(maze.resize(33, 3));  // beyond the room: unchanged
  EXPECT_EQ(maze.width(), 5);
  EXPECT_EQ(maze.height(), 3);
  EXPECT_TRUE(maze.hasWall(4, 1, Direction::East));
  EXPECT_TRUE(maze.hasWall(2, 2, Direction::North));
  EXPECT_FALSE(maze.hasWall(3, 1, Direction::East));
  EXPECT_TRUE(maze.contains(4, 2));
  EXPECT_FALSE(maze.contains(5, 2));
  maze.placeWall(4, 1, Direction::East);  // an outer wall stays, and nothing beyond changes
  EXPECT_EQ(maze.cell(5, 1), 0xFF);
}

TEST(FirmwareSolverTest, ASolverWithRoomFor32By32CostsA16By16MazeAsOneSizedForIt) {
  // a 32 x 32 firmware maze resized to 16 x 16 plans as Maze<16, 16> does (tested above
  // against the simulator's flood fill): the same cost for every state
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const unimouse::Maze truth = GenerateMaze({16, 16, seed, 0.3});
    FirmwareMaze small;
    CopyWalls(truth, &small);
    ::Maze<32, 32> large;
    ASSERT_TRUE(large.resize(16, 16));
    CopyWalls(truth, &large);
    FirmwareSolver small_solver(small);
    ::FFSolver<32, 32> large_solver(large);
    small_solver.calculateCosts(7, 7, 8, 8);
    large_solver.calculateCosts(7, 7, 8, 8);
    for (uint8_t x = 0; x < 16; ++x) {
      for (uint8_t y = 0; y < 16; ++y) {
        for (uint8_t d = 0; d < 4; ++d) {
          ASSERT_EQ(large_solver.cost(x, y, static_cast<Direction>(d)),
                    small_solver.cost(x, y, static_cast<Direction>(d)))
              << "seed " << seed << " cell " << +x << "," << +y;
        }
      }
    }
  }
}

// follows bestAction from the start facing north, counting actions, until a goal cell
int CostFollowingBestActions(const std::string& file) {
  const unimouse::Maze truth = LoadMaze(file);
  FirmwareMaze maze;
  CopyWalls(truth, &maze);
  FirmwareSolver solver(maze);
  solver.calculateCosts(7, 7, 8, 8);
  uint8_t x = 0, y = 0;
  Direction d = Direction::North;
  int actions = 0;
  for (Action a = solver.bestAction(x, y, d); a != Action::None; a = solver.bestAction(x, y, d)) {
    if (a == Action::Forward) {
      x = static_cast<uint8_t>(x + stepX(d));
      y = static_cast<uint8_t>(y + stepY(d));
    } else {
      d = a == Action::TurnLeft ? turnLeft(d) : turnRight(d);
    }
    if (++actions > 1000) return -1;
  }
  EXPECT_EQ(solver.cost(0, 0, Direction::North), actions);
  return actions;
}

TEST(FirmwareSolverTest, TheBestPathsOfJapan2018And2019CostTable54s108And118) {
  EXPECT_EQ(CostFollowingBestActions(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt"), 108);
  EXPECT_EQ(CostFollowingBestActions(UNIMOUSE_SOURCE_DIR "/mazes/japan2019.txt"), 118);
}

}  // namespace
}  // namespace unimouse
