// SPDX-License-Identifier: GPL-3.0-or-later
// The picture of an mms run shows the display commands the program sent, where the plot's
// geometry puts its cells, and the mouse's last cell.
#include "mms_picture.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>

#include "bitmap_font.h"
#include "inline_assets.h"
#include "maze_plot.h"
#include "png_file.h"
#include "run_program.h"

namespace unimouse {
namespace {

using Px = std::array<int, 3>;

struct Png {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  Px At(int x, int y) const {
    const uint8_t* p = &rgb[static_cast<size_t>((y * width + x) * 3)];
    return {p[0], p[1], p[2]};
  }
};

TEST(MmsPictureTest, SetWallsColoursAndTextsAreDrawnAndClearedOnesAreNot) {
  const Maze maze = ParseMazeText(testing::kOpenMaze5x5, "open.txt");
  MmsWorld world(maze, {});
  for (const char* line :
       {"setWall 1 1 n", "setWall 2 1 n", "clearWall 2 1 n", "setColor 3 3 r", "setColor 4 3 b",
        "clearColor 4 3", "setText 4 4 Z", "clearAllText", "setText 0 4 A", "setText 1 4 k"}) {
    EXPECT_NE(world.Handle(line).kind, MmsResponse::Kind::kInvalid) << line;
  }
  EXPECT_EQ(world.Handle("setColor 1 3 X").kind, MmsResponse::Kind::kInvalid);
  EXPECT_EQ(world.Handle("moveForward").reply, "ack");  // to (0, 1)
  const std::string dir = testing::FreshDirectory("mms_picture");
  WriteMmsPictures(maze, world, dir);
  EXPECT_TRUE(std::filesystem::exists(dir + "/maze.svg"));
  Png png;
  png.rgb = ReadPng(dir + "/maze.png", &png.width, &png.height);

  // 5 x 5 cells of 32 px in a 16 px margin: cell (x, y) has its centre at (32 + 32 x, 160 - 32 y)
  const PlotGeometry g;
  ASSERT_EQ(png.width, 2 * 16 + 5 * 32);
  auto cx = [](int x) { return 32 + 32 * x; };
  auto cy = [](int y) { return 160 - 32 * y; };
  EXPECT_EQ(g.CentreY(maze, 1), cy(1));
  const Px blue{51, 140, 255}, white{255, 255, 255};
  // the set wall between (1, 1) and (1, 2), where the maze has none; not the cleared one
  EXPECT_EQ(png.At(cx(1), cy(1) - 16), blue);
  EXPECT_EQ(png.At(cx(1) + 13, cy(1) - 17), blue);
  EXPECT_EQ(png.At(cx(2), cy(1) - 16), white);
  // red (3, 3); (4, 3) cleared and (1, 3) given an unknown letter: white
  EXPECT_EQ(png.At(cx(3) - 12, cy(3) + 12), (Px{255, 0, 0}));
  EXPECT_EQ(png.At(cx(4) - 12, cy(3) + 12), white);
  EXPECT_EQ(png.At(cx(1) - 12, cy(3) + 12), white);
  // "A" in (0, 4): font pixels of 3 from (centre - 7, centre - 10), its crossbar row 3 full;
  // (4, 4) cleared, (1, 4) "k" after clearAllText
  for (int gx = 0; gx < kGlyphWidth_px; ++gx) {
    EXPECT_EQ(png.At(cx(0) - 7 + 3 * gx + 1, cy(4) - 10 + 3 * 3 + 1), (Px{30, 30, 30})) << gx;
  }
  EXPECT_EQ(png.At(cx(4) - 7 + 1, cy(4) - 10 + 1), white);             // Z's top row would be full
  EXPECT_EQ(png.At(cx(1) - 7 + 1, cy(4) - 10 + 1), (Px{30, 30, 30}));  // k's column
  // the mouse's frame in (0, 1)
  EXPECT_EQ(png.At(cx(0) - 11, cy(1)), (Px{220, 0, 140}));
}

}  // namespace
}  // namespace unimouse
