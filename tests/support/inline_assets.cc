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

std::string GyroRobotWith(const std::string& more) {
  std::ifstream in(UNIMOUSE_SOURCE_DIR "/robots/unimouse-gyro.yaml");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::string marker = "\ncomponents:\n";
  return text.substr(0, text.find(marker)) + marker +
         "  - { type: unimouse.battery, name: battery, params: { emf_v: 6 } }\n"
         "  - { type: unimouse.h_bridge, name: left_bridge,\n"
         "      params: { command_in: left.command, voltage_out: left.voltage_v } }\n"
         "  - { type: unimouse.h_bridge, name: right_bridge,\n"
         "      params: { command_in: right.command, voltage_out: right.voltage_v } }\n"
         "  - { type: unimouse.dc_motor, name: left_motor,\n"
         "      params: { actuator: left_motor, voltage_in: left.voltage_v } }\n"
         "  - { type: unimouse.dc_motor, name: right_motor,\n"
         "      params: { actuator: right_motor, voltage_in: right.voltage_v } }\n" +
         more;
}

std::string TinyRobotWith(const std::string& components) {
  return "name: tiny\n"
         "chassis:\n"
         "  name: body\n"
         "  geoms: [{ type: sphere, radius_m: 0.02, mass_kg: 0.1 }]\n"
         "components:\n" +
         components;
}

std::string FiveTofRobot() {
  std::string text = ReadBundledRobot();
  // the new sites go after the last of the bundled ones, the new sensors after every component
  const size_t site = text.find("- { name: tof_right,");
  const size_t after_site = text.find('\n', site) + 1;
  text.insert(
      after_site,
      "    - { name: tof_left_side, pos_m: [0.030, 0.048, 0], euler_deg: [0, 0, 90] }\n"
      "    - { name: tof_right_side, pos_m: [0.030, -0.048, 0], euler_deg: [0, 0, -90] }\n");
  if (text.back() != '\n') text += '\n';
  text +=
      "  - type: unimouse.tof_sensor\n"
      "    name: tof.left_side\n"
      "    params: { site: tof_left_side, range_out: tof.left_side_m }\n"
      "  - type: unimouse.tof_sensor\n"
      "    name: tof.right_side\n"
      "    params: { site: tof_right_side, range_out: tof.right_side_m }\n";
  return text;
}

RobotSpec BareRobot() {
  RobotSpec robot = LoadRobotSpec(BundledRobotPath());
  robot.components.clear();
  return robot;
}

}  // namespace unimouse::testing
