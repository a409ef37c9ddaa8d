// SPDX-License-Identifier: GPL-3.0-or-later
// Maze + robot -> MuJoCo world: walls and posts where the maze says (table 4.8: 0.18 m pitch,
// walls 168 x 12 x 50 mm, posts 12 x 12 x 50 mm), the robot at rest in the start cell.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "inline_assets.h"
#include "kernel.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using testing::kSmallMaze;

int CountKind(const std::vector<StaticBox>& boxes, StaticBox::Kind kind) {
  int n = 0;
  for (const auto& b : boxes) n += b.kind == kind;
  return n;
}

bool HasBox(const std::vector<StaticBox>& boxes, StaticBox::Kind kind, Vec3 centre, Vec3 half) {
  for (const auto& b : boxes) {
    bool same = b.kind == kind;
    for (int k = 0; k < 3; ++k) {
      same = same && std::fabs(b.center_m[k] - centre[k]) < 1e-12 &&
             std::fabs(b.half_m[k] - half[k]) < 1e-12;
    }
    if (same) return true;
  }
  return false;
}

TEST(MazeBoxesTest, OnePostPerGridCornerAndOneBoxPerWall) {
  const Maze maze = ParseMazeText(kSmallMaze, "small.txt");
  const std::vector<StaticBox> boxes = MazeBoxes(maze);
  EXPECT_EQ(CountKind(boxes, StaticBox::Kind::kPost), 4 * 3);
  // 3 north + 1 inner + 3 south east-west walls; 3 + 3 north-south walls
  EXPECT_EQ(CountKind(boxes, StaticBox::Kind::kWall), 13);
}

TEST(MazeBoxesTest, PostsAndWallsSitOnTheCellGrid) {
  const std::vector<StaticBox> boxes = MazeBoxes(ParseMazeText(kSmallMaze, "small.txt"));
  // posts at multiples of 0.18 m, 12 x 12 x 50 mm
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kPost, {0, 0, 0.025}, {0.006, 0.006, 0.025}));
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kPost, {0.54, 0.36, 0.025}, {0.006, 0.006, 0.025}));
  // the inner wall on line y = 1 over column 1: 168 x 12 x 50 mm
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kWall, {0.27, 0.18, 0.025}, {0.084, 0.006, 0.025}));
  // the north-south wall east of cell (1, 0)
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kWall, {0.36, 0.09, 0.025}, {0.006, 0.084, 0.025}));
  // and no wall between cells (0, 0) and (1, 0)
  EXPECT_FALSE(HasBox(boxes, StaticBox::Kind::kWall, {0.18, 0.09, 0.025}, {0.006, 0.084, 0.025}));
}

TEST(MazeBoxesTest, CollisionBoxesCoverRunsOfWallsWithTheirPosts) {
  const std::vector<StaticBox> runs = MazeCollisionBoxes(ParseMazeText(kSmallMaze, "small.txt"));
  // the south edge: one box from post 0 to post 3, posts included
  EXPECT_TRUE(HasBox(runs, StaticBox::Kind::kWall, {0.27, 0, 0.025}, {0.276, 0.006, 0.025}));
  // the west edge, two cells high
  EXPECT_TRUE(HasBox(runs, StaticBox::Kind::kWall, {0, 0.18, 0.025}, {0.006, 0.186, 0.025}));
  // every post touches a wall in this maze, so none stands alone
  EXPECT_EQ(CountKind(runs, StaticBox::Kind::kPost), 0);
  // south, north, inner; west, x = 2 (two cells), east
  EXPECT_EQ(runs.size(), 6u);
}

// the rule numbers (docs/mazes.md): classic 180 mm cells, walls and posts 12 mm thick and 50 mm
// high; half-size 90 mm cells, 6 mm thick and 25 mm high
// a maze of the given size with only the south wall of cell (0, 0) and the west wall of the
// north-west cell
Maze TwoWalls(int side) {
  Maze maze(side, side);
  maze.SetWall({0, 0}, Heading::kSouth, true);
  maze.SetWall({0, side - 1}, Heading::kWest, true);
  return maze;
}

TEST(MazeBoxesTest, AClassicMazeIsBuiltAtTheClassicRulesDimensions) {
  const std::vector<StaticBox> boxes = MazeBoxes(TwoWalls(16));
  // the north-east post of a 16 x 16 maze: 16 x 180 mm = 2.88 m from the origin
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kPost, {2.88, 2.88, 0.025}, {0.006, 0.006, 0.025}));
  // the south wall of cell (0, 0): 180 - 12 = 168 mm long between its posts
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kWall, {0.09, 0, 0.025}, {0.084, 0.006, 0.025}));
}

TEST(MazeBoxesTest, AMazeLargerThan16By16IsBuiltAtTheHalfSizeRulesDimensions) {
  const std::vector<StaticBox> boxes = MazeBoxes(TwoWalls(32));
  // the north-east post of a 32 x 32 maze: 32 x 90 mm = 2.88 m, 6 x 6 x 25 mm
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kPost, {2.88, 2.88, 0.0125}, {0.003, 0.003, 0.0125}));
  // the south wall of cell (0, 0): 90 - 6 = 84 mm long, 6 mm thick, 25 mm high
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kWall, {0.045, 0, 0.0125}, {0.042, 0.003, 0.0125}));
  // the west wall of cell (0, 31)
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kWall, {0, 2.835, 0.0125}, {0.003, 0.042, 0.0125}));
}

TEST(MazeBoxesTest, A16By16MazeSaidToBeHalfSizeIsBuiltAtHalfSize) {
  Maze maze = TwoWalls(16);
  for (int x = 1; x < 16; ++x) maze.SetWall({x, 0}, Heading::kSouth, true);
  maze.set_class(MazeClass::kHalfSize);
  const std::vector<StaticBox> boxes = MazeBoxes(maze);
  EXPECT_TRUE(HasBox(boxes, StaticBox::Kind::kPost, {1.44, 1.44, 0.0125}, {0.003, 0.003, 0.0125}));
  const std::vector<StaticBox> runs = MazeCollisionBoxes(maze);
  // the south edge as one run, posts included: 16 x 90 + 6 mm
  EXPECT_TRUE(HasBox(runs, StaticBox::Kind::kWall, {0.72, 0, 0.0125}, {0.723, 0.003, 0.0125}));
}

TEST(WorldBuildTest, AHalfSizeWorldStartsTheRobotInTheCentreOfIts90MillimetreStartCell) {
  const Maze maze(32, 32);
  auto world = World::Build(testing::BareRobot(), &maze, std::nullopt, {});
  EXPECT_NEAR(world->spawn().x_m, 0.045, 1e-12);
  EXPECT_NEAR(world->spawn().y_m, 0.045, 1e-12);
  EXPECT_EQ(world->maze_dimensions(), DimensionsOf(MazeClass::kHalfSize));
  ASSERT_NE(world->maze(), nullptr);
  EXPECT_EQ(world->maze()->width(), 32);
}

class WorldTest : public ::testing::Test {
 protected:
  void SetUp() override {
    robot_ = testing::BareRobot();
    maze_ = std::make_unique<Maze>(ParseMazeText(kSmallMaze, "small.txt"));
    kernel_ = Kernel::Create(robot_, maze_.get(), registry_, 1);
  }

  bool TouchesFloor(const char* body) const {
    const mjModel& m = kernel_->mj_model();
    const mjData& d = kernel_->state().data();
    const int b = mj_name2id(&m, mjOBJ_BODY, body);
    const int floor = mj_name2id(&m, mjOBJ_GEOM, "floor");
    for (int i = 0; i < d.ncon; ++i) {
      const mjContact& c = d.contact[i];
      const bool floor_pair = c.geom1 == floor || c.geom2 == floor;
      const int other = c.geom1 == floor ? c.geom2 : c.geom1;
      if (floor_pair && m.geom_bodyid[other] == b && c.dist < 1e-4) return true;
    }
    return false;
  }

  RobotSpec robot_;
  std::unique_ptr<Maze> maze_;
  PluginRegistry registry_;
  std::unique_ptr<Kernel> kernel_;
};

TEST_F(WorldTest, SceneryHoldsEveryWallAndPostWhilePhysicsHoldsOnlyProxies) {
  int scenery_geoms = 0;
  for (const auto& chunk : kernel_->world().scenery_chunks()) scenery_geoms += chunk.model->ngeom;
  EXPECT_EQ(scenery_geoms, 12 + 13);
  // floor, proxies and the robot's 6 geoms
  EXPECT_EQ(kernel_->mj_model().ngeom, 1 + kernel_->world().proxy_count() + 6);
}

TEST_F(WorldTest, PlacesTheRobotInTheStartCellFacingNorth) {
  const Pose2D pose = kernel_->world().RobotPose(kernel_->state().data());
  EXPECT_NEAR(pose.x_m, 0.09, 1e-12);
  EXPECT_NEAR(pose.y_m, 0.09, 1e-12);
  EXPECT_NEAR(pose.yaw_rad, std::numbers::pi / 2, 1e-12);
}

TEST_F(WorldTest, RobotSettlesOnBothWheelsAndTheCaster) {
  for (int i = 0; i < 500; ++i) kernel_->Step();
  EXPECT_TRUE(TouchesFloor("left_wheel"));
  EXPECT_TRUE(TouchesFloor("right_wheel"));
  EXPECT_TRUE(TouchesFloor("caster"));
  EXPECT_FALSE(TouchesFloor("chassis"));

  // at rest, where it was put: the axle at wheel-radius height, still facing north
  const mjData& d = kernel_->state().data();
  const Pose2D pose = kernel_->world().RobotPose(d);
  EXPECT_NEAR(pose.x_m, 0.09, 1e-3);
  EXPECT_NEAR(pose.y_m, 0.09, 1e-3);
  EXPECT_NEAR(pose.yaw_rad, std::numbers::pi / 2, 1e-3);
  const int chassis = kernel_->world().robot_body();
  EXPECT_NEAR(d.xpos[3 * chassis + 2], 0.016, 5e-4);
  EXPECT_LT(std::hypot(d.cvel[6 * chassis + 3], d.cvel[6 * chassis + 4]), 1e-3);
}

TEST_F(WorldTest, RaysSeeTheMazeWallsButNotTheRobot) {
  const mjData& d = kernel_->state().data();
  // from the start cell centre at sensor height: north is open for one cell, the north edge
  // wall's face is at y = 0.36 - 0.006
  const double origin[3] = {0.09, 0.09, 0.016};
  const double north[3] = {0, 1, 0};
  EXPECT_NEAR(kernel_->world().CastRay(d, origin, north, 2), 0.354 - 0.09, 1e-9);
  // east: no wall between cells 0 and 1, the wall at x = 0.36
  const double east[3] = {1, 0, 0};
  EXPECT_NEAR(kernel_->world().CastRay(d, origin, east, 2), 0.354 - 0.09, 1e-9);
  // west: the perimeter, through the robot's own plate
  const double west[3] = {-1, 0, 0};
  EXPECT_NEAR(kernel_->world().CastRay(d, origin, west, 2), 0.09 - 0.006, 1e-9);
  // beyond max range nothing is reported
  EXPECT_EQ(kernel_->world().CastRay(d, origin, north, 0.2), -1);
}

TEST_F(WorldTest, CollisionProxiesFollowTheRobot) {
  const mjModel& m = kernel_->mj_model();
  const int first = mj_name2id(&m, mjOBJ_GEOM, "proxy0");
  auto active = [&] {
    int n = 0;
    for (int i = 0; i < kernel_->world().proxy_count(); ++i)
      n += m.geom_pos[3 * (first + i) + 2] > 0;
    return n;
  };
  // in the start cell: the west and south runs are within reach, the open east and north not
  EXPECT_EQ(active(), 2);
  // in open space far from the maze: none
  kernel_->world().PlaceRobot(kernel_->state().data(), {3, 3, 0});
  kernel_->world().UpdateCollisionProxies(kernel_->state().data());
  EXPECT_EQ(active(), 0);
}

TEST_F(WorldTest, RobotCannotDriveThroughAWall) {
  // drive west into the perimeter wall from the start cell
  kernel_->world().PlaceRobot(kernel_->state().data(), {0.09, 0.09, std::numbers::pi});
  const int left = mj_name2id(&kernel_->mj_model(), mjOBJ_ACTUATOR, "left_motor");
  const int right = mj_name2id(&kernel_->mj_model(), mjOBJ_ACTUATOR, "right_motor");
  for (int i = 0; i < 2000; ++i) {
    kernel_->state().data().ctrl[left] = 0.002;
    kernel_->state().data().ctrl[right] = 0.002;
    kernel_->Step();
  }
  const Pose2D pose = kernel_->world().RobotPose(kernel_->state().data());
  // the plate's front (0.06 m ahead of the axle) stops at the wall face x = 0.006
  EXPECT_GT(pose.x_m, 0.006 + 0.06 - 2e-3);
}

TEST(SeveralRobotsWorldTest, RobotsSeeAndTouchEachOtherButNotThemselves) {
  // robot a in the start cell facing north, robot b in the cell east of it facing west: the
  // front of b's plate, 0.06 m ahead of its axle, is at x = 0.27 - 0.06 = 0.21
  const RobotSpec robot = testing::BareRobot();
  const Maze maze = ParseMazeText(kSmallMaze, "small.txt");
  PluginRegistry registry;
  const std::vector<KernelRobot> robots = {{robot, "a", std::nullopt},
                                           {robot, "b", Pose2D{0.27, 0.09, std::numbers::pi}}};
  auto kernel = Kernel::Create(robots, &maze, registry, KernelOptions{});
  const World& world = kernel->world();
  ASSERT_EQ(world.robot_count(), 2);
  // every name of a robot in the physics is its own: b's chassis is "b/chassis"
  EXPECT_EQ(world.robot_body(1), mj_name2id(&kernel->mj_model(), mjOBJ_BODY, "b/chassis"));
  const mjData& d = kernel->state().data();
  const double from_a[3] = {0.09, 0.09, 0.016};
  const double east[3] = {1, 0, 0};
  EXPECT_NEAR(world.CastRay(d, from_a, east, 2, 0), 0.21 - 0.09, 1e-9);
  // b's own sensor does not see b: the wall at x = 0.36 - 0.006
  const double from_b[3] = {0.27, 0.09, 0.016};
  EXPECT_NEAR(world.CastRay(d, from_b, east, 2, 1), 0.354 - 0.27, 1e-9);
  EXPECT_EQ(world.RobotTouchesRobot(d, 0), -1);

  // b put down with its plate over a's: they touch, each the other, and neither a wall
  world.PlaceRobot(kernel->state().data(), {0.16, 0.09, std::numbers::pi}, 1);
  kernel->Step();
  EXPECT_EQ(world.RobotTouchesRobot(d, 0), 1);
  EXPECT_EQ(world.RobotTouchesRobot(d, 1), 0);
  // pushed apart, as solid bodies are
  for (int i = 0; i < 200; ++i) kernel->Step();
  EXPECT_GT(world.RobotPose(d, 1).x_m - world.RobotPose(d, 0).x_m, 0.07);
}

// The world lists the geom pairs that can touch as MuJoCo's predefined pairs and skips its
// broadphase (world.cc, CollidableGeomPairs). A twin of the model that finds its pairs by the
// broadphase, as MuJoCo does unless told otherwise, must step to the same state to the bit while
// a robot pushes into a wall and another one into it.
TEST(SeveralRobotsWorldTest, PredefinedPairsStepExactlyAsMujocosBroadphase) {
  const RobotSpec robot = testing::BareRobot();
  const Maze maze = ParseMazeText(kSmallMaze, "small.txt");
  auto world = World::Build({WorldRobot{&robot, "a", Pose2D{0.09, 0.09, std::numbers::pi}},
                             WorldRobot{&robot, "b", Pose2D{0.27, 0.09, std::numbers::pi}}},
                            &maze);
  mjModel& m = world->mutable_model();
  ASSERT_EQ(m.opt.collision, mjCOL_PAIR);
  ASSERT_GT(m.npair, 0);
  std::unique_ptr<mjModel, World::ModelDeleter> twin(mj_copyModel(nullptr, &m));
  twin->opt.collision = mjCOL_DYNAMIC;
  std::unique_ptr<mjData, World::DataDeleter> d(mj_makeData(&m)), d2(mj_makeData(twin.get()));
  for (int r = 0; r < 2; ++r) world->PlaceRobot(*d, world->spawn(r), r);
  mj_forward(&m, d.get());
  mj_copyData(d2.get(), twin.get(), d.get());

  int wall_contacts = 0, robot_contacts = 0;
  for (int step = 0; step < 3000; ++step) {
    // a drives west into the maze's edge, b west into a, turning a little
    const double torque[4] = {0.002, 0.0021, 0.003, 0.0025};
    for (int i = 0; i < 4; ++i) d->ctrl[i] = d2->ctrl[i] = torque[i];
    world->UpdateCollisionProxies(*d);
    std::copy_n(m.geom_pos, 3 * m.ngeom, twin->geom_pos);
    std::copy_n(m.geom_size, 3 * m.ngeom, twin->geom_size);
    std::copy_n(m.geom_rbound, m.ngeom, twin->geom_rbound);
    mj_step1(&m, d.get());
    mj_step2(&m, d.get());
    mj_step1(twin.get(), d2.get());
    mj_step2(twin.get(), d2.get());
    ASSERT_EQ(d->ncon, d2->ncon) << "step " << step;
    ASSERT_EQ(std::memcmp(d->qpos, d2->qpos, sizeof(mjtNum) * m.nq), 0) << "step " << step;
    ASSERT_EQ(std::memcmp(d->qvel, d2->qvel, sizeof(mjtNum) * m.nv), 0) << "step " << step;
    wall_contacts += world->RobotTouchesScenery(*d, 0);
    robot_contacts += world->RobotTouchesRobot(*d, 1) == 0;
  }
  // both kinds of contact happened, for long
  EXPECT_GT(wall_contacts, 1000);
  EXPECT_GT(robot_contacts, 1000);
}

TEST(OpenWorldTest, FlatWorldHasNoSceneryAndPlacesTheRobotAtTheOrigin) {
  PluginRegistry registry;
  auto kernel = Kernel::Create(testing::BareRobot(), nullptr, registry, 1);
  EXPECT_TRUE(kernel->world().scenery().empty());
  EXPECT_EQ(kernel->world().proxy_count(), 0);
  const Pose2D pose = kernel->world().RobotPose(kernel->state().data());
  EXPECT_NEAR(pose.x_m, 0, 1e-12);
  EXPECT_NEAR(pose.yaw_rad, std::numbers::pi / 2, 1e-12);
}

TEST(OpenWorldTest, NamesWithQuotesAndMarkupReachThePhysicsAsWritten) {
  RobotSpec robot = testing::BareRobot();
  robot.name = "it's <b>&\"bold\"";
  robot.chassis.name = "a'b<c>&d";
  auto world = World::Build(robot, nullptr, std::nullopt, {});
  EXPECT_GT(mj_name2id(&world->model(), mjOBJ_BODY, "a'b<c>&d"), 0);
  // the text cannot close its attribute and add an element of its own
  EXPECT_EQ(world->mjcf().find("<b>"), std::string::npos);
}

TEST(OpenWorldTest, AMazeLargerThanARunBuildsIsRefusedBeforeBuilding) {
  const Maze maze(World::kMaxMazeSide_cells + 1, 4);
  try {
    World::Build(testing::BareRobot(), &maze, std::nullopt, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a 129 x 4 maze is larger than the 128 x 128 cells a run "
                                         "builds"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace unimouse
