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

class ReplayWindow {
 public:
  ReplayWindow(ReplayScene& scene, const ReplayViewOptions& o) : scene_(scene), options_(o) {
    timeline_ = {scene.end_s(), scene.sample_times(), scene.marks()};
    controls_.cursor_s = o.start_s;
    controls_.paused = o.paused;
    controls_.speed = o.speed;
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
    scene_.ShowAt(controls_.cursor_s);
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
    while (!ViewerDisplayLost() && !glfwWindowShouldClose(window_) && !controls_.quit) {
      const auto now = Clock::now();
      if (!scrubbing_) controls_.Play(std::chrono::duration<double>(now - last).count(), timeline_);
      last = now;
      scene_.ShowAt(controls_.cursor_s);
      Frame();
      glfwPollEvents();
      if (options_.max_frames > 0 && frames_ >= options_.max_frames) break;
    }
  }

 private:
  static ReplayWindow* Of(GLFWwindow* w) {
    return static_cast<ReplayWindow*>(glfwGetWindowUserPointer(w));
  }

  void Key(int key) {
    controls_.Key(key, timeline_);
    if (!controls_.preset.empty()) {
      int width = 0, height = 0;
      glfwGetFramebufferSize(window_, &width, &height);
      camera_ =
          renderer_->Camera(controls_.preset, static_cast<double>(width) / std::max(height, 1));
      controls_.preset.clear();
    }
  }

  bool OnTimeline(double y) const {
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    return y >= height - kTimelineHeight;
  }

  void Scrub(double x) {
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    controls_.Scrub(x / std::max(width, 1), timeline_);
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
    if (controls_.follow) {
      const Pose2D p = scene_.kernel().world().RobotPose(scene_.kernel().state().data(), 0);
      camera_.lookat[0] = p.x_m;
      camera_.lookat[1] = p.y_m;
    }
    DrawOptions draw;
    draw.beams = controls_.beams;
    draw.beliefs = controls_.beliefs;
    draw.firmware = &scene_.beliefs();
    draw.clock = false;  // the corner says the time, above the timeline
    if (controls_.hud) draw.hud = scene_.Hud(options_.signals);
    mjr_setBuffer(mjFB_WINDOW, &renderer_->context());
    renderer_->Draw(viewport, camera_, draw);
    DrawTimeline(width);

    char corner[160];
    std::snprintf(corner, sizeof(corner), "replay %.3f s of %.3f s\n%s%gx%s", scene_.time_s(),
                  timeline_.end_s, controls_.paused ? "paused; " : "", controls_.speed,
                  controls_.help ? "" : "; H: help");
    mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMRIGHT,
                {0, kTimelineHeight, width, height - kTimelineHeight}, corner, nullptr,
                &renderer_->context());
    if (controls_.help) {
      mjr_overlay(mjFONT_NORMAL, mjGRID_TOPRIGHT, viewport, ReplayControls::HelpKeys(),
                  ReplayControls::HelpActions(), &renderer_->context());
    }
    ++frames_;
    const bool last = options_.max_frames > 0 && frames_ >= options_.max_frames;
    if (controls_.screenshot || last) {
      Screenshot(last ? "replay.png" : "replay_" + std::to_string(++screenshots_) + ".png", width,
                 height, draw.hud);
      controls_.screenshot = false;
    }
    glfwSwapBuffers(window_);
  }

  // the run's length as a bar, the played part filled, a tick at every event, the cursor
  void DrawTimeline(int width) {
    const double end = std::max(timeline_.end_s, 1e-9);
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
  ReplayControls controls_;
  ReplayTimeline timeline_;
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
