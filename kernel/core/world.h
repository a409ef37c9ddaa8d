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

  Pose2D spawn() const { return spawn_; }
  /// The maze the world was built from, or null on an open floor.
  const Maze* maze() const { return maze_ ? &*maze_ : nullptr; }
  /// The maze's dimensions; classic ones on an open floor.
  MazeDimensions maze_dimensions() const { return maze_ ? maze_->dimensions() : MazeDimensions{}; }
  int robot_body() const { return robot_body_; }
  double robot_radius_m() const { return robot_radius_m_; }
  int proxy_count() const { return proxy_count_; }
  /// Ticks on which more static shapes were near the robot than there are proxies.
  long proxy_overflows() const { return proxy_overflows_; }

  /// Puts the robot at rest on the floor at `pose`.
  void PlaceRobot(mjData& d, const Pose2D& pose) const;
  /// Returns the robot's pose on the floor.
  Pose2D RobotPose(const mjData& d) const;

  /// Returns whether any part of the robot touches a wall, post or obstacle.
  bool RobotTouchesScenery(const mjData& d) const;

  /// Moves the collision proxies onto the static shapes near the robot. A function of the robot's
  /// position alone, called before every step, so it keeps runs deterministic.
  void UpdateCollisionProxies(const mjData& d);

  /// Returns the distance along unit `direction` to the first surface that is not part of a
  /// robot, or -1 when there is none within max_m (or an argument is not finite).
  double CastRay(const mjData& d, const double origin[3], const double direction[3],
                 double max_m) const;

 private:
  World() = default;

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
  Pose2D spawn_;
  std::optional<Maze> maze_;
  int robot_body_ = -1;
  int robot_qpos_ = -1;
  int robot_qvel_ = -1;
  double robot_rest_height_m_ = 0;
  double robot_radius_m_ = 0;
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
