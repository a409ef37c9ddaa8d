// SPDX-License-Identifier: GPL-3.0-or-later
// Small robots and mazes shared by tests, inline so that each test reads whole.
#ifndef UNIMOUSE_TESTS_INLINE_ASSETS_H_
#define UNIMOUSE_TESTS_INLINE_ASSETS_H_

#include <string>

#include "robot_spec.h"

namespace unimouse::testing {

/// The bundled robot file, read from the source tree.
std::string BundledRobotPath();
/// The collection of contest mazes beside the project, or "" when absent.
std::string SharedMazesDir();

/// The bundled robot file's text.
std::string ReadBundledRobot();

/// The bundled robot with two more ToF sensors at the middle of the plate's sides, looking
/// straight left and right (sites tof_left_side and tof_right_side, signals tof.left_side_m and
/// tof.right_side_m): five in all. Its components list ends the text, so more can be appended.
std::string FiveTofRobot();

/// A one-body robot (a 0.1 kg sphere named `body`, no joints) whose components list is the given
/// YAML list items; its first component is on line 6.
std::string TinyRobotWith(const std::string& components);

/// The bundled robot without its components: the bare mechanics.
RobotSpec BareRobot();

/// The bundled robot's YAML with its components list replaced by `components` (YAML list items,
/// each starting with "- "), and the line number the first of them lands on.
struct RobotYaml {
  std::string text;
  int first_component_line = 0;
};
RobotYaml BundledRobotWith(const std::string& components);

/// The gyro robot (robots/unimouse-gyro.yaml: an IMU site `imu`, inputs left.command,
/// right.command and fan.command) with its components replaced by an ideal 6 V supply, the two
/// H-bridges and motors, and then `more` (YAML list items); the last line of `more` is the
/// text's last line.
std::string GyroRobotWith(const std::string& more);

/// A 3 x 2 maze drawn so that posts and walls can be counted by hand:
///
///   o---o---o---o      north edge: 3 walls
///   |       |   |      row 1: walls at x = 0, 2, 3
///   o   o---o   o      one wall on line y = 1, over column 1
///   | S     |   |      row 0: walls at x = 0, 2, 3
///   o---o---o---o      south edge: 3 walls
inline constexpr const char* kSmallMaze =
    "o---o---o---o\n"
    "|       |   |\n"
    "o   o---o   o\n"
    "| S     |   |\n"
    "o---o---o---o\n";

/// 5 x 5, no inner walls but one east of the start (0, 0); the goal is the centre cell (2, 2).
inline constexpr const char* kOpenMaze5x5 =
    "o---o---o---o---o---o\n"
    "|                   |\n"
    "o   o   o   o   o   o\n"
    "|                   |\n"
    "o   o   o   o   o   o\n"
    "|                   |\n"
    "o   o   o   o   o   o\n"
    "|                   |\n"
    "o   o   o   o   o   o\n"
    "| S |               |\n"
    "o---o---o---o---o---o\n";

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_INLINE_ASSETS_H_
