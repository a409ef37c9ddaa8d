// SPDX-License-Identifier: GPL-3.0-or-later
#include "contact_watch.h"

#include <cmath>

#include "world.h"

namespace unimouse {

namespace {

// a name without the robot's prefix ("b/chassis" is robot b's chassis)
std::string Unprefixed(const char* name) {
  if (name == nullptr) return "";
  const std::string text = name;
  const size_t slash = text.find('/');
  return slash == std::string::npos ? text : text.substr(slash + 1);
}

// the robot's part in a contact: its geom's name, else its body's
std::string PartOf(const mjModel& m, const World& world, const mjContact& c, int robot) {
  const int geom = world.RobotOfBody(m.geom_bodyid[c.geom1]) == robot ? c.geom1 : c.geom2;
  std::string part = Unprefixed(mj_id2name(&m, mjOBJ_GEOM, geom));
  if (part.empty()) part = Unprefixed(mj_id2name(&m, mjOBJ_BODY, m.geom_bodyid[geom]));
  return part.empty() ? "robot" : part;
}

// the cell a point is in, and the side of it nearest to the point: a wall's face is half a
// wall's thickness inside the cell, a post's corner within a thickness of two sides at once
void PlaceOnMaze(const World& world, Contact& contact) {
  const Maze* maze = world.maze();
  if (maze == nullptr) return;
  const MazeDimensions dims = maze->dimensions();
  const Cell cell = CellAt(contact.x_m, contact.y_m, dims);
  if (!maze->Contains(cell)) return;
  contact.cell = cell;
  const double in_x = contact.x_m - cell.x * dims.cell_m;
  const double in_y = contact.y_m - cell.y * dims.cell_m;
  const double to_west = in_x, to_east = dims.cell_m - in_x;
  const double to_south = in_y, to_north = dims.cell_m - in_y;
  const double to_x = std::min(to_west, to_east), to_y = std::min(to_south, to_north);
  if (to_x < dims.wall_thickness_m && to_y < dims.wall_thickness_m) {
    contact.side = 'P';
  } else if (to_x < to_y) {
    contact.side = to_west < to_east ? 'W' : 'E';
  } else {
    contact.side = to_south < to_north ? 'S' : 'N';
  }
}

}  // namespace

bool ContactWatch::Begins(Touch& touch, bool touching, double time_s) {
  if (touching) {
    const bool begins = !touch.on;
    touch.on = true;
    touch.last_s = time_s;
    touch.count += begins;
    return begins;
  }
  // clear for long enough: the next touch is a new contact
  if (touch.on && time_s - touch.last_s >= kRelease_s) touch.on = false;
  return false;
}

void ContactWatch::Keep(Contact contact) {
  if (contacts_.size() < kMaxKept) {
    contacts_.push_back(std::move(contact));
  } else {
    ++not_kept_;
  }
}

void ContactWatch::Update(const World& world, const mjModel& m, const mjData& d) {
  for (int robot = 0; robot < static_cast<int>(robots_.size()); ++robot) {
    RobotTouches& r = robots_[static_cast<size_t>(robot)];
    int at = -1;
    const bool wall = world.RobotTouchesScenery(d, robot, &at);
    if (Begins(r.wall, wall, d.time)) {
      const mjContact& c = d.contact[at];
      Contact contact{d.time, robot, -1, c.pos[0], c.pos[1], {}, 0, PartOf(m, world, c, robot)};
      PlaceOnMaze(world, contact);
      Keep(std::move(contact));
    }
    const int other = world.robot_count() > 1 ? world.RobotTouchesRobot(d, robot, &at) : -1;
    if (Begins(r.robot, other >= 0, d.time)) {
      const mjContact& c = d.contact[at];
      Keep({d.time, robot, other, c.pos[0], c.pos[1], {}, 0, PartOf(m, world, c, robot)});
    }
    if (other >= 0) r.other = other;
    if (!r.robot.on) r.other = -1;
  }
}

}  // namespace unimouse
