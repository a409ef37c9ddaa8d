// SPDX-License-Identifier: GPL-3.0-or-later
// The `unimouse` program's command line. Each subcommand adds its options beside its own code
// (AddRunCommand in commands.cc, AddMazeCommands in maze_commands.cc, ...), with what it does
// once they are read; main() is the list of them.
#ifndef UNIMOUSE_APP_COMMAND_LINE_H_
#define UNIMOUSE_APP_COMMAND_LINE_H_

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace unimouse {

class CommandLine {
 public:
  CommandLine();
  CLI::App& app() { return app_; }
  /// The global --plugin-path, once the command line is read.
  const std::string& plugin_path() const { return plugin_path_; }
  /// Runs `action` when `command` is the one given; it returns the program's exit code.
  void Add(CLI::App* command, std::function<int()> action);
  /// Reads the command line and runs the command given: its exit code, or 2 for bad input
  /// (an unknown command or option, an InputError) and 3 for a fault.
  int Run(int argc, char** argv);

 private:
  CLI::App app_;
  std::string plugin_path_;
  std::vector<std::pair<CLI::App*, std::function<int()>>> commands_;
};

}  // namespace unimouse

#endif  // UNIMOUSE_APP_COMMAND_LINE_H_
