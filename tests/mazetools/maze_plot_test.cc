// SPDX-License-Identifier: GPL-3.0-or-later
// Maze pictures show what they should where geometry says: walls, the start, the goal, paths,
// and walls not yet seen in a lighter colour.
#include "maze_plot.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdio>
#include <filesystem>

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
