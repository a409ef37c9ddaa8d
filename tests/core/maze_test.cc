// SPDX-License-Identifier: GPL-3.0-or-later
// The text maze format: walls where the characters are, start and goals, precise errors.
#include "maze.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "inline_assets.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using testing::kSmallMaze;

std::string ErrorOf(const std::string& text) {
  try {
    ParseMazeText(text, "m.txt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MazeClassTest, TheClassesHaveTheirRulesCellWallAndHeight) {
  // classic: 18 cm cells, walls 1.2 cm thick and 5 cm high (IEEE / All Japan classic rules)
  const MazeDimensions classic = DimensionsOf(MazeClass::kClassic);
  EXPECT_EQ(classic.cell_m, 0.18);
  EXPECT_EQ(classic.wall_thickness_m, 0.012);
  EXPECT_EQ(classic.wall_height_m, 0.05);
  // half-size: 9 cm cells, walls 0.6 cm thick and 2.5 cm high (NTF half-size rules)
  const MazeDimensions half = DimensionsOf(MazeClass::kHalfSize);
  EXPECT_EQ(half.cell_m, 0.09);
  EXPECT_EQ(half.wall_thickness_m, 0.006);
  EXPECT_EQ(half.wall_height_m, 0.025);
}

TEST(MazeClassTest, AMazeLargerThan16CellsASideIsHalfSizeAndASmallerOneClassic) {
  EXPECT_EQ(DefaultMazeClass(16, 16), MazeClass::kClassic);
  EXPECT_EQ(DefaultMazeClass(5, 5), MazeClass::kClassic);
  EXPECT_EQ(DefaultMazeClass(21, 21), MazeClass::kHalfSize);
  EXPECT_EQ(DefaultMazeClass(32, 16), MazeClass::kHalfSize);
  EXPECT_EQ(Maze(32, 32).maze_class(), MazeClass::kHalfSize);
  EXPECT_EQ(Maze(32, 32).dimensions().cell_m, 0.09);
  EXPECT_EQ(Maze(16, 16).dimensions().cell_m, 0.18);
}

TEST(MazeTextTest, ReadsSizeWallsAndStart) {
  const Maze maze = ParseMazeText(kSmallMaze, "small.txt");
  EXPECT_EQ(maze.width(), 3);
  EXPECT_EQ(maze.height(), 2);
  EXPECT_EQ(maze.start(), (Cell{0, 0}));
  EXPECT_EQ(maze.start_heading(), Heading::kNorth);
  EXPECT_TRUE(maze.HasWall({0, 0}, Heading::kWest));
  EXPECT_TRUE(maze.HasWall({0, 0}, Heading::kSouth));
  EXPECT_FALSE(maze.HasWall({0, 0}, Heading::kEast));
  EXPECT_FALSE(maze.HasWall({0, 0}, Heading::kNorth));
  EXPECT_TRUE(maze.HasWall({1, 0}, Heading::kNorth));
  EXPECT_TRUE(maze.HasWall({1, 1}, Heading::kSouth));  // the same wall, seen from above
  EXPECT_TRUE(maze.HasWall({1, 0}, Heading::kEast));
  EXPECT_TRUE(maze.HasWall({2, 0}, Heading::kWest));
}

TEST(MazeTextTest, WithoutMarkersTheStartIsSouthWestAndTheGoalTheCentre) {
  const Maze maze = ParseMazeText(
      "o---o---o---o---o\n|               |\no   o   o   o   o\n|               |\n"
      "o   o   o   o   o\n|               |\no   o   o   o   o\n|               |\n"
      "o---o---o---o---o\n",
      "plain.txt");
  EXPECT_EQ(maze.start(), (Cell{0, 0}));
  EXPECT_EQ(maze.goals(), (std::vector<Cell>{{1, 1}, {2, 1}, {1, 2}, {2, 2}}));
}

TEST(MazeTextTest, ToleratesCrlfPlusPostsAndTrailingBlankLines) {
  std::string text = kSmallMaze;
  std::string crlf;
  for (char c : text) {
    if (c == 'o') c = '+';
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  const Maze maze = ParseMazeText(crlf + "\r\n\r\n", "crlf.txt");
  EXPECT_EQ(maze.width(), 3);
  EXPECT_TRUE(maze.HasWall({1, 0}, Heading::kNorth));
}

TEST(MazeTextTest, ReadsGoalsAndAStartThatFacesItsOpening) {
  const Maze maze = ParseMazeText(
      "o---o---o\n"
      "| G     |\n"
      "o---o   o\n"
      "| S     |\n"
      "o---o---o\n",
      "m.txt");
  EXPECT_EQ(maze.goals(), (std::vector<Cell>{Cell{0, 1}}));
  EXPECT_EQ(maze.start_heading(), Heading::kEast);
}

TEST(MazeTextTest, ErrorsNameTheLineAndColumn) {
  EXPECT_EQ(ErrorOf("o---o\n|   |\n"),
            "m.txt:2:1: a maze has an odd number of lines, at least 3 (post rows and cell rows "
            "alternate); found 2");
  EXPECT_EQ(ErrorOf("o---o---o\n|   |   |\no-x-o---o\n"),
            "m.txt:3:2: expected a wall '---' or three spaces, found '-x-'");
  EXPECT_EQ(ErrorOf("o---o\n| * |\no---o\n"),
            "m.txt:2:3: unexpected '*' inside a cell (only 'S' or 'G' at its centre)");
  EXPECT_EQ(ErrorOf("o---o\n|   |  |\no---o\n"),
            "m.txt:2:6: line is longer than the first line (5 characters): ragged maze");
  EXPECT_EQ(ErrorOf("o---o---o\n| S | S |\no---o---o\n"),
            "m.txt:2:7: a second start 'S'; a maze has one start");
  EXPECT_EQ(ErrorOf("o---x\n|   |\no---o\n"), "m.txt:1:5: expected a post 'o' or '+', found 'x'");
}

TEST(MazeTextTest, AGoalInEveryCellOfTheLargestMazeWritesAndReadsInLinearTime) {
  Maze maze(kMaxMazeSide_cells, kMaxMazeSide_cells);
  std::vector<Cell> goals;
  for (int y = 0; y < maze.height(); ++y) {
    for (int x = 0; x < maze.width(); ++x) goals.push_back({x, y});
  }
  maze.set_goals(goals);
  const auto start = std::chrono::steady_clock::now();
  const Maze read = ParseMazeText(FormatMazeText(maze), "goals.txt");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  // every cell but the start, which shows 'S'
  EXPECT_EQ(read.goals().size(), goals.size() - 1);
  EXPECT_TRUE(read.IsGoal({kMaxMazeSide_cells - 1, kMaxMazeSide_cells - 1}));
  EXPECT_FALSE(read.IsGoal({0, 0}));
}

TEST(MazeTextTest, ReadsTheDissertationsMazes) {
  const std::string dir = UNIMOUSE_SOURCE_DIR "/mazes/";
  for (const char* name : {"japan2018.txt", "japan2019.txt"}) {
    const Maze maze = LoadMaze(dir + name);
    EXPECT_EQ(maze.width(), 16);
    EXPECT_EQ(maze.height(), 16);
    EXPECT_EQ(maze.start(), (Cell{0, 0}));
    EXPECT_EQ(maze.goals().size(), 4u);
    EXPECT_TRUE(maze.HasWall({0, 0}, Heading::kEast));  // the classic start cell
  }
}

TEST(MazeTextTest, ReadsEveryMazeOfTheContestCollection) {
  const std::string dir = testing::SharedMazesDir();
  if (dir.empty())
    GTEST_SKIP() << "the maze collection (../shared/mazes) is not beside the project";
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".txt") continue;
    const Maze maze = LoadMaze(entry.path().string());
    EXPECT_GE(maze.width(), 1) << entry.path();
    ++count;
  }
  EXPECT_EQ(count, 579);
}

}  // namespace
}  // namespace unimouse
