// SPDX-License-Identifier: GPL-3.0-or-later
// The floor's index finds every shape a query can meet, as a look at every shape would, and the
// walls a ray meets are the ones MuJoCo's ray cast over the whole scenery meets, to the bit.
#include "floor_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "inline_assets.h"
#include "maze.h"
#include "world.h"

namespace unimouse {
namespace {

// whether the segment from (x, y) along unit (ux, uy) for `length` meets the rectangle (slabs)
bool SegmentMeets(const FloorRect& r, double x, double y, double ux, double uy, double length) {
  double t0 = 0, t1 = length;
  const double lo[2] = {r.x0_m, r.y0_m}, hi[2] = {r.x1_m, r.y1_m}, p[2] = {x, y}, u[2] = {ux, uy};
  for (int k = 0; k < 2; ++k) {
    if (u[k] == 0) {
      if (p[k] < lo[k] || p[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - p[k]) / u[k], b = (hi[k] - p[k]) / u[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

std::vector<FloorRect> RandomRects(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> at(-1, 3), size(0.001, 0.4);
  std::vector<FloorRect> rects;
  for (int i = 0; i < n; ++i) {
    const double x = at(rng), y = at(rng);
    rects.push_back({x, y, x + size(rng), y + size(rng)});
  }
  return rects;
}

TEST(FloorGridTest, ARectangleQueryListsEveryShapeItOverlapsInAscendingOrder) {
  std::mt19937_64 rng(7);
  const std::vector<FloorRect> rects = RandomRects(rng, 400);
  const FloorGrid grid(rects, 0.18);
  std::uniform_real_distribution<double> at(-1.5, 3.5), size(0, 0.5);
  for (int q = 0; q < 500; ++q) {
    const double x = at(rng), y = at(rng);
    const FloorRect area{x, y, x + size(rng), y + size(rng)};
    std::vector<int> found;
    grid.ShapesNear(area, found);
    EXPECT_TRUE(std::is_sorted(found.begin(), found.end()));
    EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end());
    for (int i = 0; i < static_cast<int>(rects.size()); ++i) {
      const FloorRect& r = rects[i];
      const bool overlaps =
          r.x0_m <= area.x1_m && area.x0_m <= r.x1_m && r.y0_m <= area.y1_m && area.y0_m <= r.y1_m;
      if (overlaps) {
        EXPECT_TRUE(std::binary_search(found.begin(), found.end(), i)) << q << " " << i;
      }
    }
  }
}

TEST(FloorGridTest, ASegmentQueryListsEveryShapeItMeetsAlsoThroughCornersAndFromOutside) {
  std::mt19937_64 rng(11);
  const std::vector<FloorRect> rects = RandomRects(rng, 400);
  const FloorGrid grid(rects, 0.18);
  std::uniform_real_distribution<double> at(-2, 4), turn(0, 2 * 3.141592653589793), length(0, 3);
  for (int q = 0; q < 2000; ++q) {
    double x = at(rng), y = at(rng), a = turn(rng);
    // every tenth along an axis or a diagonal, and every twentieth from a square's corner: the
    // hard cases
    if (q % 10 == 0) a = (q / 10 % 8) * 3.141592653589793 / 4;
    if (q % 20 == 0) {
      x = grid.bounds().x0_m + grid.square_m() * (q % 7);
      y = grid.bounds().y0_m + grid.square_m() * (q % 5);
    }
    const double ux = std::cos(a), uy = std::sin(a), l = length(rng);
    std::vector<int> found;
    grid.ShapesAlong(x, y, ux, uy, l, found);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end());
    for (int i = 0; i < static_cast<int>(rects.size()); ++i) {
      if (SegmentMeets(rects[i], x, y, ux, uy, l)) {
        EXPECT_TRUE(std::binary_search(found.begin(), found.end(), i))
            << "query " << q << " misses shape " << i;
      }
    }
  }
}

TEST(FloorGridTest, WhatIsNotANumberOrFarAwayMeetsNothingAndEndsAtOnce) {
  std::mt19937_64 rng(5);
  const FloorGrid grid(RandomRects(rng, 50), 0.18);
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  std::vector<int> found;
  grid.ShapesAlong(nan, 1, 1, 0, 1, found);
  grid.ShapesAlong(1, 1, nan, 0, 1, found);
  grid.ShapesAlong(1, 1, 1, 0, inf, found);
  grid.ShapesAlong(1e12, 1e12, -1, -1, 1e3, found);  // far away, and never reaching the grid
  grid.ShapesAlong(-1e12, 1, 1, 0, 10, found);
  grid.ShapesNear({nan, 0, 1, 1}, found);
  grid.ShapesNear({1e12, 1e12, 2e12, 2e12}, found);
  EXPECT_TRUE(found.empty());
  // from far away along the grid's row, a long ray finds what a short one from the edge finds
  std::vector<int> near_edge, from_far;
  grid.ShapesAlong(grid.bounds().x0_m - 0.01, 1, 1, 0, 10, near_edge);
  grid.ShapesAlong(-1e9, 1, 1, 0, 2e9, from_far);
  std::sort(near_edge.begin(), near_edge.end());
  std::sort(from_far.begin(), from_far.end());
  EXPECT_FALSE(near_edge.empty());
  EXPECT_EQ(near_edge, from_far);
}

TEST(FloorGridTest, AWorldsRaysMeetTheSameWallAtTheSameDistanceAsMujocosRayOverEveryWall) {
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  const std::unique_ptr<World> world = World::Build(testing::BareRobot(), &maze);
  mjData* d = mj_makeData(&world->model());
  mj_forward(&world->model(), d);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> at(-0.1, 16 * 0.18 + 0.1), turn(-3.2, 3.2),
      tilt(-0.3, 0.3), height(0.005, 0.045);
  int hits = 0;
  for (int q = 0; q < 20000; ++q) {
    const double origin[3] = {at(rng), at(rng), height(rng)};
    const double a = turn(rng), e = q % 100 == 0 ? -1.5707963267948966 : tilt(rng);
    const double direction[3] = {std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e)};
    const double max_m = q % 2 ? 1.2 : 4;
    // what the world measured before it had an index: MuJoCo's ray over every scenery geom
    // (the maze's 577, here in two models), against the floor in the physics
    const mjtByte world_only[mjNGROUP] = {1, 0, 0, 0, 0, 0};
    int geom = -1;
    double expected = mj_ray(&world->model(), d, origin, direction, world_only, 1, -1, &geom);
    for (const World::SceneryChunk& chunk : world->scenery_chunks()) {
      const double wall =
          mj_ray(chunk.model.get(), chunk.data.get(), origin, direction, nullptr, 1, -1, &geom);
      if (wall >= 0 && (expected < 0 || wall < expected)) expected = wall;
    }
    if (!(expected >= 0 && expected <= max_m)) expected = -1;
    hits += expected >= 0;
    ASSERT_EQ(world->CastRay(*d, origin, direction, max_m), expected) << "ray " << q;
  }
  EXPECT_GT(hits, 10000);
  // a ray that is not a number meets nothing
  const double origin[3] = {std::nan(""), 0.1, 0.02}, east[3] = {1, 0, 0};
  EXPECT_EQ(world->CastRay(*d, origin, east, 1.2), -1);
  mj_deleteData(d);
}

}  // namespace
}  // namespace unimouse
