// SPDX-License-Identifier: GPL-3.0-or-later
// Maze pictures show what they should where geometry says: walls, the start, the goal, paths,
// walls not yet seen in a lighter colour, and what a firmware or program reported: believed
// walls, cell colours and texts, and the mouse's cell.
#include "maze_plot.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdio>
#include <filesystem>

#include "bitmap_font.h"
#include "inline_assets.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  std::array<int, 3> At(int x, int y) const {
    const uint8_t* p = &rgb[static_cast<size_t>((y * width + x) * 3)];
    return {p[0], p[1], p[2]};
  }
};

Image ReadPng(const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_file(&image, path.c_str())) << path;
  image.format = PNG_FORMAT_RGB;
  Image out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr));
  return out;
}

class MazePlotTest : public ::testing::Test {
 protected:
  const Maze maze_ = ParseMazeText(testing::kSmallMaze, "small.txt");
  const PlotGeometry g_;
  // one file per test: ctest runs tests in parallel processes
  const std::string png_ =
      (std::filesystem::temp_directory_path() /
       ("unimouse_plot_" +
        std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".png"))
          .string();
};

TEST_F(MazePlotTest, PngShowsWallsStartGoalAndPathWhereTheGeometrySays) {
  MazePicture picture;
  picture.maze = &maze_;
  const OpenSides sides(maze_);
  StateFloodFill fill;
  fill.Compute(sides, maze_.goals());
  picture.closed_path = fill.PathFrom(sides, maze_.start(), maze_.start_heading());
  ASSERT_TRUE(picture.closed_path.found);
  WriteMazePng(picture, png_);
  const Image img = ReadPng(png_);

  // 3 x 2 cells of 32 px and a 16 px margin
  EXPECT_EQ(img.width, 2 * 16 + 3 * 32);
  EXPECT_EQ(img.height, 2 * 16 + 2 * 32);
  // the start cell (0, 0) is green inside, clear of the path at its corner
  EXPECT_EQ(img.At(g_.CentreX(maze_, 0) - 10, g_.CentreY(maze_, 0) + 10),
            (std::array<int, 3>{170, 225, 170}));
  // the south wall of (0, 0) lies 16 px below its centre, dark
  EXPECT_EQ(img.At(g_.CentreX(maze_, 0) + 8, g_.CentreY(maze_, 0) + 16),
            (std::array<int, 3>{30, 30, 30}));
  // no wall between (0, 0) and (1, 0): the midpoint of that side is not dark
  EXPECT_NE(img.At(g_.CentreX(maze_, 0) + 16, g_.CentreY(maze_, 0) + 8),
            (std::array<int, 3>{30, 30, 30}));
  // the goal is the centre column: the path leaves the start east into (1, 0), drawn blue
  // 3 px below the line of centres
  EXPECT_EQ(picture.closed_path.cells, (std::vector<Cell>{{0, 0}, {1, 0}}));
  EXPECT_EQ(img.At(g_.CentreX(maze_, 0) + 16, g_.CentreY(maze_, 0) + 3),
            (std::array<int, 3>{31, 95, 214}));
}

TEST_F(MazePlotTest, WallsTheMouseHasNotSeenAreLight) {
  WallKnowledge knowledge(maze_);
  knowledge.Sense(maze_, {0, 0});
  MazePicture picture;
  picture.maze = &maze_;
  picture.knowledge = &knowledge;
  WriteMazePng(picture, png_);
  const Image img = ReadPng(png_);
  // seen: the south wall of the start cell; not seen: the far east wall
  EXPECT_EQ(img.At(g_.CentreX(maze_, 0) + 8, g_.CentreY(maze_, 0) + 16),
            (std::array<int, 3>{30, 30, 30}));
  EXPECT_EQ(img.At(g_.CentreX(maze_, 2) + 16, g_.CentreY(maze_, 1) + 8),
            (std::array<int, 3>{200, 200, 200}));
  // the visited start keeps its start colour; an unvisited cell stays white
  EXPECT_EQ(img.At(g_.CentreX(maze_, 2) - 10, g_.CentreY(maze_, 1) + 10),
            (std::array<int, 3>{255, 255, 255}));
}

TEST_F(MazePlotTest, SvgHasOneLinePerWallAndThePathThroughEveryCell) {
  MazePicture picture;
  picture.maze = &maze_;
  picture.open_path = DescribeRoute({{0, 0}, {0, 1}, {1, 1}}, Heading::kNorth);
  const std::string svg = RenderMazeSvg(picture);
  int walls = 0;
  for (size_t at = svg.find("class='wall'"); at != std::string::npos;
       at = svg.find("class='wall'", at + 1)) {
    ++walls;
  }
  EXPECT_EQ(walls, 13);  // the small maze's 7 east-west and 6 north-south walls
  EXPECT_NE(svg.find("class='open-path' fill='none' stroke-width='3' stroke='#ff8c00' "
                     "points='29,61 29,29 61,29 '"),
            std::string::npos)
      << svg;
}

TEST_F(MazePlotTest, ReportedWallsColoursTextsAndTheMouseAreDrawnWhereTheGeometrySays) {
  using Px = std::array<int, 3>;
  const Px blue{51, 140, 255}, dark{30, 30, 30}, white{255, 255, 255};
  FirmwareBeliefs beliefs;
  beliefs.walls[{0, 0}] = {1, 1 | 2};  // north believed (none is there), east known open
  beliefs.walls[{1, 0}] = {2, 2};      // east believed, where the true wall is
  beliefs.walls[{7, 7}] = {15, 15};    // outside the maze: left out
  beliefs.colours[{2, 1}] = 'g';
  beliefs.colours[{2, 0}] = '!';  // not a colour: the cell keeps its own
  beliefs.colours[{1, 1}] = 'B';
  beliefs.texts[{0, 1}] = "A";
  beliefs.texts[{1, 1}] = "abcdefg";
  MazePicture picture;
  picture.maze = &maze_;
  picture.beliefs = &beliefs;
  picture.mouse = Cell{2, 0};
  WriteMazePng(picture, png_);
  const Image img = ReadPng(png_);
  auto cx = [&](int x) { return g_.CentreX(maze_, x); };
  auto cy = [&](int y) { return g_.CentreY(maze_, y); };

  // believed walls: a 2 px strip on the wall's line, 2 px short of the posts; the true wall's
  // edges stay dark around it
  EXPECT_EQ(img.At(cx(0), cy(0) - 16), blue);
  EXPECT_EQ(img.At(cx(0), cy(0) - 17), blue);
  EXPECT_NE(img.At(cx(0), cy(0) - 18), blue);
  EXPECT_NE(img.At(cx(0) + 16, cy(0)), blue);  // known open: nothing drawn
  EXPECT_EQ(img.At(cx(1) + 16, cy(0)), blue);
  EXPECT_EQ(img.At(cx(1) + 14, cy(0)), dark);
  EXPECT_EQ(img.At(cx(1) + 17, cy(0)), dark);

  // colours fill the cell; an unknown letter changes nothing
  EXPECT_EQ(img.At(cx(2) - 10, cy(1) + 10), (Px{0, 255, 0}));
  EXPECT_EQ(img.At(cx(1) - 13, cy(1) + 13), (Px{0, 0, 128}));
  const Image plain = [&] {
    MazePicture without = picture;
    without.beliefs = nullptr;
    WriteMazePng(without, png_);
    return ReadPng(png_);
  }();
  EXPECT_EQ(img.At(cx(2) - 13, cy(0) + 13), plain.At(cx(2) - 13, cy(0) + 13));

  // "A" alone: font pixels of 3 (6 x 3 <= 28, 8 x 3 <= 28), from (centre - 7, centre - 10),
  // dark on white
  for (int gy = 0; gy < kGlyphHeight_px; ++gy) {
    for (int gx = 0; gx < kGlyphWidth_px; ++gx) {
      const bool on = GlyphOf('A')[static_cast<size_t>(gy)] >> (4 - gx) & 1;
      EXPECT_EQ(img.At(cx(0) - 7 + 3 * gx + 1, cy(1) - 10 + 3 * gy + 1), on ? dark : white)
          << gx << "," << gy;
    }
  }
  // "abcdefg": "abcde" over "fg", font pixels of 1, white on dark blue; rows start at
  // (centre - 14, centre - 7) and (centre - 5, centre + 1)
  EXPECT_EQ(img.At(cx(1) - 14 + 1, cy(1) - 7 + 2), white);  // 'a' row 2: .###.
  EXPECT_EQ(img.At(cx(1) - 14 + 0, cy(1) - 7 + 2), (Px{0, 0, 128}));
  EXPECT_EQ(img.At(cx(1) - 5 + 2, cy(1) + 1), white);  // 'f' row 0: ..##.
  EXPECT_EQ(img.At(cx(1) - 5 + 1, cy(1) + 1), (Px{0, 0, 128}));

  // the mouse: a frame 2 px wide, 5 px inside its cell
  EXPECT_EQ(img.At(cx(2) - 11, cy(0)), (Px{220, 0, 140}));
  EXPECT_EQ(img.At(cx(2) - 10, cy(0) + 10), (Px{220, 0, 140}));
  EXPECT_NE(img.At(cx(2) - 9, cy(0)), (Px{220, 0, 140}));
}

TEST_F(MazePlotTest, SvgShowsReportedWallsColoursTextsAndTheMouse) {
  FirmwareBeliefs beliefs;
  beliefs.walls[{0, 0}] = {1 | 4, 15};
  beliefs.colours[{2, 1}] = 'r';
  beliefs.texts[{0, 1}] = "a<b&c d e f";
  MazePicture picture;
  picture.maze = &maze_;
  picture.beliefs = &beliefs;
  picture.mouse = Cell{0, 0};
  const std::string svg = RenderMazeSvg(picture);
  EXPECT_NE(svg.find("<line class='believed-wall' x1='18' y1='80' x2='46' y2='80' "
                     "stroke-width='2' stroke='#338cff'/>"),
            std::string::npos)
      << svg;  // the start's south side: y 16 + 2 x 32, from 16 + 2 to 48 - 2
  EXPECT_NE(svg.find("class='believed-wall' x1='18' y1='48'"), std::string::npos);
  EXPECT_NE(svg.find("fill='#ff0000'"), std::string::npos);
  EXPECT_NE(svg.find(">a&lt;b&amp;c<"), std::string::npos);
  EXPECT_NE(svg.find("> d e <"), std::string::npos);  // the second row: characters 6 to 10
  EXPECT_NE(svg.find("class='mouse'"), std::string::npos);
}

TEST_F(MazePlotTest, ThePictureKindFollowsTheFileName) {
  MazePicture picture;
  picture.maze = &maze_;
  EXPECT_THROW(
      WriteMazePicture(picture, (std::filesystem::temp_directory_path() / "picture.jpg").string()),
      InputError);
  EXPECT_THROW(WriteMazePicture(picture, "/nonexistent/dir/picture.png"), InputError);
}

}  // namespace
}  // namespace unimouse
