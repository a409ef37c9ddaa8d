// SPDX-License-Identifier: GPL-3.0-or-later
// Every component type that ships with unimouse, linked in statically: for tests and benchmarks,
// which use the component classes directly instead of loading the plugin libraries.
#ifndef UNIMOUSE_PLUGINS_BUNDLED_COMPONENTS_H_
#define UNIMOUSE_PLUGINS_BUNDLED_COMPONENTS_H_

#include "plugin_registry.h"

namespace unimouse {

/// Registers every plugin that plugins/CMakeLists.txt adds, compiled into the program.
void AddBundledComponents(PluginRegistry& registry);

}  // namespace unimouse

#endif  // UNIMOUSE_PLUGINS_BUNDLED_COMPONENTS_H_
