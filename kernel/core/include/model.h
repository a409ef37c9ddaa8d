// SPDX-License-Identifier: GPL-3.0-or-later
// Everything constant for a run: the world, the robot's components bound to it, and the tables
// that give a State its shape. A Model is built once by Kernel::Create; a State holds everything
// that changes. The one part of the world that moves is the set of collision proxies, placed
// before each step as a function of the State alone (see world.h).
#ifndef UNIMOUSE_CORE_MODEL_H_
#define UNIMOUSE_CORE_MODEL_H_

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "unimouse/plugin_abi.h"
#include "world.h"
#include "yaml_doc.h"

namespace unimouse {

/// One component of the robot, created and bound.
struct ComponentInstance {
  const unimouse_component_type* type = nullptr;
  void* self = nullptr;  ///< owned: destroyed through type->destroy with the Model
  std::string name;      ///< as the run's messages name it: "b/link" when robot b is one of several
  std::string file_name;  ///< as the robot file names it: "link"
  int robot = 0;          ///< which robot of the run it belongs to
  SourceLocation location;
  int every_n_steps = 1;
  int state_offset = 0;
  int nstate = 0;
};

/// A beam a component declared at bind (a ToF sensor's): drawn from a site along its x axis, as
/// long as a signal's value.
struct BeamSpec {
  int site = -1;
  int length_signal = -1;
  double range_max_m = 0;  ///< a length this long means no target
};

/// A beam as drawn: from its site to as far as its signal says, in the world frame, and whether
/// it hit something (a reading short of the range).
struct BeamLine {
  std::array<double, 3> from_m{}, to_m{};
  bool hit = false;
};
/// Returns a beam's line in the state `d` (its sites placed by kinematics) with `signals`.
BeamLine BeamLineOf(const BeamSpec& beam, const mjData& d, const std::vector<double>& signals);

/// A component that reads a signal before its writer runs, in YAML order: within a phase it sees
/// the value the writer left on the previous tick.
struct EarlyRead {
  int signal = -1;
  int reader = -1;  ///< component indices
  int writer = -1;
};

struct Model {
  Model() = default;
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;
  ~Model();

  const mjModel& mj() const { return world->model(); }
  double timestep_s() const { return world->model().opt.timestep; }
  /// Returns a signal's id, or -1.
  int FindSignal(const std::string& name) const;

  std::unique_ptr<World> world;
  std::vector<ComponentInstance> components;  ///< in YAML order: the order of every phase
  std::vector<std::string> signal_names;
  std::vector<std::string> rng_names;
  std::vector<BeamSpec> beams;
  std::vector<EarlyRead> early_reads;  ///< in signal order
  /// Per MuJoCo joint id, what the robot file calls it and where, with the actuators on it:
  /// "joint 'left_wheel' (robot.yaml:37:7), actuator 'left_motor' (robot.yaml:60:5)"; empty
  /// for joints the robot file does not declare.
  std::vector<std::string> joint_places;
  int component_state_size = 0;
  /// What the components declared themselves to be: UNIMOUSE_TRAIT_* bits of all, or-ed.
  int traits = 0;
  /// Per robot: its name ("" for the only robot of a run), the prefix of its names in the
  /// physics model and among the signals ("" or "name/"), and its components' traits.
  std::vector<std::string> robot_names;
  std::vector<std::string> robot_prefixes;
  std::vector<int> robot_traits;
};

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_MODEL_H_
