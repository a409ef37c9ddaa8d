// SPDX-License-Identifier: GPL-3.0-or-later
#include "viewer.h"

#include <GLFW/glfw3.h>
#include <X11/Xlib.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "png_file.h"
#include "scene_renderer.h"
#include "unimouse/errors.h"

// GLFW's X11 display, declared as glfw3native.h does (which would need Xrandr's headers too)
extern "C" Display* glfwGetX11Display(void);

namespace unimouse {

namespace {

Viewer* Of(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

std::string last_glfw_error;
void KeepGlfwError(int, const char* text) { last_glfw_error = text; }

// Xlib ends the process when the display goes away (its X server quits): instead the display
// is only marked dead, every Xlib call on it returns at once, and the viewer ends the run with
// its result
bool display_lost = false;
int DisplayLost(Display*) {
  display_lost = true;
  return 0;
}
void DisplayLostExit(Display*, void*) { display_lost = true; }
constexpr const char* kDisplayLost = "the viewer's display went away (its X server quit)";

}  // namespace

GLFWwindow* OpenViewerWindow(const std::string& title, const std::string& option) {
  glfwSetErrorCallback(KeepGlfwError);
  if (!glfwInit()) {
    throw InputError(
        option + " needs a display: " +
        (last_glfw_error.empty() ? std::string("GLFW cannot start") : last_glfw_error));
  }
  if (Display* display = glfwGetX11Display()) {
    XSetIOErrorHandler(DisplayLost);
    XSetIOErrorExitHandler(display, DisplayLostExit, nullptr);
  }
  auto open = [&](int samples) {
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_SAMPLES, samples);
    GLFWwindow* window = glfwCreateWindow(1200, 900, title.c_str(), nullptr, nullptr);
    if (window == nullptr) {
      throw InputError(option + " cannot open a window: " + last_glfw_error);
    }
    glfwMakeContextCurrent(window);
    return window;
  };
  GLFWwindow* window = open(4);
  // a software rasteriser shades every pixel four times over with 4x multisampling, which
  // halves its frame rate (docs/performance.md): there the window draws without it
  if (IsSoftwareRenderer(reinterpret_cast<const char*>(glGetString(GL_RENDERER)))) {
    glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(window);
    window = open(0);
  }
  glfwSwapInterval(1);
  glfwShowWindow(window);
  return window;
}

bool ViewerDisplayLost() { return display_lost; }

double Viewer::FramesPerSecond() const {
  return FrameRate(run_frames_, std::chrono::duration<double>(last_drawn_ - first_drawn_).count());
}

Viewer::Viewer(const std::string& title, std::string out_dir, int max_frames)
    : out_dir_(std::move(out_dir)), max_frames_(max_frames) {
  window_ = OpenViewerWindow(title, "--view");
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
    if (action != GLFW_RELEASE) Of(w)->controls_.Key(key);
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
    Viewer* v = Of(w);
    const bool down = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_LEFT) v->left_down_ = down;
    if (button == GLFW_MOUSE_BUTTON_RIGHT) v->right_down_ = down;
    glfwGetCursorPos(w, &v->last_x_, &v->last_y_);
  });
  glfwSetCursorPosCallback(window_,
                           [](GLFWwindow* w, double x, double y) { Of(w)->OnMouseMove(x, y); });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
    Viewer* v = Of(w);
    if (v->renderer_) v->renderer_->MoveCamera(mjMOUSE_ZOOM, 0, -0.05 * dy, &v->camera_);
  });
  // a thread holds one context at a time: the window's is current only while it draws, so that
  // the run's pictures can draw in theirs
  glfwMakeContextCurrent(nullptr);
}

Viewer::~Viewer() {
  // with the display gone, neither the window nor the GL objects in it can be let go of
  if (display_lost) {
    (void)renderer_.release();
    return;
  }
  glfwMakeContextCurrent(window_);
  renderer_.reset();  // its GL objects go while the context still exists
  if (window_ != nullptr) glfwDestroyWindow(window_);

  // no glfwTerminate: GLFW stays initialised until the process ends, and with it the display
  // connection and Mesa's driver (closing the display unloads the driver and strands what it
  // allocated, as eglTerminate would)
}

void Viewer::OnMouseMove(double x, double y) {
  const double dx = x - last_x_, dy = y - last_y_;
  last_x_ = x;
  last_y_ = y;
  if (!renderer_ || (!left_down_ && !right_down_)) return;
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  if (height <= 0) return;
  const int action = left_down_ ? mjMOUSE_ROTATE_V : mjMOUSE_MOVE_V;
  renderer_->MoveCamera(action, dx / height, dy / height, &camera_);
}

void Viewer::SaveScreenshot(const std::string& file) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  mjr_setBuffer(mjFB_WINDOW, &renderer_->context());
  const Image image = renderer_->Read({0, 0, width, height});
  const std::string path = (std::filesystem::path(out_dir_) / file).string();
  WritePng(path, image.width, image.height, image.rgb);
  std::printf("  screenshot: %s\n", path.c_str());
}

void Viewer::Draw(Session& run, const std::string& state) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  const mjrRect viewport{0, 0, width, height};
  if (!controls_.preset.empty()) {
    camera_ = renderer_->Camera(controls_.preset, static_cast<double>(width) / height);
    controls_.preset.clear();
  }
  if (controls_.follow) {
    const int robot = controls_.followed % run.kernel().robot_count();
    const Pose2D p = run.kernel().world().RobotPose(run.kernel().state().data(), robot);
    camera_.lookat[0] = p.x_m;
    camera_.lookat[1] = p.y_m;
  }
  DrawOptions draw;
  draw.beams = controls_.beams;
  draw.beliefs = controls_.beliefs;
  draw.firmware = &run.beliefs();
  if (controls_.hud) draw.hud = run.hud();
  mjr_setBuffer(mjFB_WINDOW, &renderer_->context());
  renderer_->Draw(viewport, camera_, draw);

  char speed[64];
  std::snprintf(speed, sizeof(speed), "%s%gx real time%s", controls_.follow ? "following; " : "",
                controls_.speed, controls_.help ? "" : "; H: help");
  const std::string corner = state + speed;
  mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMRIGHT, viewport, corner.c_str(), nullptr,
              &renderer_->context());
  if (controls_.help) {
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPRIGHT, viewport, ViewerControls::HelpKeys(),
                ViewerControls::HelpActions(), &renderer_->context());
  }
}

std::string Viewer::State(Session& run) const {
  if (run.Over()) {
    const std::string verdict = run.verdict();
    return "run over" + (verdict.empty() ? "" : ": " + verdict) + "\n";
  }
  return controls_.paused ? "paused\n" : "";
}

bool Viewer::Frame(Session& run, const std::string& state) {
  glfwMakeContextCurrent(window_);
  Draw(run, state);
  last_drawn_ = std::chrono::steady_clock::now();
  ++frames_;
  if (run_frames_++ == 0) first_drawn_ = last_drawn_;
  const bool last_frame = max_frames_ > 0 && frames_ >= max_frames_;
  if (controls_.screenshot || last_frame) {
    SaveScreenshot(last_frame ? "view.png" : "view_" + std::to_string(++screenshots_) + ".png");
    controls_.screenshot = false;
  }
  glfwSwapBuffers(window_);
  glfwMakeContextCurrent(nullptr);
  glfwPollEvents();
  if (last_frame) controls_.quit = true;
  return !display_lost && !glfwWindowShouldClose(window_) && !controls_.quit;
}

void Viewer::Begin(Session& run) {
  glfwMakeContextCurrent(window_);
  renderer_ = std::make_unique<SceneRenderer>(run.kernel(), mjFONTSCALE_150);
  glfwMakeContextCurrent(nullptr);
  if (frames_ == 0) controls_.preset = "free";
}

void Viewer::Show(Session& run) {
  run_frames_ = 0;  // a run started again is a run of its own
  controls_.restart = false;
  Begin(run);
  using Clock = std::chrono::steady_clock;
  auto last = Clock::now();
  double behind_s = 0;  // sim time owed to the wall clock
  const double dt = run.kernel().timestep_s();
  while (!controls_.restart) {
    const auto now = Clock::now();
    const double wall_s = std::chrono::duration<double>(now - last).count();
    last = now;
    if (!run.Over()) {
      if (controls_.paused) {
        for (; controls_.steps_wanted > 0 && !run.Over(); --controls_.steps_wanted) run.Step();
        behind_s = 0;
      } else {
        // catch up with the wall clock, but never spend more than a frame's time on it: a slow
        // machine shows the run slower, not in jumps
        behind_s += wall_s * controls_.speed;
        const auto until = now + std::chrono::milliseconds(30);
        while (behind_s >= dt && !run.Over() && Clock::now() < until) {
          run.Step();
          behind_s -= dt;
        }
        if (behind_s > 0.1 * controls_.speed) behind_s = 0;
      }
    }
    if (!Frame(run, State(run))) break;
  }
  if (display_lost) {
    run.Stop(kDisplayLost);
    return;
  }
  glfwMakeContextCurrent(window_);
  renderer_.reset();
  glfwMakeContextCurrent(nullptr);
}

void Viewer::Watch(Session& run) {
  using Clock = std::chrono::steady_clock;
  constexpr auto kFrame = std::chrono::milliseconds(33);
  if (!renderer_) {
    Begin(run);
    last_frame_ = Clock::now() - kFrame;
  }
  const double sim_s = run.kernel().state().data().time;
  for (;;) {
    // the caller runs the program: it cannot start again from here
    controls_.restart = false;
    const Clock::time_point now = Clock::now();
    // a frame's time after the last one was drawn: on a slow renderer the run still advances
    if (now - last_frame_ >= kFrame) {
      const bool open = Frame(run, State(run));
      last_frame_ = Clock::now();
      if (!open) {
        run.Stop(display_lost ? kDisplayLost : "the viewer's window was closed");
        return;
      }
      continue;
    }
    if (controls_.paused) {
      pace_speed_ = 0;  // the pace starts again from here
      if (controls_.steps_wanted > 0) {
        --controls_.steps_wanted;
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      continue;
    }
    // sim time runs at speed x the wall clock from the last change of speed; a slow machine
    // shows the run slower, not in jumps
    const double late_s = std::chrono::duration<double>(now - pace_wall_).count() -
                          (sim_s - pace_sim_s_) / controls_.speed;
    if (pace_speed_ != controls_.speed || late_s > 0.25) {
      pace_speed_ = controls_.speed;
      pace_wall_ = now;
      pace_sim_s_ = sim_s;
      return;
    }
    if (late_s >= 0) return;
    std::this_thread::sleep_for(std::min(
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(-late_s)),
        Clock::duration(kFrame)));
  }
}

void Viewer::Linger(Session& run, const std::string& ending) {
  if (display_lost) return;
  if (!renderer_) Begin(run);
  controls_.restart = false;
  while (!glfwWindowShouldClose(window_) && !controls_.quit &&
         Frame(run, "run over: " + ending + "\n")) {
    controls_.restart = false;
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  glfwMakeContextCurrent(window_);
  renderer_.reset();
  glfwMakeContextCurrent(nullptr);
}

}  // namespace unimouse
