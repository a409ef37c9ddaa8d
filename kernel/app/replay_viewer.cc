// SPDX-License-Identifier: GPL-3.0-or-later
#include "replay_viewer.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <thread>

#include "png_file.h"
#include "scene_renderer.h"
#include "unimouse/errors.h"
#include "viewer.h"

namespace unimouse {
namespace {

// the timeline's strip along the bottom of the window, in pixels
constexpr int kTimelineHeight = 24;

const char* kHelpKeys =
    "Space\nLeft Right\n+ - 0\n[ ]  PgUp PgDn\nHome End\nF\n1 2 3\nR\nB\nU\nS\nQ, Esc\nmouse";
const char* kHelpActions =
    "play, pause\na sample back, forward (pauses)\nfaster, slower, real time\n"
    "previous, next event\nstart, end\nfollow the robot\ncamera: top, chase, free\nToF beams\n"
    "firmware's walls\nHUD\nscreenshot\nquit\n"
    "drag the timeline: scrub; drag: orbit (left), pan (right); wheel: zoom";

class ReplayWindow {
 public:
  ReplayWindow(ReplayScene& scene, const ReplayViewOptions& o)
      : scene_(scene), options_(o), paused_(o.paused), speed_(o.speed), cursor_s_(o.start_s) {
    window_ = OpenViewerWindow(o.title, "replay");
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
      if (action != GLFW_RELEASE) Of(w)->Key(key);
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
      ReplayWindow* v = Of(w);
      glfwGetCursorPos(w, &v->last_x_, &v->last_y_);
      const bool down = action == GLFW_PRESS;
      if (button == GLFW_MOUSE_BUTTON_LEFT) {
        v->scrubbing_ = down && v->OnTimeline(v->last_y_);
        v->left_down_ = down && !v->scrubbing_;
        if (v->scrubbing_) v->Scrub(v->last_x_);
      }
      if (button == GLFW_MOUSE_BUTTON_RIGHT) v->right_down_ = down;
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) { Of(w)->Move(x, y); });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
      ReplayWindow* v = Of(w);
      v->renderer_->MoveCamera(mjMOUSE_ZOOM, 0, -0.05 * dy, &v->camera_);
    });
    scene_.ShowAt(cursor_s_);
    renderer_ = std::make_unique<SceneRenderer>(scene_.kernel(), mjFONTSCALE_150);
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    camera_ = renderer_->Camera("top", static_cast<double>(width) / std::max(height, 1));
  }

  ~ReplayWindow() {
    if (ViewerDisplayLost()) {
      (void)renderer_.release();  // nothing of a lost display can be let go of
      return;
    }
    glfwMakeContextCurrent(window_);
    renderer_.reset();
    glfwDestroyWindow(window_);
  }

  void Run() {
    using Clock = std::chrono::steady_clock;
    auto last = Clock::now();
    while (!ViewerDisplayLost() && !glfwWindowShouldClose(window_) && !quit_) {
      const auto now = Clock::now();
      if (!paused_ && !scrubbing_) {
        cursor_s_ += std::chrono::duration<double>(now - last).count() * speed_;
        if (cursor_s_ >= End()) {
          cursor_s_ = End();
          paused_ = true;  // at the end it waits, as a player does
        }
      }
      last = now;
      scene_.ShowAt(cursor_s_);
      Frame();
      glfwPollEvents();
      if (options_.max_frames > 0 && frames_ >= options_.max_frames) break;
    }
  }

 private:
  static ReplayWindow* Of(GLFWwindow* w) {
    return static_cast<ReplayWindow*>(glfwGetWindowUserPointer(w));
  }

  double End() const { return scene_.end_s(); }

  void Key(int key) {
    const std::vector<double>& marks = scene_.marks();
    const double* speed = std::find(std::begin(kReplaySpeeds), std::end(kReplaySpeeds), speed_);
    switch (key) {
      case GLFW_KEY_SPACE:
        if (paused_ && cursor_s_ >= End()) cursor_s_ = 0;  // played to the end: from the start
        paused_ = !paused_;
        break;
      case GLFW_KEY_LEFT:
      case GLFW_KEY_RIGHT:
        paused_ = true;
        cursor_s_ = scene_.NextSample(cursor_s_, key == GLFW_KEY_RIGHT ? 1 : -1);
        break;
      case GLFW_KEY_EQUAL:
      case GLFW_KEY_KP_ADD:
        if (speed + 1 < std::end(kReplaySpeeds)) speed_ = speed[1];
        break;
      case GLFW_KEY_MINUS:
      case GLFW_KEY_KP_SUBTRACT:
        if (speed > std::begin(kReplaySpeeds) && speed != std::end(kReplaySpeeds))
          speed_ = speed[-1];
        break;
      case GLFW_KEY_0:
        speed_ = 1;
        break;
      case GLFW_KEY_RIGHT_BRACKET:
      case GLFW_KEY_PAGE_DOWN: {
        const auto next = std::upper_bound(marks.begin(), marks.end(), cursor_s_ + 1e-9);
        if (next != marks.end()) cursor_s_ = *next;
        paused_ = true;
        break;
      }
      case GLFW_KEY_LEFT_BRACKET:
      case GLFW_KEY_PAGE_UP: {
        const auto next = std::lower_bound(marks.begin(), marks.end(), cursor_s_ - 1e-9);
        if (next != marks.begin()) cursor_s_ = *std::prev(next);
        paused_ = true;
        break;
      }
      case GLFW_KEY_HOME:
        cursor_s_ = 0;
        break;
      case GLFW_KEY_END:
        cursor_s_ = End();
        break;
      case GLFW_KEY_F:
        follow_ = !follow_;
        break;
      case GLFW_KEY_1:
      case GLFW_KEY_2:
      case GLFW_KEY_3: {
        int width = 0, height = 0;
        glfwGetFramebufferSize(window_, &width, &height);
        camera_ = renderer_->Camera(kCameraNames[key - GLFW_KEY_1],
                                    static_cast<double>(width) / std::max(height, 1));
        break;
      }
      case GLFW_KEY_R:
        beams_ = !beams_;
        break;
      case GLFW_KEY_B:
        beliefs_ = !beliefs_;
        break;
      case GLFW_KEY_U:
        hud_ = !hud_;
        break;
      case GLFW_KEY_H:
      case GLFW_KEY_F1:
        help_ = !help_;
        break;
      case GLFW_KEY_S:
        screenshot_ = true;
        break;
      case GLFW_KEY_Q:
      case GLFW_KEY_ESCAPE:
        quit_ = true;
        break;
      default:
        break;
    }
    cursor_s_ = std::clamp(cursor_s_, 0.0, End());
  }

  bool OnTimeline(double y) const {
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    return y >= height - kTimelineHeight;
  }

  void Scrub(double x) {
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    cursor_s_ = std::clamp(x / std::max(width, 1), 0.0, 1.0) * End();
  }

  void Move(double x, double y) {
    const double dx = x - last_x_, dy = y - last_y_;
    last_x_ = x;
    last_y_ = y;
    if (scrubbing_) {
      Scrub(x);
      return;
    }
    if (!left_down_ && !right_down_) return;
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    if (height <= 0) return;
    renderer_->MoveCamera(left_down_ ? mjMOUSE_ROTATE_V : mjMOUSE_MOVE_V, dx / height, dy / height,
                          &camera_);
  }

  void Frame() {
    glfwMakeContextCurrent(window_);
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    const mjrRect viewport{0, 0, width, height};
    if (follow_) {
      const Pose2D p = scene_.kernel().world().RobotPose(scene_.kernel().state().data(), 0);
      camera_.lookat[0] = p.x_m;
      camera_.lookat[1] = p.y_m;
    }
    DrawOptions draw;
    draw.beams = beams_;
    draw.beliefs = beliefs_;
    draw.firmware = &scene_.beliefs();
    draw.clock = false;  // the corner says the time, above the timeline
    if (hud_) draw.hud = scene_.Hud(options_.signals);
    mjr_setBuffer(mjFB_WINDOW, &renderer_->context());
    renderer_->Draw(viewport, camera_, draw);
    DrawTimeline(width);

    char corner[160];
    std::snprintf(corner, sizeof(corner), "replay %.3f s of %.3f s\n%s%gx%s", scene_.time_s(),
                  End(), paused_ ? "paused; " : "", speed_, help_ ? "" : "; H: help");
    mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMRIGHT,
                {0, kTimelineHeight, width, height - kTimelineHeight}, corner, nullptr,
                &renderer_->context());
    if (help_) {
      mjr_overlay(mjFONT_NORMAL, mjGRID_TOPRIGHT, viewport, kHelpKeys, kHelpActions,
                  &renderer_->context());
    }
    ++frames_;
    const bool last = options_.max_frames > 0 && frames_ >= options_.max_frames;
    if (screenshot_ || last) {
      Screenshot(last ? "replay.png" : "replay_" + std::to_string(++screenshots_) + ".png", width,
                 height, draw.hud);
      screenshot_ = false;
    }
    glfwSwapBuffers(window_);
  }

  // the run's length as a bar, the played part filled, a tick at every event, the cursor
  void DrawTimeline(int width) {
    const double end = std::max(End(), 1e-9);
    mjr_rectangle({0, 0, width, kTimelineHeight}, 0.12f, 0.12f, 0.14f, 1);
    mjr_rectangle({0, 6, static_cast<int>(width * scene_.time_s() / end), kTimelineHeight - 12},
                  0.25f, 0.5f, 0.85f, 1);
    for (double mark : scene_.marks()) {
      mjr_rectangle({static_cast<int>(width * mark / end), 2, 1, 4}, 0.95f, 0.75f, 0.2f, 1);
    }
    mjr_rectangle({static_cast<int>(width * scene_.time_s() / end) - 1, 0, 3, kTimelineHeight}, 1,
                  1, 1, 1);
  }

  void Screenshot(const std::string& file, int width, int height,
                  const std::vector<std::string>& hud) {
    const Image image = renderer_->Read({0, 0, width, height});
    const std::string path = (std::filesystem::path(options_.out_dir) / file).string();
    WritePng(path, image.width, image.height, image.rgb);
    std::printf("  screenshot: %s at %.3f s\n", path.c_str(), scene_.time_s());
    for (const std::string& line : hud) std::printf("    %s\n", line.c_str());
    std::fflush(stdout);
  }

  ReplayScene& scene_;
  ReplayViewOptions options_;
  GLFWwindow* window_ = nullptr;
  std::unique_ptr<SceneRenderer> renderer_;
  mjvCamera camera_{};
  bool paused_, follow_ = false, beams_ = true, beliefs_ = true, hud_ = true, help_ = false;
  bool screenshot_ = false, quit_ = false;
  double speed_;
  double cursor_s_;
  int frames_ = 0, screenshots_ = 0;
  bool left_down_ = false, right_down_ = false, scrubbing_ = false;
  double last_x_ = 0, last_y_ = 0;
};

}  // namespace

void ShowReplay(ReplayScene& scene, const ReplayViewOptions& options) {
  ReplayWindow window(scene, options);
  window.Run();
}

}  // namespace unimouse
