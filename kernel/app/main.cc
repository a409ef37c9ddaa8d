// SPDX-License-Identifier: GPL-3.0-or-later
// unimouse: a micromouse and mobile-robot simulator. Each command adds its own options.
#include <csignal>

#include "batch_command.h"
#include "command_line.h"
#include "commands.h"
#include "firmware_command.h"
#include "fit_commands.h"
#include "maze_commands.h"
#include "mms_command.h"
#include "replay_command.h"

int main(int argc, char** argv) {
  using namespace unimouse;
  // a firmware or a reader that closes its end of a pipe is an error to report, not the end of
  // the process
  std::signal(SIGPIPE, SIG_IGN);
  CommandLine cli;
  AddRunCommand(cli);
  AddCheckCommand(cli);
  AddInformationCommands(cli);
  AddMazeCommands(cli);
  AddMmsCommand(cli);
  AddFirmwareCommands(cli);
  AddBatchCommands(cli);
  AddFitCommands(cli);
  AddReplayCommand(cli);
  return cli.Run(argc, argv);
}
