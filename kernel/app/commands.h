// SPDX-License-Identifier: GPL-3.0-or-later
// The subcommands of the `unimouse` program.
#ifndef UNIMOUSE_APP_COMMANDS_H_
#define UNIMOUSE_APP_COMMANDS_H_

#include <cstdint>
#include <string>
#include <vector>

#include "session.h"

namespace unimouse {

class CommandLine;

/// What `unimouse run` takes: the run itself, which the command line binds straight into
/// SessionOptions, and the pictures asked for, as written (PicturesFor reads them).
struct RunOptions {
  SessionOptions session;
  // pictures (docs/pictures.md)
  std::string camera = "top";             ///< top, chase or free
  std::string snapshot_size = "640x480";  ///< WIDTHxHEIGHT
  std::string snapshot_every;             ///< "1s", "250ms"; "" for none
  std::vector<std::string> snapshot_at;   ///< sim times
  bool snapshot_end = false;              ///< final.png, or exit 2 when the machine cannot draw
  double frames_fps = 0;                  ///< PNG frames; 0 for none
  std::string video;                      ///< MP4 file in the output directory; "" for none
  double video_fps = 30;
  bool view = false;    ///< a live window instead of a headless run
  int view_frames = 0;  ///< close the window after so many frames; 0 never
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

/// Adds `unimouse run`, whose options are bound into RunOptions::session.
void AddRunCommand(CommandLine& cli);
/// Adds `unimouse check`.
void AddCheckCommand(CommandLine& cli);
/// Adds the commands that list what is installed: plugins, robot-schema, scenarios,
/// scenario-api.
void AddInformationCommands(CommandLine& cli);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_COMMANDS_H_
