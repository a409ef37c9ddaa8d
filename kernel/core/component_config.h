// SPDX-License-Identifier: GPL-3.0-or-later
// Checks a component's YAML parameters against its type's declared table and fills defaults,
// so that a component is created with complete, valid values or not at all.
#ifndef UNIMOUSE_CORE_COMPONENT_CONFIG_H_
#define UNIMOUSE_CORE_COMPONENT_CONFIG_H_

#include <map>
#include <string>
#include <vector>

#include "robot_spec.h"
#include "unimouse/plugin_abi.h"

/// Validated parameter values of one component; what plugins read through unimouse_host.
struct unimouse_config {
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> strings;
  std::vector<std::string> given;  ///< names the robot file set explicitly
  /// names whose values a data file gave, not the command line (see KernelOptions)
  std::vector<std::string> from_data_file;
};

namespace unimouse {

/// Returns the validated parameters; throws InputError "file:line:col: component 'name'
/// (type): reason".
unimouse_config ValidateParams(const unimouse_component_type& type, const ComponentSpec& spec);

/// Returns the host table plugins read their parameters through.
const unimouse_host& ConfigHost();

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_COMPONENT_CONFIG_H_
