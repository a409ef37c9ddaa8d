// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse run --view`: the run in a live 3D window (GLFW), for labs. The window steps the run
// itself, paced to `speed` times the wall clock, and draws it as the pictures do: the robot, the
// ToF beams, what the firmware believes about the maze and the scenario's HUD. The keys are in
// viewer_controls.h; H shows them in the window.
#ifndef UNIMOUSE_APP_VIEWER_H_
#define UNIMOUSE_APP_VIEWER_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "session.h"
#include "viewer_controls.h"

struct GLFWwindow;

namespace unimouse {

class SceneRenderer;

class Viewer {
 public:
  /// Opens the window; throws InputError (exit code 2) when there is no display. GLFW, once
  /// initialised, stays so until the process ends; the window closes with the Viewer.
  /// `max_frames` > 0 closes it after that many frames (for scripts and tests).
  Viewer(const std::string& title, std::string out_dir, int max_frames);
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;
  ~Viewer();

  /// Shows a run, stepping it at the chosen speed, until the window is closed, Q is pressed or
  /// the run is to start again (see restart_requested()).
  void Show(Session& session);

  bool restart_requested() const { return controls_.restart; }
  /// Frames drawn since the window opened.
  int frames() const { return frames_; }

 private:
  void OnMouseMove(double x, double y);
  void Draw(Session& session);
  void SaveScreenshot(const std::string& file);

  GLFWwindow* window_ = nullptr;
  std::string out_dir_;
  int max_frames_ = 0;
  int frames_ = 0;
  int screenshots_ = 0;
  ViewerControls controls_;
  std::unique_ptr<SceneRenderer> renderer_;
  mjvCamera camera_{};
  // the mouse
  bool left_down_ = false, right_down_ = false;
  double last_x_ = 0, last_y_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_APP_VIEWER_H_
