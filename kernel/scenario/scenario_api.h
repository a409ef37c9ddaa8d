// SPDX-License-Identifier: GPL-3.0-or-later
// The scenario API: the C++ bodies behind `sim.*` and the list that names them all, with the
// API level each appeared in (`unimouse scenario-api` prints it; a golden test guards it). The
// list holds bodies, not C functions: Lua reaches them only through the Lua boundary
// (lua_call.h), which turns their exceptions into Lua errors.
#ifndef UNIMOUSE_SCENARIO_SCENARIO_API_H_
#define UNIMOUSE_SCENARIO_SCENARIO_API_H_

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lua_call.h"
#include "scenario.h"

namespace unimouse {

/// One function a script can call: its name, its C++ body, the API level it appeared in, and
/// its help.
struct ApiEntry {
  const char* name;
  LuaBody body;  ///< null: defined in Lua, in the prelude
  int since;
  const char* signature;
  const char* summary;
};

/// Every `sim.*` function, in the order `unimouse scenario-api` lists them.
std::span<const ApiEntry> ScenarioApiEntries();

/// The table argument of a function as its signature shows it: its position (1 for
/// "robot_place{x_m, y_m, yaw_deg?}", 2 for "snapshot_save(file, {camera?, ...})", 0 when it takes
/// none) and the keys it takes, the signature's names without "?" or "= ...". A script that gives
/// any other key is stopped at its line. A table written "{field = value, ...}" takes keys of the
/// script's choosing and is not one of these.
struct TableArgument {
  int position = 0;
  std::vector<std::string> keys;
};
TableArgument TableArgumentOf(const ApiEntry& entry);

/// The host's functions the prelude builds the sandbox with: print (to the run's log), random
/// (math.random, from the run's seed), take_firmware_lines (for the events), budget_spent
/// (the instruction budget's error once it is spent, else nil) and charge (work done in C,
/// counted against the budget).
std::span<const ApiEntry> ScenarioHostEntries();

/// Returns the value at `index` with its Lua type when it is a boolean, a number or a string
/// (read as it is: a numeric string stays a string); nothing for any other type.
std::optional<ScenarioValue> ScalarAt(lua_State* L, int index);

}  // namespace unimouse

#endif  // UNIMOUSE_SCENARIO_SCENARIO_API_H_
