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

RobotYaml BundledRobotWith(const std::string& components) {
  std::ifstream in(BundledRobotPath());
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  const std::string marker = "components: []";
  const size_t at = text.find(marker);
  RobotYaml out;
  out.first_component_line =
      static_cast<int>(std::count(text.begin(), text.begin() + at, '\n')) + 2;
  out.text = text.substr(0, at) + "components:\n" + components + text.substr(at + marker.size());
  return out;
}

}  // namespace unimouse::testing
