// SPDX-License-Identifier: GPL-3.0-or-later
// What the replay window's keys and timeline do to its cursor, apart from any window, so that
// it can be tested without one; the keys for what is shown are the run viewer's (DisplayKeys).
#ifndef UNIMOUSE_APP_REPLAY_CONTROLS_H_
#define UNIMOUSE_APP_REPLAY_CONTROLS_H_

#include <vector>

#include "viewer_controls.h"

namespace unimouse {

/// The speeds a replay plays at, in sim seconds per wall second.
inline constexpr double kReplaySpeeds[] = {0.1, 0.25, 0.5, 1, 2, 4, 8, 16};

/// What a replay's cursor moves over: the recording's length, the times of its samples (the
/// first robot's poses) and of its events, each in time order.
struct ReplayTimeline {
  double end_s = 0;
  std::vector<double> samples;
  std::vector<double> marks;
};

struct ReplayControls : DisplayKeys {
  double cursor_s = 0;
  double speed = 1;  ///< one of kReplaySpeeds
  bool paused = false;

  /// Applies a key press (a GLFW key code); returns false for a key that means nothing.
  bool Key(int key, const ReplayTimeline& timeline);
  /// Moves the cursor on by `wall_s` of wall time at the speed, unless paused; at the end it
  /// stops there, paused, as a player does.
  void Play(double wall_s, const ReplayTimeline& timeline);
  /// Puts the cursor at a point of the timeline's bar: 0 its start, 1 its end.
  void Scrub(double fraction, const ReplayTimeline& timeline);

  /// One line per key.
  static const char* HelpKeys();
  static const char* HelpActions();
};

}  // namespace unimouse

#endif  // UNIMOUSE_APP_REPLAY_CONTROLS_H_
