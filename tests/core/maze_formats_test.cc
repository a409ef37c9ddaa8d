// SPDX-License-Identifier: GPL-3.0-or-later
// Maze formats told apart by content: the text variants, mms .num, binary .maz in any layout
// and bit order; and the corpus of broken files in tests/data/broken_mazes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "maze.h"
#include "maze_generator.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

std::string WriteTemp(const std::string& name, const std::string& content) {
  const fs::path path = fs::temp_directory_path() / ("unimouse_format_" + name);
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

// the standard binary layout, encoded here independently: x = i div n, y = i mod n,
// N=1 E=2 S=4 W=8
std::string EncodeBinary(const Maze& m, bool transposed = false, bool other_bits = false) {
  std::string bytes;
  const int n = m.width();
  for (int i = 0; i < n * n; ++i) {
    int x = i / n, y = i % n;
    if (transposed) std::swap(x, y);
    const int bit_n = other_bits ? 8 : 1, bit_e = other_bits ? 4 : 2, bit_s = other_bits ? 2 : 4,
              bit_w = other_bits ? 1 : 8;
    int b = 0;
    if (m.HasWall({x, y}, Heading::kNorth)) b |= bit_n;
    if (m.HasWall({x, y}, Heading::kEast)) b |= bit_e;
    if (m.HasWall({x, y}, Heading::kSouth)) b |= bit_s;
    if (m.HasWall({x, y}, Heading::kWest)) b |= bit_w;
    bytes += static_cast<char>(b);
  }
  return bytes;
}

std::string Walls(const Maze& m) {
  // the text drawing without markers compares walls only
  std::string text = FormatMazeText(m);
  for (char& c : text) {
    if (c == 'S' || c == 'G') c = ' ';
  }
  return text;
}

TEST(MazeFormatsTest, ReadsTheNumFormat) {
  // mms's own example: a 2 x 1 corridor closed at both ends
  const Maze m = ParseMazeNum("0 0 1 0 1 1\n1 0 1 1 1 0\n", "c.num");
  EXPECT_EQ(m.width(), 2);
  EXPECT_EQ(m.height(), 1);
  EXPECT_FALSE(m.HasWall({0, 0}, Heading::kEast));
  EXPECT_TRUE(m.HasWall({1, 0}, Heading::kEast));
  EXPECT_EQ(m.start_heading(), Heading::kEast);  // its only exit
}

TEST(MazeFormatsTest, NumAndTextDescribeTheSameMaze) {
  const Maze maze = GenerateMaze({7, 5, 3, 0.2});
  std::ostringstream num;
  for (int y = maze.height() - 1; y >= 0; --y) {
    for (int x = 0; x < maze.width(); ++x) {
      num << x << ' ' << y << ' ' << maze.HasWall({x, y}, Heading::kNorth) << ' '
          << maze.HasWall({x, y}, Heading::kEast) << ' ' << maze.HasWall({x, y}, Heading::kSouth)
          << ' ' << maze.HasWall({x, y}, Heading::kWest) << "\r\n";
    }
  }
  EXPECT_EQ(Walls(ParseMazeNum(num.str(), "m.num")), Walls(maze));
}

TEST(MazeFormatsTest, ReadsBinaryMazesInTheStandardLayout) {
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  std::string layout;
  const Maze read = ParseMazeBinary(EncodeBinary(maze), "j.maz", &layout);
  EXPECT_EQ(Walls(read), Walls(maze));
  EXPECT_EQ(layout, "binary .maz, column-major from the south-west, bits N=1 E=2 S=4 W=8");
  EXPECT_EQ(EncodeBinary(maze)[0], 0x0E);  // the classic start byte: E + S + W
}

TEST(MazeFormatsTest, DetectsOtherLayoutsAndBitOrders) {
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2019.txt");
  std::string layout;
  EXPECT_EQ(Walls(ParseMazeBinary(EncodeBinary(maze, true, false), "t.maz", &layout)), Walls(maze));
  EXPECT_NE(layout.find("layout 1 of 8"), std::string::npos) << layout;
  EXPECT_EQ(Walls(ParseMazeBinary(EncodeBinary(maze, false, true), "b.maz", &layout)), Walls(maze));
  EXPECT_NE(layout.find("bits W=1 S=2 E=4 N=8"), std::string::npos) << layout;
}

TEST(MazeFormatsTest, TellsFormatsApartByContentNotExtension) {
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  std::string format;
  // a .maz that is really .num text, as mms's older releases shipped
  LoadMaze(WriteTemp("num.maz", "0 0 1 0 1 1\n1 0 1 1 1 0\n"), &format);
  EXPECT_EQ(format, "num");
  EXPECT_EQ(Walls(LoadMaze(WriteTemp("bin.txt", EncodeBinary(maze)), &format)), Walls(maze));
  EXPECT_NE(format.find("binary .maz"), std::string::npos);
  LoadMaze(WriteTemp("text.num", FormatMazeText(maze)), &format);
  EXPECT_EQ(format, "text");
}

TEST(MazeFormatsTest, TextMayLeaveOutPostsAndEndWithFreeText) {
  const Maze m = ParseMazeText(
      "o---o---o---o\n"
      "|           |\n"
      "o           o\n"
      "| S     |   |\n"
      "o---o---o---o\n"
      "\n"
      "Drawn from the 1990 final; posts without walls omitted.\n",
      "m.txt");
  EXPECT_EQ(m.width(), 3);
  EXPECT_EQ(m.height(), 2);
  EXPECT_TRUE(m.HasWall({1, 0}, Heading::kEast));
  EXPECT_FALSE(m.HasWall({1, 0}, Heading::kNorth));
}

TEST(MazeFormatsTest, TextWithOneNonAsciiByteInItsNotesIsStillText) {
  const std::string drawing =
      "o---o---o\n"
      "|       |\n"
      "o   o   o\n"
      "| S |   |\n"
      "o---o---o\n"
      "\n";
  std::string format;
  // UTF-8, then a lone Latin-1 byte
  for (const std::string notes : {"Drawn by Ren\xc3\xa9"
                                  "e.\n",
                                  "Drawn by Ren\xe9"
                                  "e.\n"}) {
    const Maze m = LoadMaze(WriteTemp("accent.txt", drawing + notes), &format);
    EXPECT_EQ(format, "text");
    EXPECT_EQ(m.width(), 2);
    EXPECT_TRUE(m.HasWall({0, 0}, Heading::kEast));
  }
}

// what reading `content` says, or "read" when it reads
std::string LoadError(const std::string& name, const std::string& content) {
  try {
    LoadMaze(WriteTemp(name, content));
  } catch (const InputError& e) {
    return e.what();
  }
  return "read";
}

TEST(MazeFormatsTest, ANumCoordinateBeyondTheLimitIsRefusedAtItsLine) {
  const std::string path = WriteTemp("big.num", "");
  EXPECT_EQ(LoadError("big.num", "0 0 1 1 1 1\n2147483647 0 1 1 1 1\n"),
            path +
                ":2:1: a 2147483648 x 1 maze is larger than the 256 x 256 cells unimouse "
                "reads (docs/limits.md)");
  EXPECT_EQ(LoadError("big.num", "0 0 1 1 1 1\n1023 1023 1 1 1 1\n"),
            path +
                ":2:1: a 1024 x 1024 maze is larger than the 256 x 256 cells unimouse reads "
                "(docs/limits.md)");
}

TEST(MazeFormatsTest, TheLargestMazeIsReadInEveryFormatAndOneMoreIsRefused) {
  Maze largest(kMaxMazeSide_cells, kMaxMazeSide_cells);
  for (int i = 0; i < kMaxMazeSide_cells; ++i) {
    largest.SetWall({i, 0}, Heading::kSouth, true);
    largest.SetWall({i, kMaxMazeSide_cells - 1}, Heading::kNorth, true);
    largest.SetWall({0, i}, Heading::kWest, true);
    largest.SetWall({kMaxMazeSide_cells - 1, i}, Heading::kEast, true);
  }
  EXPECT_EQ(LoadError("largest.txt", FormatMazeText(largest)), "read");
  const std::string path = WriteTemp("wider.txt", "");
  std::string posts = "o";
  for (int x = 0; x <= kMaxMazeSide_cells; ++x) posts += "   o";
  EXPECT_EQ(LoadError("wider.txt", posts + "\n|\n" + posts + "\n"),
            path +
                ": a 257 x 1 maze is larger than the 256 x 256 cells unimouse reads "
                "(docs/limits.md)");
  const std::string bin = WriteTemp("huge.maz", "");
  EXPECT_EQ(LoadError("huge.maz", std::string(kMaxMazeSide_cells * kMaxMazeSide_cells + 1, '\x0e')),
            bin +
                ": 65537 bytes is more than a binary maze of at most 256 x 256 cells has "
                "(docs/limits.md)");
}

TEST(MazeFormatsTest, EveryBrokenFileOfTheCorpusGivesItsExpectedError) {
  const fs::path dir = UNIMOUSE_SOURCE_DIR "/tests/data/broken_mazes";
  int cases = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path file = entry.path();
    if (file.extension() == ".expected" || file.extension() == ".md") continue;
    std::ifstream expected_in(file.string() + ".expected");
    ASSERT_TRUE(expected_in.good()) << file << " has no .expected file";
    std::string expected;
    std::getline(expected_in, expected);
    const std::string prefix = file.parent_path().string() + "/";
    try {
      LoadMaze(file.string());
      ADD_FAILURE() << file << " was read without error";
    } catch (const InputError& e) {
      EXPECT_EQ(prefix + expected, e.what()) << file;
    }
    ++cases;
  }
  EXPECT_GE(cases, 13);
}

}  // namespace
}  // namespace unimouse
