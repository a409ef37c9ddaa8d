// SPDX-License-Identifier: GPL-3.0-or-later
// Generated mazes keep the classic rules and are reproducible.
#include "maze_generator.h"

#include <gtest/gtest.h>

#include <queue>

namespace unimouse {
namespace {

int ReachableCells(const Maze& maze) {
  std::vector<char> seen(static_cast<size_t>(maze.width() * maze.height()), 0);
  std::queue<Cell> q;
  q.push(maze.start());
  seen[0] = 1;
  int n = 0;
  while (!q.empty()) {
    const Cell c = q.front();
    q.pop();
    ++n;
    for (int h = 0; h < 4; ++h) {
      const Cell next{c.x + (h == 0) - (h == 2), c.y + (h == 1) - (h == 3)};
      if (!maze.Contains(next) || maze.HasWall(c, static_cast<Heading>(h))) continue;
      char& s = seen[static_cast<size_t>(next.y * maze.width() + next.x)];
      if (!s) {
        s = 1;
        q.push(next);
      }
    }
  }
  return n;
}

int OpenInnerEdges(const Maze& maze) {
  int n = 0;
  for (int y = 0; y < maze.height(); ++y) {
    for (int x = 0; x < maze.width(); ++x) {
      if (x + 1 < maze.width() && !maze.HasWall({x, y}, Heading::kEast)) ++n;
      if (y + 1 < maze.height() && !maze.HasWall({x, y}, Heading::kNorth)) ++n;
    }
  }
  return n;
}

TEST(MazeGeneratorTest, FollowsTheClassicRules) {
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const Maze maze = GenerateMaze({16, 16, seed, 0});
    EXPECT_EQ(maze.start(), (Cell{0, 0}));
    EXPECT_TRUE(maze.HasWall({0, 0}, Heading::kEast));
    EXPECT_FALSE(maze.HasWall({0, 0}, Heading::kNorth));
    EXPECT_EQ(maze.goals(), (std::vector<Cell>{{7, 7}, {8, 7}, {7, 8}, {8, 8}}));
    // the goal area has no inner walls and one entrance among its 8 outer sides
    int entrances = 0;
    for (Cell g : maze.goals()) {
      for (int h = 0; h < 4; ++h) {
        const Cell n{g.x + (h == 0) - (h == 2), g.y + (h == 1) - (h == 3)};
        const bool inside = n.x >= 7 && n.x <= 8 && n.y >= 7 && n.y <= 8;
        if (inside) {
          EXPECT_FALSE(maze.HasWall(g, static_cast<Heading>(h)));
        } else if (!maze.HasWall(g, static_cast<Heading>(h))) {
          ++entrances;
        }
      }
    }
    EXPECT_EQ(entrances, 1);
    // closed perimeter, every cell reachable, and a tree: the 252 cells outside the goal joined
    // by 251 openings, plus the goal's 4 inner openings and its entrance
    for (int i = 0; i < 16; ++i) {
      EXPECT_TRUE(maze.HasWall({i, 0}, Heading::kSouth));
      EXPECT_TRUE(maze.HasWall({i, 15}, Heading::kNorth));
      EXPECT_TRUE(maze.HasWall({0, i}, Heading::kWest));
      EXPECT_TRUE(maze.HasWall({15, i}, Heading::kEast));
    }
    EXPECT_EQ(ReachableCells(maze), 256);
    EXPECT_EQ(OpenInnerEdges(maze), 251 + 4 + 1);
  }
}

TEST(MazeGeneratorTest, TheSameSeedGivesTheSameMaze) {
  EXPECT_EQ(FormatMazeText(GenerateMaze({16, 16, 7, 0.1})),
            FormatMazeText(GenerateMaze({16, 16, 7, 0.1})));
  EXPECT_NE(FormatMazeText(GenerateMaze({16, 16, 7, 0.1})),
            FormatMazeText(GenerateMaze({16, 16, 8, 0.1})));
}

TEST(MazeGeneratorTest, LoopsOpenExtraWalls) {
  const int tree = OpenInnerEdges(GenerateMaze({16, 16, 3, 0}));
  const int loopy = OpenInnerEdges(GenerateMaze({16, 16, 3, 0.2}));
  EXPECT_GT(loopy, tree + 20);
}

TEST(MazeGeneratorTest, WritesTextThatReadsBackToTheSameMaze) {
  for (int size : {5, 16, 32}) {
    const Maze maze = GenerateMaze({size, size + 1, 11, 0.1});
    const std::string text = FormatMazeText(maze);
    const Maze again = ParseMazeText(text, "generated.txt");
    EXPECT_EQ(FormatMazeText(again), text);
    EXPECT_EQ(again.goals(), maze.goals());
    EXPECT_EQ(again.start(), maze.start());
  }
}

}  // namespace
}  // namespace unimouse
