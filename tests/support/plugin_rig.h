// SPDX-License-Identifier: GPL-3.0-or-later
// Kernels with every bundled component type registered statically, and a test rig: a heavy
// block on the floor carrying a free-spinning wheel that touches nothing.
#ifndef UNIMOUSE_TESTS_PLUGIN_RIG_H_
#define UNIMOUSE_TESTS_PLUGIN_RIG_H_

#include <memory>
#include <string>

#include "kernel.h"

namespace unimouse::testing {

/// Returns a registry with battery, H-bridge, DC motor, encoder, ToF sensor, logger and link.
PluginRegistry BundledComponents();

/// Robot YAML of the rig: block `base` (1 kg), wheel `rotor` (sphere r 0.016 m, 0.01 kg, no
/// contact) on hinge `rotor` about y with `armature_kg_m2` added, actuator `rotor_motor`, input
/// signal `volts`, then the given component lines.
std::string RigYaml(double armature_kg_m2, const std::string& components);

/// Builds a kernel from robot YAML text on an open floor (or in `maze`).
std::unique_ptr<Kernel> MakeKernel(const std::string& robot_yaml, const Maze* maze = nullptr,
                                   KernelOptions options = {});

/// Reads or writes a signal by name; fails the test if it does not exist.
double SignalValue(const Kernel& kernel, const std::string& name);
void SetSignal(Kernel& kernel, const std::string& name, double value);

/// Returns the position or speed of a hinge joint by name.
double JointAngle(const Kernel& kernel, const std::string& joint);
double JointSpeed(const Kernel& kernel, const std::string& joint);

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_PLUGIN_RIG_H_
