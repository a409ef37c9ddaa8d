// SPDX-License-Identifier: GPL-3.0-or-later
// Shortest paths against the dissertation's tables 5.3/5.4 and against a brute-force Dijkstra
// over robot states written here, on many random mazes.
#include "maze_solver.h"

#include <gtest/gtest.h>

#include <queue>
#include <tuple>

#include "inline_assets.h"
#include "maze_generator.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

struct Solved {
  MazePath modified;
  MazePath traditional;
  int traditional_cells = 0;
};

Solved Solve(const Maze& maze, const TieRule& rule = {}) {
  const OpenSides sides(maze);
  StateFloodFill states;
  states.Compute(sides, maze.goals());
  CellFloodFill cells;
  cells.Compute(sides, maze.goals());
  return {states.PathFrom(sides, maze.start(), maze.start_heading()),
          cells.PathFrom(sides, maze.start(), maze.start_heading(), rule),
          cells.Distance(maze.start())};
}

TEST(MazeSolverTest, ModifiedFloodFillReproducesTables53And54) {
  EXPECT_EQ(Solve(LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt")).modified.Cost(), 108);
  EXPECT_EQ(Solve(LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2019.txt")).modified.Cost(), 118);
}

TEST(MazeSolverTest, TraditionalFloodFillWithTheDefaultTieRuleReproducesTables53And54) {
  const Solved a = Solve(LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt"));
  const Solved b = Solve(LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2019.txt"));
  EXPECT_EQ(a.traditional.Cost(), 118);
  EXPECT_EQ(b.traditional.Cost(), 120);
  // "both paths visit the same amount of cells": the traditional path is no longer in cells
  EXPECT_EQ(a.traditional.straights, a.traditional_cells);
  EXPECT_EQ(b.traditional.straights, b.traditional_cells);
  EXPECT_EQ(b.traditional.straights, b.modified.straights);
}

TEST(MazeSolverTest, TheTraditionalPathsTurnsDependOnTheTieRule) {
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  EXPECT_EQ(Solve(maze, TieRule::Parse("compass:NESW")).traditional.Cost(), 112);
  EXPECT_EQ(Solve(maze, TieRule::Parse("relative:LRFB")).traditional.Cost(), 118);
  EXPECT_EQ(Solve(maze, TieRule::Parse("straight:NESW")).traditional.Cost(), 112);
}

TEST(MazeSolverTest, TieRulesParseAndNameThemselves) {
  EXPECT_EQ(TieRule{}.Name(), "compass:WENS");
  EXPECT_EQ(TieRule::Parse("relative:FLRB").Name(), "relative:FLRB");
  EXPECT_THROW(TieRule::Parse("compass:NNEW"), InputError);
  EXPECT_THROW(TieRule::Parse("spiral:NESW"), InputError);
  EXPECT_THROW(TieRule::Parse("compass"), InputError);
}

TEST(MazeSolverTest, DescribesARouteByItsMovesAndQuarterTurns) {
  // north, north, east, south: 4 moves; right turn, then right turn again
  const MazePath p = DescribeRoute({{0, 0}, {0, 1}, {0, 2}, {1, 2}, {1, 1}}, Heading::kNorth);
  EXPECT_EQ(p.straights, 4);
  EXPECT_EQ(p.turns, 2);
  // an about-turn counts two
  EXPECT_EQ(DescribeRoute({{0, 1}, {0, 0}}, Heading::kNorth).turns, 2);
}

TEST(MazeSolverTest, ARouteBetweenTheFarthestCellsAnIntHoldsIsDescribedWithoutOverflow) {
  // 2147483647 - (-2147483648) does not fit an int; as a 64-bit step it is no east-west
  // neighbour, and the route's last case (south) takes it: an about-turn from north
  const MazePath p = DescribeRoute({{-2147483647 - 1, 0}, {2147483647, 0}}, Heading::kNorth);
  EXPECT_EQ(p.straights, 1);
  EXPECT_EQ(p.turns, 2);
}

TEST(MazeSolverTest, AGoalThatCannotBeReachedGivesNoPath) {
  // the goal cell (2, 0) is walled off
  const Maze maze = ParseMazeText(
      "o---o---o---o\n"
      "| S     | G |\n"
      "o---o---o---o\n",
      "sealed.txt");
  const Solved s = Solve(maze);
  EXPECT_FALSE(s.modified.found);
  EXPECT_FALSE(s.traditional.found);
}

// Dijkstra over (cell, heading) with forward, left and right at cost 1, written independently
int BruteForceCost(const Maze& maze) {
  const int w = maze.width(), h = maze.height();
  std::vector<int> best(static_cast<size_t>(4 * w * h), 1 << 30);
  using Item = std::tuple<int, int, int, int>;  // cost, x, y, heading
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const Cell s = maze.start();
  open.push({0, s.x, s.y, static_cast<int>(maze.start_heading())});
  while (!open.empty()) {
    const auto [cost, x, y, hd] = open.top();
    open.pop();
    for (Cell g : maze.goals()) {
      if (g == Cell{x, y}) return cost;
    }
    int& seen = best[static_cast<size_t>(4 * (y * w + x) + hd)];
    if (cost >= seen) continue;
    seen = cost;
    open.push({cost + 1, x, y, (hd + 1) % 4});
    open.push({cost + 1, x, y, (hd + 3) % 4});
    const int nx = x + (hd == 0) - (hd == 2), ny = y + (hd == 1) - (hd == 3);
    if (nx >= 0 && ny >= 0 && nx < w && ny < h && !maze.HasWall({x, y}, static_cast<Heading>(hd))) {
      open.push({cost + 1, nx, ny, hd});
    }
  }
  return -1;
}

TEST(MazeSolverTest, ModifiedFloodFillEqualsBruteForceOnRandomMazes) {
  int compared = 0;
  for (int size : {3, 5, 8, 16, 21, 32}) {
    for (double loops : {0.0, 0.1, 0.5}) {
      for (uint64_t seed = 1; seed <= 12; ++seed) {
        const Maze maze = GenerateMaze({size, size + (seed % 3 == 0 ? 1 : 0), seed, loops});
        const Solved s = Solve(maze);
        ASSERT_TRUE(s.modified.found) << size << " " << loops << " " << seed;
        EXPECT_EQ(s.modified.Cost(), BruteForceCost(maze)) << size << " " << loops << " " << seed;
        // the path it returns really costs what the flood fill says, and is a legal route
        EXPECT_EQ(DescribeRoute(s.modified.cells, maze.start_heading()).Cost(), s.modified.Cost());
        for (size_t i = 1; i < s.modified.cells.size(); ++i) {
          const Cell a = s.modified.cells[i - 1], b = s.modified.cells[i];
          const int h = b.x > a.x ? 0 : b.x < a.x ? 2 : b.y > a.y ? 1 : 3;
          ASSERT_FALSE(maze.HasWall(a, static_cast<Heading>(h)));
        }
        // no route of cells beats the traditional one, and turns only add to it
        EXPECT_LE(s.traditional.straights, s.modified.straights);
        EXPECT_GE(s.traditional.Cost(), s.modified.Cost());
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 6 * 3 * 12);
}

}  // namespace
}  // namespace unimouse
