// SPDX-License-Identifier: GPL-3.0-or-later
// The mms protocol's physics tier: a motion controller that carries out each move on the
// simulated robot of a Session, as firmware would, through the robot's own signals. It writes
// the H-bridge commands (left.command, right.command, -1023..1023) and reads the encoders
// (left.encoder_counts, right.encoder_counts: counts each tick) and the time-of-flight sensors
// (tof.left_m, tof.front_m, tof.right_m) every tick.
//
//  - A move of N cells: both wheels forward, the pose estimated from the encoders and, between
//    side walls, from the 45-degree sensors (an observer learns the offset from the corridor's
//    middle and the heading from how the walls' readings change along the way); the robot is
//    steered back to the middle, along the corridor; the move ends at the last cell's centre
//    (the front sensor's readings of the wall beyond it correct the distance along), or 35 mm
//    before a wall the front sensor sees nearer than that.
//  - A quarter turn: the wheels opposite, closed on the estimated heading, braked as it nears,
//    until the robot rests within half a degree of it.
//  - Walls: while the robot crosses into its last cell, the 45-degree sensors see that cell's
//    side walls and the front sensor the wall beyond it (it is blind nearer than 3 cm, so at the
//    cell's centre it cannot see that wall any more).
// docs/mms.md gives the thresholds and the limits.
#ifndef UNIMOUSE_MMS_MMS_PHYSICAL_H_
#define UNIMOUSE_MMS_MMS_PHYSICAL_H_

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "mms_protocol.h"
#include "session.h"

namespace unimouse {

/// The robot's controller's distances and limits, for the classic maze's 180 mm cells.
struct MmsControl {
  double side_wall_m = 0.10;     ///< a 45-degree reading below this is a side wall
  double front_wall_m = 0.15;    ///< a front reading below this, crossing into a cell, is a wall
  double front_stop_m = 0.035;   ///< a move ends this near a wall ahead
  double cell_budget_s = 1.5;    ///< simulated time a move may take per cell, plus
  double move_budget_s = 2;      ///< this for any move or turn, before the robot counts as stuck
  double off_course_rad = 0.35;  ///< a heading farther than this from the mouse's is off course
};

class MmsRobot final : public MmsBody {
 public:
  /// Drives the robot of `session` (not owned), which runs in a maze with no other driver; the
  /// robot starts at rest in cell (0, 0) facing north, as the mms mouse does. Throws InputError
  /// when the maze starts elsewhere or the robot lacks one of the signals above.
  explicit MmsRobot(Session& session, const MmsControl& control = {});

  MmsMotion Drive(long cells) override;
  MmsMotion Turn(int quarter_turns) override;
  std::optional<bool> SensedWall(int side) override;
  void Reset() override;

  /// Returns the wall contacts so far: each time the robot began to touch a wall or post.
  long wall_contacts() const { return wall_contacts_; }
  /// Returns what result.json says of the robot: wall contacts, and how far from its cell's
  /// centre and heading it came to rest at worst.
  nlohmann::json Facts() const;

 private:
  // one tick with these commands; false when the session is over (out of time, fault, signal)
  bool Tick(double left, double right);
  // stops the wheels and waits for the robot to come to rest; false when the session is over
  bool Settle();
  // puts the estimate in the middle of the cell facing the heading, and checks the true pose
  MmsMotion Arrived(double start_s);
  // a move cut short by the session's end
  MmsMotion Ended(double start_s);
  double now_s();

  Session& session_;
  MmsControl control_;
  double cell_m_ = 0.18;
  double scale_ = 1;  // the cell over the classic 180 mm
  int left_command_ = -1, right_command_ = -1, left_counts_ = -1, right_counts_ = -1;
  int tof_left_ = -1, tof_front_ = -1, tof_right_ = -1;
  double metres_per_count_ = 0;
  double track_m_ = 0.096;
  // where the controller believes it is: the cell, the heading in quarter turns from east, and
  // the pose estimated from the encoders
  int x_ = 0, y_ = 0, heading_ = 1;
  double est_x_m_ = 0, est_y_m_ = 0, est_yaw_rad_ = 0;
  // the walls its sensors saw of its cell, by heading (east, north, west, south)
  std::array<std::optional<bool>, 4> seen_;
  bool move_contact_ = false;
  long wall_contacts_ = 0;
  double worst_offset_m_ = 0;
  double worst_yaw_error_rad_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_MMS_MMS_PHYSICAL_H_
