// SPDX-License-Identifier: GPL-3.0-or-later
// The scenario prelude (prelude.lua), built into the library from its source at build time.
#ifndef UNIMOUSE_SCENARIO_PRELUDE_H_
#define UNIMOUSE_SCENARIO_PRELUDE_H_

#include <string_view>

namespace unimouse {

/// Returns the Lua source of the prelude: the sandbox, the sim API's Lua half and the host's
/// steps in Lua (see prelude.lua).
std::string_view PreludeSource();

}  // namespace unimouse

#endif  // UNIMOUSE_SCENARIO_PRELUDE_H_
