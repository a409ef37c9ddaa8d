// SPDX-License-Identifier: GPL-3.0-or-later
// The world a robot lives in: a floor, the robot, and static scenery (maze walls and posts).
//
// MuJoCo 2.2.2 spends about 50 ns per geom per step on kinematics, whether or not the geom can
// collide, so a 16x16 maze of ~560 wall and post geoms cuts the step rate four- to five-fold. The
// physics model therefore holds only the floor, the robot and a small pool of collision proxies:
// before each step the proxies take the place of the static shapes nearest the robot. Every wall
// and post lives in separate scenery models that ray casts (and rendering) see in full. Both the
// proxies and the rays find the shapes near them through an index of floor squares, so that a
// step costs the same in any maze.
#ifndef UNIMOUSE_CORE_WORLD_H_
#define UNIMOUSE_CORE_WORLD_H_

#include <mujoco/mujoco.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "floor_grid.h"
#include "maze.h"
#include "robot_spec.h"

namespace unimouse {

/// An immovable box of the scenery.
struct StaticBox {
  enum class Kind { kWall, kPost, kObstacle };
  Kind kind = Kind::kObstacle;
  Vec3 center_m{};
  Vec3 half_m{};  ///< half extents along the box's own axes
  double yaw_rad = 0;
};

/// A pose on the floor: position and heading (0 east, counter-clockwise positive).
struct Pose2D {
  double x_m = 0;
  double y_m = 0;
  double yaw_rad = 0;
};

/// Returns the walls and posts of a maze at its dimensions, one box each, in a fixed order: posts
/// row by row from the south-west, then east-west walls, then north-south walls.
std::vector<StaticBox> MazeBoxes(const Maze& maze);

/// Returns boxes covering the same space with fewer, larger pieces: each straight run of walls
/// becomes one box including its posts, and only posts touching no wall stay on their own.
std::vector<StaticBox> MazeCollisionBoxes(const Maze& maze);

/// Returns the world position of a cell's centre.
Pose2D CellCentre(Cell c, Heading h, const MazeDimensions& dims = {});

/// Returns the cell a point on the floor is in (outside the maze too: negative, or beyond it).
Cell CellAt(double x_m, double y_m, const MazeDimensions& dims);

/// One robot of a world: its file, the prefix of every name it brings into the physics model
/// ("" for the only robot of a run, "name/" when there are several), and where it starts.
struct WorldRobot {
  const RobotSpec* spec = nullptr;
  std::string prefix;
  std::optional<Pose2D> spawn;  ///< default: the maze's start, or the origin facing north
};

class World {
 public:
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  ~World();

  /// Most cells on a side of a maze a run builds a world from: its walls and posts are shapes
  /// MuJoCo compiles, 500 to a model, and a 128 x 128 maze takes about 1.2 s.
  static constexpr int kMaxMazeSide_cells = 128;

  /// Builds a robot in a maze (or on an open floor when maze is null), facing the maze's start
  /// heading in its start cell, or `spawn` when given; `boxes` are more walls and obstacles, as a
  /// scenario adds. Throws InputError, also for a maze beyond kMaxMazeSide_cells a side.
  static std::unique_ptr<World> Build(const RobotSpec& robot, const Maze* maze,
                                      std::optional<Pose2D> spawn = std::nullopt,
                                      const std::vector<StaticBox>& boxes = {});
  /// Builds several robots in one maze; they collide with each other and see each other.
  static std::unique_ptr<World> Build(const std::vector<WorldRobot>& robots, const Maze* maze,
                                      const std::vector<StaticBox>& boxes = {});

  const mjModel& model() const { return *model_; }
  /// Writable only for the collision proxies and kernel-owned bookkeeping.
  mjModel& mutable_model() { return *model_; }
  const std::string& mjcf() const { return mjcf_; }

  /// Walls, posts and obstacles as drawn and as seen by rays.
  const std::vector<StaticBox>& scenery() const { return scenery_; }

  struct ModelDeleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  struct DataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  /// The scenery as MuJoCo models of a few hundred boxes each (with their data, placed), in the
  /// order of scenery(): what pictures draw.
  struct SceneryChunk {
    std::unique_ptr<mjModel, ModelDeleter> model;
    std::unique_ptr<mjData, DataDeleter> data;
  };
  const std::vector<SceneryChunk>& scenery_chunks() const { return scenery_chunks_; }

  int robot_count() const { return static_cast<int>(robots_.size()); }
  /// Where robot `robot` starts.
  Pose2D spawn(int robot = 0) const { return robots_[robot].spawn; }
  /// The maze the world was built from, or null on an open floor.
  const Maze* maze() const { return maze_ ? &*maze_ : nullptr; }
  /// The maze's dimensions; classic ones on an open floor.
  MazeDimensions maze_dimensions() const { return maze_ ? maze_->dimensions() : MazeDimensions{}; }
  int robot_body(int robot = 0) const { return robots_[robot].body; }
  double robot_radius_m(int robot = 0) const { return robots_[robot].radius_m; }
  /// The robot whose body tree holds MuJoCo body `body`, or -1 (the world, a proxy).
  int RobotOfBody(int body) const;
  int proxy_count() const { return proxy_count_; }
  /// Ticks on which more static shapes were near the robot than there are proxies.
  long proxy_overflows() const { return proxy_overflows_; }

  /// Puts a robot at rest on the floor at `pose`.
  void PlaceRobot(mjData& d, const Pose2D& pose, int robot = 0) const;
  /// Returns a robot's pose on the floor.
  Pose2D RobotPose(const mjData& d, int robot = 0) const;

  /// Returns whether any part of a robot touches a wall, post or obstacle; `contact`, if given,
  /// gets the index in d.contact of the first such touch (-1 none).
  bool RobotTouchesScenery(const mjData& d, int robot = 0, int* contact = nullptr) const;
  /// Returns the lowest-numbered other robot that a robot touches, or -1; `contact` as above.
  int RobotTouchesRobot(const mjData& d, int robot, int* contact = nullptr) const;

  /// Moves the collision proxies onto the static shapes near each robot. A function of the
  /// robots' positions alone, called before every step, so it keeps runs deterministic.
  void UpdateCollisionProxies(const mjData& d);

  /// Returns the distance along unit `direction` to the first surface that is not part of robot
  /// `from` (other robots are surfaces; -1: no robot's own sensor), or -1 when there is none
  /// within max_m (or an argument is not finite).
  double CastRay(const mjData& d, const double origin[3], const double direction[3], double max_m,
                 int from = -1) const;

 private:
  World() = default;
  void UpdateProxiesOf(const mjData& d, int robot);

  std::string mjcf_;
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::vector<StaticBox> scenery_;
  std::vector<StaticBox> collision_shapes_;
  std::vector<std::array<double, 2>> shape_cos_sin_;  // of each collision shape's yaw
  std::vector<SceneryChunk> scenery_chunks_;
  // each scenery box as a ray cast tests it: placed by MuJoCo, in the order of scenery_
  struct RayBox {
    double pos[3], mat[9], size[3];
  };
  std::vector<RayBox> ray_boxes_;
  std::optional<Maze> maze_;
  // each robot's place in the physics model; its collision proxies are slots
  // [robot * kProxiesPerRobot, (robot + 1) * kProxiesPerRobot)
  struct RobotSlot {
    Pose2D spawn;
    int body = -1;
    int qpos = -1;
    int qvel = -1;
    double rest_height_m = 0;
    double radius_m = 0;
    std::vector<int> geoms;  // that other robots' rays can hit
  };
  std::vector<RobotSlot> robots_;
  int first_proxy_ = -1;
  int proxy_count_ = 0;
  std::vector<int> proxy_shape_;         // shape index per proxy slot, -1 when parked
  FloorGrid collision_grid_;             // where the collision shapes are
  FloorGrid scenery_grid_;               // where the scenery's boxes are
  std::vector<int> near_;                // scratch for UpdateCollisionProxies
  std::vector<int> candidates_;          // scratch for UpdateCollisionProxies
  mutable std::vector<int> ray_shapes_;  // scratch for CastRay
  long proxy_overflows_ = 0;
};

/// Compiles MJCF text through an in-memory file; throws InputError with MuJoCo's reason.
mjModel* CompileMjcf(const std::string& mjcf, const std::string& what);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_WORLD_H_
