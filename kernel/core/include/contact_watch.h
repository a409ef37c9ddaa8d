// SPDX-License-Identifier: GPL-3.0-or-later
// Watches each robot's contacts with the scenery and with other robots, step by step, and
// turns them into contacts a person would count: one begins at the first touch and ends only
// once the robot has stayed clear for kRelease_s. A robot pressed against a wall, whose touch
// flickers from step to step, is one contact (a lost mouse once counted 4,500).
#ifndef UNIMOUSE_CORE_CONTACT_WATCH_H_
#define UNIMOUSE_CORE_CONTACT_WATCH_H_

#include <mujoco/mujoco.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "maze.h"

namespace unimouse {

class World;

/// One contact, as it began.
struct Contact {
  double time_s = 0;
  int robot = 0;
  int other_robot = -1;  ///< -1: a wall, post or obstacle
  double x_m = 0;        ///< where, on the floor
  double y_m = 0;
  std::optional<Cell> cell;  ///< the maze cell the point is in; none off the maze
  char side = 0;     ///< of that cell: 'N', 'E', 'S', 'W', or 'P' a post; 0 no maze, a robot
  std::string part;  ///< the robot's geom (or body) that touched, without the robot's prefix
};

class ContactWatch {
 public:
  /// A touch that breaks for less than this is the same contact.
  static constexpr double kRelease_s = 0.1;
  /// Contacts kept with their details; later ones are counted only.
  static constexpr size_t kMaxKept = 1000;

  explicit ContactWatch(int robots) : robots_(static_cast<size_t>(robots)) {}

  /// Reads the contacts MuJoCo found for this step (after mj_step1 or mj_forward).
  void Update(const World& world, const mjModel& m, const mjData& d);

  bool touching_wall(int robot) const { return robots_[robot].wall.on; }
  /// The other robot it touches (the lowest-numbered), or -1.
  int touching_robot(int robot) const { return robots_[robot].other; }
  int64_t wall_contacts(int robot) const { return robots_[robot].wall.count; }
  int64_t robot_contacts(int robot) const { return robots_[robot].robot.count; }
  /// Every contact that began, in order, up to kMaxKept.
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// Contacts that began beyond kMaxKept.
  int64_t contacts_not_kept() const { return not_kept_; }

 private:
  struct Touch {
    bool on = false;
    double last_s = 0;  // the last step it touched
    int64_t count = 0;
  };
  struct RobotTouches {
    Touch wall, robot;
    int other = -1;
  };
  // true when a contact begins now
  static bool Begins(Touch& touch, bool touching, double time_s);
  void Keep(Contact contact);

  std::vector<RobotTouches> robots_;
  std::vector<Contact> contacts_;
  int64_t not_kept_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_CONTACT_WATCH_H_
