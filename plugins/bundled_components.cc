// SPDX-License-Identifier: GPL-3.0-or-later
#include "bundled_components.h"

#include "bundled_plugins.h"

namespace unimouse {

void AddBundledComponents(PluginRegistry& registry) {
#define UNIMOUSE_ADD_STATIC(folder, type) registry.AddStatic(ComponentType<type>());
  UNIMOUSE_BUNDLED_PLUGINS(UNIMOUSE_ADD_STATIC)
#undef UNIMOUSE_ADD_STATIC
}

}  // namespace unimouse
