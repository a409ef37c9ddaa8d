// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse mms` on the command line.
#ifndef UNIMOUSE_APP_MMS_COMMAND_H_
#define UNIMOUSE_APP_MMS_COMMAND_H_

namespace unimouse {

class CommandLine;

/// Adds `unimouse mms` (docs/mms.md).
void AddMmsCommand(CommandLine& cli);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_MMS_COMMAND_H_
