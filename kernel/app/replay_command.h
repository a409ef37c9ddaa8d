// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse replay` (docs/replay.md): a run's recording played again in a window or written as
// one offline page, beside another run's or a real robot's log.
#ifndef UNIMOUSE_APP_REPLAY_COMMAND_H_
#define UNIMOUSE_APP_REPLAY_COMMAND_H_

#include <string>
#include <vector>

namespace unimouse {

class CommandLine;

struct ReplayOptions {
  std::vector<std::string> recordings;  ///< one or two: a run.mcap or an output folder
  std::string import_csv;               ///< a real robot's logged run, drawn as a ghost
  std::string html;                     ///< write the offline page here instead of a window
  std::vector<std::string> signals;     ///< the signals the page plots
  double at_s = 0;                      ///< where the cursor starts
  double speed = 1;
  bool paused = false;
  int view_frames = 0;
  std::string out_dir;  ///< screenshots; default: the first recording's folder
  std::string plugin_path;
};

/// Adds `unimouse replay`.
void AddReplayCommand(CommandLine& cli);

/// Reads the recordings (and the logged run), prints what they hold and where two runs first
/// diverge, then writes the page or opens the window. Exit 0, or 2 for a bad recording, log or
/// option (one sentence, nothing written).
int ReplayCommand(const ReplayOptions& options);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_REPLAY_COMMAND_H_
