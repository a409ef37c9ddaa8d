// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse fit` and `unimouse compare` (docs/calibrate.md): the CLI face of kernel/fit.
#ifndef UNIMOUSE_APP_FIT_COMMANDS_H_
#define UNIMOUSE_APP_FIT_COMMANDS_H_

#include <string>
#include <vector>

namespace unimouse {

struct FitOptions {
  std::string robot;              ///< robot file, or the name of a bundled robot
  std::vector<std::string> logs;  ///< the sysid CSV logs
  std::string out_dir = "fit";    ///< where the fitted robot file and the plots go
  std::string plugin_path;
};

class CommandLine;

/// Adds `unimouse fit` and `unimouse compare`.
void AddFitCommands(CommandLine& cli);

/// Fits the robot file's motor constants to the logs, prints the report and writes
/// out_dir/<robot>-fitted.yaml and, per log and channel, out_dir/<log>-<channel>-fit.png; exit 2
/// and nothing written for a bad robot file or log.
int FitCommand(const FitOptions& options);
/// Replays each log on the robot file, prints each channel's RMSE and largest error and writes
/// out_dir/<log>-<channel>-compare.png.
int CompareCommand(const FitOptions& options);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_FIT_COMMANDS_H_
