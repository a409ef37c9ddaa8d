// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse batch` on the command line.
#ifndef UNIMOUSE_APP_BATCH_COMMAND_H_
#define UNIMOUSE_APP_BATCH_COMMAND_H_

namespace unimouse {

class CommandLine;

/// Adds `unimouse batch run|plan|collect|job` (docs/batch.md).
void AddBatchCommands(CommandLine& cli);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_BATCH_COMMAND_H_
