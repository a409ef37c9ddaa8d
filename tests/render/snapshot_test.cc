// SPDX-License-Identifier: GPL-3.0-or-later
// Offscreen pictures: size, content, the robot where the pinhole camera puts it, the HUD, the
// ToF beams' colours and repeatability. Skipped with the reason when no EGL display can be made.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "egl_context.h"
#include "inline_assets.h"
#include "plugin_rig.h"
#include "scene_renderer.h"

namespace unimouse {
namespace {

using testing::MakeKernel;
using testing::SetSignal;

const Maze& Japan2018() {
  static const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  return maze;
}

class SnapshotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      egl_ = EglContext::Create();
    } catch (const RenderUnavailable& e) {
      GTEST_SKIP() << "no offscreen rendering on this machine: " << e.what();
    }
  }

  // the bundled robot, or the one in `yaml`, at `spawn` in `maze` (an open floor when null),
  // with a renderer
  void Build(const Maze* maze, std::optional<Pose2D> spawn, uint64_t seed = 1,
             const std::string& yaml = testing::ReadBundledRobot()) {
    robot_ = ParseRobotSpec(yaml, "unimouse.yaml");
    KernelOptions options;
    options.seed = seed;
    options.spawn = spawn;
    options.output_dir = ::testing::TempDir();
    kernel_ = MakeKernel(yaml, maze, options);
    kernel_->Step();
    renderer_ = std::make_unique<SceneRenderer>(*kernel_);
  }

  Image Picture(int width, int height, DrawOptions draw, const std::string& camera = "top") {
    return renderer_->Snapshot(width, height, camera, draw);
  }

  std::unique_ptr<EglContext> egl_;
  RobotSpec robot_;
  std::unique_ptr<Kernel> kernel_;
  std::unique_ptr<SceneRenderer> renderer_;
};

const uint8_t* Pixel(const Image& image, int x, int y) {
  return image.rgb.data() + (static_cast<size_t>(y) * image.width + x) * 3;
}

// counts pixels for which `is` holds, and their centroid
template <class Predicate>
int CountPixels(const Image& image, Predicate is, double* cx = nullptr, double* cy = nullptr) {
  int n = 0;
  double sx = 0, sy = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = Pixel(image, x, y);
      if (!is(p[0], p[1], p[2])) continue;
      ++n;
      sx += x;
      sy += y;
    }
  }
  if (cx != nullptr && n > 0) *cx = sx / n;
  if (cy != nullptr && n > 0) *cy = sy / n;
  return n;
}

// the robot's plate (rgba 0.15 0.45 0.2 in robots/unimouse.yaml): clearly greener than grey
bool PlateColour(int r, int g, int b) { return g > r + 40 && g > b + 40; }

constexpr DrawOptions kSceneOnly{.beams = false, .beliefs = false, .hud = {}, .clock = false};

TEST_F(SnapshotTest, HasTheSizeAskedForAndIsNotBlank) {
  Build(&Japan2018(), std::nullopt);
  const Image image = Picture(320, 200, kSceneOnly);
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 200);
  ASSERT_EQ(image.rgb.size(), 320u * 200 * 3);
  // a maze seen from above: many light wall pixels on a dark floor
  const int light = CountPixels(image, [](int r, int g, int b) { return r + g + b > 450; });
  const int dark = CountPixels(image, [](int r, int g, int b) { return r + g + b < 150; });
  // 275 walls, 49.5 m, at some 65 pixels a metre and under a pixel wide: about 1800 pixels
  EXPECT_GT(light, 1000);
  EXPECT_GT(dark, 320 * 200 / 4);
}

// where a pinhole camera looking straight down puts a point: MuJoCo's free camera with
// elevation -90 and azimuth 90 looks along -z with north up, and fovy is the vertical view angle
struct Projected {
  double col, row;
};
Projected ProjectTopDown(const mjvCamera& cam, double fovy_deg, int width, int height, double x,
                         double y, double z) {
  const double depth = cam.lookat[2] + cam.distance - z;
  const double half_height_m = depth * std::tan(fovy_deg / 2 * std::numbers::pi / 180);
  const double aspect = static_cast<double>(width) / height;
  const double ndc_x = (x - cam.lookat[0]) / (half_height_m * aspect);
  const double ndc_y = (y - cam.lookat[1]) / half_height_m;
  return {(1 + ndc_x) * width / 2 - 0.5, (1 - ndc_y) * height / 2 - 0.5};
}

TEST_F(SnapshotTest, ShowsTheRobotWherePoseAndCameraPutIt) {
  const int width = 640, height = 480;
  for (const Pose2D pose : {Pose2D{0.09 + 0.18 * 5, 0.09 + 0.18 * 9, 0},
                            Pose2D{0.09 + 0.18 * 12, 0.09 + 0.18 * 2, std::numbers::pi / 2}}) {
    Build(&Japan2018(), pose);
    const Image image = Picture(width, height, kSceneOnly);
    const mjData& d = kernel_->state().data();
    const int body = kernel_->world().robot_body();
    const double plate_top_z = d.xpos[3 * body + 2] + 0.010;  // half the plate's 0.020 m height
    const mjvCamera cam = renderer_->Camera("top", static_cast<double>(width) / height);
    const Projected expected =
        ProjectTopDown(cam, kernel_->mj_model().vis.global.fovy, width, height, d.xpos[3 * body],
                       d.xpos[3 * body + 1], plate_top_z);
    double cx = 0, cy = 0;
    const int plate = CountPixels(image, PlateColour, &cx, &cy);
    // the plate is 0.120 x 0.096 m: some 25 x 20 pixels at this scale; measured within 0.2 px
    EXPECT_GT(plate, 150);
    EXPECT_NEAR(cx, expected.col, 0.5) << "robot at " << pose.x_m << ", " << pose.y_m;
    EXPECT_NEAR(cy, expected.row, 0.5) << "robot at " << pose.x_m << ", " << pose.y_m;
  }
}

TEST_F(SnapshotTest, DrawsTheHudText) {
  Build(&Japan2018(), std::nullopt);
  DrawOptions with = kSceneOnly;
  with.hud = {"lap 2 of 3", "best 00:12.345"};
  const Image plain = Picture(640, 480, kSceneOnly);
  const Image hud = Picture(640, 480, with);
  // the text sits at the top left and nowhere else
  auto differ_in = [&](int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        n += !std::equal(Pixel(plain, x, y), Pixel(plain, x, y) + 3, Pixel(hud, x, y));
      }
    }
    return n;
  };
  EXPECT_GT(differ_in(0, 0, 200, 80), 400);  // two lines of letters, some 30 pixels each
  EXPECT_EQ(differ_in(0, 240, 640, 480), 0);
  EXPECT_EQ(differ_in(320, 0, 640, 480), 0);
  // the letters are white
  int white = 0;
  for (int y = 0; y < 80; ++y) {
    for (int x = 0; x < 200; ++x) white += Pixel(hud, x, y)[0] > 220 && Pixel(hud, x, y)[2] > 220;
  }
  EXPECT_GT(white, 100);
}

// the pixels the beams change, counted as green (a hit) or red (a miss)
struct BeamPixels {
  int green = 0;
  int red = 0;
};
BeamPixels CountBeamPixels(const Image& without, const Image& with) {
  BeamPixels n;
  for (size_t i = 0; i < with.rgb.size(); i += 3) {
    if (std::equal(with.rgb.begin() + i, with.rgb.begin() + i + 3, without.rgb.begin() + i))
      continue;
    const int r = with.rgb[i], g = with.rgb[i + 1], b = with.rgb[i + 2];
    n.green += g > r + 80 && g > b + 80;
    n.red += r > g + 80 && r > b + 80;
  }
  return n;
}

TEST_F(SnapshotTest, BeamsAreGreenOnAHitAndRedOnAMiss) {
  DrawOptions beams = kSceneOnly;
  beams.beams = true;
  // in the start cell every beam meets a wall within 1.2 m
  Build(&Japan2018(), std::nullopt);
  for (int i = 0; i < 40; ++i) kernel_->Step();  // a ToF period: every sensor has read
  BeamPixels n =
      CountBeamPixels(Picture(640, 480, kSceneOnly, "chase"), Picture(640, 480, beams, "chase"));
  EXPECT_GT(n.green, 500);
  EXPECT_EQ(n.red, 0);
  // on an open floor nothing is hit
  Build(nullptr, std::nullopt);
  for (int i = 0; i < 40; ++i) kernel_->Step();
  n = CountBeamPixels(Picture(640, 480, kSceneOnly, "chase"), Picture(640, 480, beams, "chase"));
  EXPECT_GT(n.red, 500);
  EXPECT_EQ(n.green, 0);
}

TEST_F(SnapshotTest, AFiveTofRobotDrawsFiveBeams) {
  DrawOptions beams = kSceneOnly;
  beams.beams = true;
  // on an open floor every beam misses: 1.2 m of red each
  auto red_pixels = [&](const std::string& yaml) {
    Build(nullptr, std::nullopt, 1, yaml);
    for (int i = 0; i < 40; ++i) kernel_->Step();
    return CountBeamPixels(Picture(640, 480, kSceneOnly), Picture(640, 480, beams)).red;
  };
  const int three = red_pixels(testing::ReadBundledRobot());
  const int five = red_pixels(testing::FiveTofRobot());
  // the sensors declared their beams; the renderer knows nothing of the robot's sensors
  EXPECT_EQ(kernel_->model().beams.size(), 5u);
  EXPECT_GT(three, 300);
  EXPECT_GT(five, three * 3 / 2);
}

TEST_F(SnapshotTest, TheSameSeedGivesTheSameImage) {
  // 0.5 s of driving in a curve: motion and noisy ToF readings, all from the seed
  auto driven = [&](uint64_t seed) {
    Build(&Japan2018(), std::nullopt, seed);
    SetSignal(*kernel_, "left.command", 700);
    SetSignal(*kernel_, "right.command", 500);
    for (int i = 0; i < 500; ++i) kernel_->Step();
    return Picture(640, 480, {.hud = {"run 1"}}, "chase");
  };
  const Image a = driven(7);
  const Image b = driven(7);
  EXPECT_EQ(a.rgb, b.rgb);
  // and the picture shows the state: other noise in the readings, other beam lengths
  const Image c = driven(8);
  EXPECT_NE(a.rgb, c.rgb);
}

TEST_F(SnapshotTest, DrawsTheWallsTheFirmwareBelievesIn) {
  Build(&Japan2018(), std::nullopt);
  FirmwareBeliefs beliefs;
  unimouse_report walls{};
  walls.size = sizeof(walls);
  walls.kind = UNIMOUSE_REPORT_WALLS;
  walls.walls = 2 | 4 | 8;  // east, south, west
  walls.known = 15;
  ASSERT_TRUE(beliefs.Apply(walls));
  DrawOptions draw = kSceneOnly;
  draw.firmware = &beliefs;
  const Image plain = Picture(640, 480, kSceneOnly);
  draw.beliefs = false;
  EXPECT_EQ(Picture(640, 480, draw).rgb, plain.rgb);  // toggled off
  draw.beliefs = true;
  const Image shown = Picture(640, 480, draw);
  // three blue strips along the start cell's walls, and nothing else changed
  int blue = 0, other = 0;
  for (size_t i = 0; i < shown.rgb.size(); i += 3) {
    if (std::equal(shown.rgb.begin() + i, shown.rgb.begin() + i + 3, plain.rgb.begin() + i))
      continue;
    const int r = shown.rgb[i], b = shown.rgb[i + 2];
    (b > r + 60 ? blue : other)++;
  }
  EXPECT_GT(blue, 3 * 25);  // each strip is a cell long: some 50 pixels at this scale
  EXPECT_LT(other, blue / 2);
}

TEST_F(SnapshotTest, DrawsReportedCellColoursAsFloorTilesAndTextsAsLabels) {
  Build(&Japan2018(), std::nullopt);
  FirmwareBeliefs beliefs;
  beliefs.colours[{3, 0}] = 'r';
  DrawOptions draw = kSceneOnly;
  draw.beliefs = true;
  draw.firmware = &beliefs;
  const Image plain = Picture(640, 480, kSceneOnly);
  const Image tiled = Picture(640, 480, draw);
  // a red tile on cell (3, 0), clear of the robot on the start cell: some 25 x 25 pixels at
  // this scale, and nothing else changed
  int red = 0, other = 0;
  for (size_t i = 0; i < tiled.rgb.size(); i += 3) {
    if (std::equal(tiled.rgb.begin() + i, tiled.rgb.begin() + i + 3, plain.rgb.begin() + i))
      continue;
    const int r = tiled.rgb[i], g = tiled.rgb[i + 1], b = tiled.rgb[i + 2];
    (r > g + 60 && r > b + 60 ? red : other)++;
  }
  EXPECT_GT(red, 300);
  EXPECT_LT(other, red / 4);
  // a text adds its label's pixels
  beliefs.texts[{3, 0}] = "12";
  EXPECT_NE(Picture(640, 480, draw).rgb, tiled.rgb);
}

TEST_F(SnapshotTest, RefusesUnknownCamerasAndSizes) {
  Build(nullptr, std::nullopt);
  EXPECT_THROW(Picture(640, 480, {}, "side"), InputError);
  EXPECT_THROW(Picture(8, 480, {}), InputError);
  EXPECT_THROW(Picture(640, 5000, {}), InputError);
}

}  // namespace
}  // namespace unimouse
