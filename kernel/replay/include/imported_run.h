// SPDX-License-Identifier: GPL-3.0-or-later
// A real robot's logged run beside a recording (`unimouse replay ... --import FILE.csv`,
// docs/replay.md): a CSV with a header, either
//   time_s,x_m,y_m,yaw_rad              the robot's pose as the lab measured it, or
//   time_s,left_counts,right_counts     its encoders' totals, integrated here with the robot
//                                       file's wheel radius, track and counts per turn from a
//                                       start pose (the recording's first)
// Lines starting with '#' are comments. Other columns are ignored.
#ifndef UNIMOUSE_REPLAY_IMPORTED_RUN_H_
#define UNIMOUSE_REPLAY_IMPORTED_RUN_H_

#include <string>

#include "recording.h"
#include "robot_spec.h"

namespace unimouse {

/// Reads a logged run. `robot` gives the geometry an encoder log needs (null: such a log is
/// refused) and `start` where it begins. Throws InputError "file:line: reason" for a missing
/// column, a value that is not a finite number, time going backwards, or fewer than two rows.
RecordedRobot ReadImportedRun(const std::string& path, const RobotSpec* robot, Pose2D start);

}  // namespace unimouse

#endif  // UNIMOUSE_REPLAY_IMPORTED_RUN_H_
