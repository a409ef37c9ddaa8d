// SPDX-License-Identifier: GPL-3.0-or-later
// The subcommands of the `unimouse` program.
#ifndef UNIMOUSE_APP_COMMANDS_H_
#define UNIMOUSE_APP_COMMANDS_H_

#include <cstdint>
#include <string>
#include <vector>

#include "session.h"

namespace unimouse {

struct RunOptions {
  std::string robot = "unimouse";
  std::string maze = "japan2018";  ///< "none" for an open floor
  double duration_s = 10;
  uint64_t seed = 1;
  std::string out_dir = "out";
  std::string plugin_path;
  std::string link;  ///< firmware link transport spec (transport_spec.h), "" for none
  std::vector<std::string> link_sets;  ///< link parameters, "name=value"
  std::string firmware_profile;        ///< "unimousesim-0.1" for the original's firmware
  bool realtime = false;               ///< pace to the wall clock; always on with a link
  std::string scenario;                ///< scenario file or bundled name; "" for none
  std::vector<std::string> sets;       ///< scenario parameters, "name=value"
  std::string controller;              ///< Lua controller file for the scenario; "" for none
  double trace_period_s = -1;  ///< seconds between trace rows; 0 no trace; -1 the robot file's
  std::string trace_signals;   ///< signals the trace records; "" the robot file's
  bool duration_given = false;
  bool maze_given = false;
  // pictures (docs/pictures.md)
  std::string camera = "top";             ///< top, chase or free
  std::string snapshot_size = "640x480";  ///< WIDTHxHEIGHT
  std::string snapshot_every;             ///< "1s", "250ms"; "" for none
  std::vector<std::string> snapshot_at;   ///< sim times
  std::vector<std::string> snapshot_on;   ///< scenario events
  bool snapshot_end = false;              ///< final.png, or exit 2 when the machine cannot draw
  bool no_pictures = false;               ///< not even the final.png taken when possible
  double frames_fps = 0;                  ///< PNG frames; 0 for none
  std::string video;                      ///< MP4 file in the output directory; "" for none
  double video_fps = 30;
  bool view = false;    ///< a live window instead of a headless run
  int view_frames = 0;  ///< close the window after so many frames; 0 never
  std::string start;    ///< the robot's start cell and heading, "X,Y,H"; "" the scenario's
  /// Two or more robots, each with its own link, controller and start (`--robot A --link ...
  /// --robot B ...`), in place of robot, link, link_sets, firmware_profile, controller, start.
  std::vector<SessionRobot> robots;
  /// Why the options could not be read (a --link before the first of several --robot): the
  /// run writes it as its result and exits with code 2.
  std::string bad_options;
};

/// Runs a simulation headless and writes out_dir/result.json; returns the exit code.
int RunCommand(const RunOptions& options);
/// What `unimouse check` is given.
struct CheckOptions {
  /// robot files or bundled names, scenario files (.lua) or bundled names, directories (every
  /// .yaml, .yml and .lua file inside, at any depth)
  std::vector<std::string> targets;
  std::vector<std::string> sets;  ///< scenario parameters, "name=value"
  std::string plugin_path;
};

/// Validates robot files (their components created and bound) and scenarios (loaded, and their
/// world built around the bundled robot) without running a step, starting no program and writing
/// nothing; reports each and returns the worst exit code: 0 all good, 2 any problem.
int CheckCommand(const CheckOptions& options);
/// Lists every component type found and its parameters; returns the exit code.
int PluginsCommand(const std::string& plugin_path);
/// Lists every key of a robot file and every component type's parameters, as text or as the
/// Markdown of docs/robots.md; returns the exit code.
int RobotSchemaCommand(bool markdown, const std::string& plugin_path);
/// Lists the bundled scenarios and their parameters, as text or as the Markdown table of
/// docs/scenarios.md; returns the exit code.
int ScenariosCommand(bool markdown);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_COMMANDS_H_
