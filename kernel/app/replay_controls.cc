// SPDX-License-Identifier: GPL-3.0-or-later
#include "replay_controls.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <iterator>

namespace unimouse {
namespace {

// a time within a nanosecond of the cursor is the cursor's own
constexpr double kSame_s = 1e-9;

// the first of `times` after `t_s`, or `t_s` when there is none
double After(const std::vector<double>& times, double t_s) {
  const auto next = std::upper_bound(times.begin(), times.end(), t_s + kSame_s);
  return next == times.end() ? t_s : *next;
}

// the last of `times` before `t_s`, or `t_s` when there is none
double Before(const std::vector<double>& times, double t_s) {
  const auto next = std::lower_bound(times.begin(), times.end(), t_s - kSame_s);
  return next == times.begin() ? t_s : *std::prev(next);
}

}  // namespace

bool ReplayControls::Key(int key, const ReplayTimeline& timeline) {
  const double* at = std::find(std::begin(kReplaySpeeds), std::end(kReplaySpeeds), speed);
  const auto first = std::begin(kReplaySpeeds), last = std::end(kReplaySpeeds) - 1;
  switch (key) {
    case GLFW_KEY_SPACE:
      if (paused && cursor_s >= timeline.end_s) cursor_s = 0;  // played to the end: again
      paused = !paused;
      return true;
    case GLFW_KEY_RIGHT:
      paused = true;
      cursor_s = After(timeline.samples, cursor_s);
      return true;
    case GLFW_KEY_LEFT:
      paused = true;
      cursor_s = Before(timeline.samples, cursor_s);
      return true;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
      speed = at >= last ? *last : at[1];
      return true;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
      speed = at <= first || at > last ? *first : at[-1];
      return true;
    case GLFW_KEY_0:
      speed = 1;
      return true;
    case GLFW_KEY_RIGHT_BRACKET:
    case GLFW_KEY_PAGE_DOWN:
      paused = true;
      cursor_s = After(timeline.marks, cursor_s);
      return true;
    case GLFW_KEY_LEFT_BRACKET:
    case GLFW_KEY_PAGE_UP:
      paused = true;
      cursor_s = Before(timeline.marks, cursor_s);
      return true;
    case GLFW_KEY_HOME:
      cursor_s = 0;
      return true;
    case GLFW_KEY_END:
      cursor_s = timeline.end_s;
      return true;
    default:
      return DisplayKeys::Key(key);
  }
}

void ReplayControls::Play(double wall_s, const ReplayTimeline& timeline) {
  if (paused) return;
  cursor_s += wall_s * speed;
  if (cursor_s >= timeline.end_s) {
    cursor_s = timeline.end_s;
    paused = true;
  }
}

void ReplayControls::Scrub(double fraction, const ReplayTimeline& timeline) {
  cursor_s = std::clamp(fraction, 0.0, 1.0) * timeline.end_s;
}

const char* ReplayControls::HelpKeys() {
  return "Space\nLeft Right\n+ - 0\n[ ]  PgUp PgDn\nHome End\nF\n1 2 3\nR\nB\nU\nS\nQ, Esc\nmouse";
}

const char* ReplayControls::HelpActions() {
  return "play, pause\na sample back, forward (pauses)\nfaster, slower, real time\n"
         "previous, next event\nstart, end\nfollow the robot\ncamera: top, chase, free\nToF beams\n"
         "firmware's walls\nHUD\nscreenshot\nquit\n"
         "drag the timeline: scrub; drag: orbit (left), pan (right); wheel: zoom";
}

}  // namespace unimouse
