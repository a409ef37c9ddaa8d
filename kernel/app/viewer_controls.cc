// SPDX-License-Identifier: GPL-3.0-or-later
#include "viewer_controls.h"

#include <GLFW/glfw3.h>

#include <algorithm>

namespace unimouse {

bool DisplayKeys::Key(int key) {
  switch (key) {
    case GLFW_KEY_F:
      follow = !follow;
      return true;
    case GLFW_KEY_1:
      preset = "top";
      return true;
    case GLFW_KEY_2:
      preset = "chase";
      return true;
    case GLFW_KEY_3:
      preset = "free";
      return true;
    case GLFW_KEY_R:
      beams = !beams;
      return true;
    case GLFW_KEY_B:
      beliefs = !beliefs;
      return true;
    case GLFW_KEY_U:
      hud = !hud;
      return true;
    case GLFW_KEY_H:
    case GLFW_KEY_F1:
      help = !help;
      return true;
    case GLFW_KEY_S:
      screenshot = true;
      return true;
    case GLFW_KEY_Q:
    case GLFW_KEY_ESCAPE:
      quit = true;
      return true;
    default:
      return false;
  }
}

bool ViewerControls::Key(int key) {
  switch (key) {
    case GLFW_KEY_SPACE:
      paused = !paused;
      return true;
    case GLFW_KEY_RIGHT:
    case GLFW_KEY_N:
      paused = true;
      ++steps_wanted;
      return true;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
      speed = std::min(speed * 2, kMaxSpeed);
      return true;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
      speed = std::max(speed / 2, kMinSpeed);
      return true;
    case GLFW_KEY_0:
      speed = 1;
      return true;
    case GLFW_KEY_TAB:
      // the next robot of several, followed
      follow = true;
      ++followed;
      return true;
    case GLFW_KEY_BACKSPACE:
      restart = true;
      return true;
    default:
      return DisplayKeys::Key(key);
  }
}

const char* ViewerControls::HelpKeys() {
  return "Space\nRight, N\n+ - 0\nF\nTab\n1 2 3\nR\nB\nU\nS\nBackspace\nQ, Esc\nmouse";
}

const char* ViewerControls::HelpActions() {
  return "pause, resume\none step (pauses)\nfaster, slower, real time\nfollow the robot\n"
         "follow the next robot\n"
         "camera: top, chase, free\nToF beams\nfirmware's walls\nHUD\nscreenshot\n"
         "start the run again\nquit\ndrag: orbit (left), pan (right); wheel: zoom";
}

double FrameRate(int frames, double span_s) {
  return frames > 1 && span_s > 0 ? (frames - 1) / span_s : 0;
}

}  // namespace unimouse
