// SPDX-License-Identifier: GPL-3.0-or-later
// What the viewer's keys do, apart from any window, so that it can be tested without one.
#ifndef UNIMOUSE_APP_VIEWER_CONTROLS_H_
#define UNIMOUSE_APP_VIEWER_CONTROLS_H_

#include <string>

namespace unimouse {

/// The keys both viewers share (the live run's and the replay's): what is shown and how.
struct DisplayKeys {
  bool follow = false;  ///< the camera's centre stays on the robot
  bool beams = true;
  bool beliefs = true;
  bool hud = true;
  bool help = false;
  std::string preset;  ///< a named camera just chosen, "" when none
  bool screenshot = false;
  bool quit = false;

  /// Applies F, 1 2 3, R, B, U, H (F1), S, Q (Esc); returns false for another key.
  bool Key(int key);
};

/// Frames a second of `frames` drawn from the first to the last, `span_s` apart; 0 with fewer
/// than two frames or no time between them.
double FrameRate(int frames, double span_s);

struct ViewerControls : DisplayKeys {
  bool paused = false;
  int steps_wanted = 0;  ///< physics steps to take while paused
  double speed = 1;      ///< sim seconds per wall second
  int followed = 0;      ///< which robot it follows, counted on through the run's robots
  bool restart = false;

  static constexpr double kMinSpeed = 1.0 / 16;
  static constexpr double kMaxSpeed = 64;

  /// Applies a key press (a GLFW key code); returns false for a key that means nothing.
  bool Key(int key);
  /// One line per key.
  static const char* HelpKeys();
  static const char* HelpActions();
};

}  // namespace unimouse

#endif  // UNIMOUSE_APP_VIEWER_CONTROLS_H_
