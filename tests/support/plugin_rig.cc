// SPDX-License-Identifier: GPL-3.0-or-later
#include "plugin_rig.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>

#include "bundled_components.h"

namespace unimouse::testing {

PluginRegistry BundledComponents() {
  PluginRegistry registry;
  AddBundledComponents(registry);
  return registry;
}

std::string RigYaml(double armature_kg_m2, const std::string& components) {
  std::ostringstream y;
  y << "name: rig\n"
       "chassis:\n"
       "  name: base\n"
       "  geoms: [{ type: box, size_m: [0.2, 0.2, 0.1], mass_kg: 1 }]\n"
       "  bodies:\n"
       "    - name: rotor\n"
       "      pos_m: [0, 0, 0.2]\n"
       "      joint: { name: rotor, type: hinge, axis: [0, 1, 0], armature_kg_m2: "
    << armature_kg_m2
    << " }\n"
       "      geoms: [{ type: sphere, radius_m: 0.016, mass_kg: 0.01, contact: false }]\n"
       "actuators: [{ name: rotor_motor, joint: rotor }]\n"
       "inputs: [volts]\n"
       "components:\n"
    << components;
  return y.str();
}

std::unique_ptr<Kernel> MakeKernel(const std::string& robot_yaml, const Maze* maze,
                                   KernelOptions options) {
  static const PluginRegistry registry = BundledComponents();
  // traces of the bundled robot's logger go to a scratch directory, not the working one
  if (options.output_dir == ".") {
    options.output_dir =
        (std::filesystem::temp_directory_path() / ("unimouse_tests_" + std::to_string(::getpid())))
            .string();
  }
  return Kernel::Create(ParseRobotSpec(robot_yaml, "robot.yaml"), maze, registry, options);
}

double SignalValue(const Kernel& kernel, const std::string& name) {
  const int id = kernel.model().FindSignal(name);
  EXPECT_GE(id, 0) << "no signal " << name;
  return id < 0 ? 0 : kernel.state().signals()[id];
}

void SetSignal(Kernel& kernel, const std::string& name, double value) {
  const int id = kernel.model().FindSignal(name);
  ASSERT_GE(id, 0) << "no signal " << name;
  kernel.state().signals()[id] = value;
}

double JointAngle(const Kernel& kernel, const std::string& joint) {
  const int j = mj_name2id(&kernel.mj_model(), mjOBJ_JOINT, joint.c_str());
  return kernel.state().data().qpos[kernel.mj_model().jnt_qposadr[j]];
}

double JointSpeed(const Kernel& kernel, const std::string& joint) {
  const int j = mj_name2id(&kernel.mj_model(), mjOBJ_JOINT, joint.c_str());
  return kernel.state().data().qvel[kernel.mj_model().jnt_dofadr[j]];
}

}  // namespace unimouse::testing
