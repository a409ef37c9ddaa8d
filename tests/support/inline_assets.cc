// SPDX-License-Identifier: GPL-3.0-or-later
#include "inline_assets.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace unimouse::testing {

std::string BundledRobotPath() { return UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml"; }

std::string SharedMazesDir() {
  const std::filesystem::path dir = UNIMOUSE_SOURCE_DIR "/../shared/mazes";
  return std::filesystem::is_directory(dir) ? dir.lexically_normal().string() : "";
}

std::string ReadBundledRobot() {
  std::ifstream in(BundledRobotPath());
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

RobotYaml BundledRobotWith(const std::string& components) {
  const std::string text = ReadBundledRobot();
  // the components list is the file's last section
  const std::string marker = "\ncomponents:\n";
  const size_t at = text.find(marker);
  RobotYaml out;
  out.text = text.substr(0, at) + marker + components;
  out.first_component_line =
      static_cast<int>(std::count(out.text.begin(), out.text.begin() + at, '\n')) + 3;
  return out;
}

RobotSpec BareRobot() {
  RobotSpec robot = LoadRobotSpec(BundledRobotPath());
  robot.components.clear();
  return robot;
}

}  // namespace unimouse::testing
