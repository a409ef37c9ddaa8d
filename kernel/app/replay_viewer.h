// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse replay`'s window (docs/replay.md): a recording played back on the simulator's model
// of its robots, with the run viewer's cameras and drawing, a timeline to drag along the bottom
// and keys to play, pause, step a sample, change speed and jump between events. H lists the keys.
#ifndef UNIMOUSE_APP_REPLAY_VIEWER_H_
#define UNIMOUSE_APP_REPLAY_VIEWER_H_

#include <string>
#include <vector>

#include "replay_controls.h"
#include "replay_scene.h"

namespace unimouse {

struct ReplayViewOptions {
  std::string title;
  double start_s = 0;   ///< where the cursor starts
  bool paused = false;  ///< start paused
  double speed = 1;     ///< one of kReplaySpeeds
  int max_frames = 0;   ///< > 0: close after that many frames, saving the last as replay.png
  std::string out_dir;  ///< where screenshots go
  std::vector<std::string> signals;  ///< recorded signals the HUD shows at the cursor
};

/// Shows the scene until the window is closed or Q is pressed; throws InputError (exit code 2)
/// when there is no display.
void ShowReplay(ReplayScene& scene, const ReplayViewOptions& options);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_REPLAY_VIEWER_H_
