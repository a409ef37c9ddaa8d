// SPDX-License-Identifier: GPL-3.0-or-later
// The scenario API: the C functions behind `sim.*` and the list that names them all, with the
// API level each appeared in (`unimouse scenario-api` prints it; a golden test guards it).
#ifndef UNIMOUSE_SCENARIO_SCENARIO_API_H_
#define UNIMOUSE_SCENARIO_SCENARIO_API_H_

#include <lua5.4/lua.h>

#include <span>

namespace unimouse {

/// One `sim.*` function: its name, its C function, the API level it appeared in, and its help.
struct ApiEntry {
  const char* name;
  lua_CFunction fn;  // null: defined in Lua, in the prelude
  int since;
  const char* signature;
  const char* summary;
};

/// Every `sim.*` function, in the order `unimouse scenario-api` lists them.
std::span<const ApiEntry> ScenarioApiEntries();

/// The sandbox's own functions: math.random from the run's seed, print to the run's log, and
/// the firmware log lines since the last call (for the events, in the prelude).
struct SandboxFunctions {
  lua_CFunction random;
  lua_CFunction print;
  lua_CFunction take_firmware_lines;
};
SandboxFunctions ScenarioSandboxFunctions();

}  // namespace unimouse

#endif  // UNIMOUSE_SCENARIO_SCENARIO_API_H_
