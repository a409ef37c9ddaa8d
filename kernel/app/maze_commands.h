// SPDX-License-Identifier: GPL-3.0-or-later
// The `unimouse maze` subcommands.
#ifndef UNIMOUSE_APP_MAZE_COMMANDS_H_
#define UNIMOUSE_APP_MAZE_COMMANDS_H_

#include <cstdint>
#include <string>
#include <vector>

namespace unimouse {

class CommandLine;

struct MazeOptions {
  std::vector<std::string> files;  ///< files, bundled maze names or directories
  bool json = false;
  std::string csv;      ///< summary file for many mazes; "" for none
  bool strict = false;  ///< check: warnings are errors
  std::string tie_rule = "compass:WENS";
  double cell_time_s = 0.5;
  double turn_time_s = 0.5;
  std::string size = "16x16";
  uint64_t seed = 1;
  double loops = 0;
  std::string out;
  std::string plot_dir;           ///< explore: pictures of every trip go here
  std::string path = "modified";  ///< plot: which path to draw
  bool costs = false;             ///< plot: cell distances to the goal
};

int MazeShow(const MazeOptions& options);
int MazeCheck(const MazeOptions& options);
int MazeSolve(const MazeOptions& options);
int MazeExplore(const MazeOptions& options);
int MazePlot(const MazeOptions& options);
int MazeConvert(const MazeOptions& options);
int MazeGenerate(const MazeOptions& options);

/// Adds `unimouse maze show|check|solve|explore|plot|convert|generate`.
void AddMazeCommands(CommandLine& cli);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_MAZE_COMMANDS_H_
