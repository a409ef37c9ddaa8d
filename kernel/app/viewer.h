// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse run --view`: the run in a live 3D window (GLFW), for labs. The window steps the run
// itself, paced to `speed` times the wall clock, and draws it as the pictures do: the robot, the
// ToF beams, what the firmware believes about the maze and the scenario's HUD. The keys are in
// viewer_controls.h; H shows them in the window.
#ifndef UNIMOUSE_APP_VIEWER_H_
#define UNIMOUSE_APP_VIEWER_H_

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "session.h"
#include "viewer_controls.h"

struct GLFWwindow;

namespace unimouse {

class SceneRenderer;

/// Opens a 1200 x 900 window with its OpenGL context current, for the viewers (4x multisampling,
/// none on a software renderer); throws
/// InputError naming `option` (exit code 2) when there is no display. GLFW, once initialised,
/// stays so until the process ends.
GLFWwindow* OpenViewerWindow(const std::string& title, const std::string& option);
/// Whether the viewers' display went away (its X server quit): then no window can be drawn in,
/// nor let go of.
bool ViewerDisplayLost();

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

  /// For a run its caller steps (`unimouse mms --physical --view`): called after every step, it
  /// draws a frame when one is due and holds the run to the chosen speed or while paused. A
  /// closed window or Q stops the run (Session::Stop).
  void Watch(Session& session);
  /// Shows the ended run, saying how it ended, until the window is closed or Q is pressed.
  void Linger(Session& session, const std::string& ending);

  bool restart_requested() const { return controls_.restart; }
  /// Frames drawn of the run shown last (Show).
  int frames() const { return run_frames_; }
  /// Frames drawn a second of that run, from its first frame to its last.
  double FramesPerSecond() const;

 private:
  void OnMouseMove(double x, double y);
  void Draw(Session& session, const std::string& state);
  // draws one frame, saves a screenshot if asked, and takes the window's events; false when the
  // window is to close
  bool Frame(Session& session, const std::string& state);
  // the renderer for this run's model, made when its first frame is drawn
  void Begin(Session& session);
  // the run's state line for the corner: over, paused or running
  std::string State(Session& session) const;
  void SaveScreenshot(const std::string& file);

  GLFWwindow* window_ = nullptr;
  std::string out_dir_;
  int max_frames_ = 0;
  int frames_ = 0;      // since the window opened
  int run_frames_ = 0;  // of the run shown last
  int screenshots_ = 0;
  ViewerControls controls_;
  std::unique_ptr<SceneRenderer> renderer_;
  mjvCamera camera_{};
  // Watch: when the last frame was drawn, and the wall and sim time the pace counts from
  std::chrono::steady_clock::time_point last_frame_, pace_wall_;
  std::chrono::steady_clock::time_point first_drawn_, last_drawn_;  // for the frame rate
  double pace_sim_s_ = 0;
  double pace_speed_ = 0;
  // the mouse
  bool left_down_ = false, right_down_ = false;
  double last_x_ = 0, last_y_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_APP_VIEWER_H_
