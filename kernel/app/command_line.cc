// SPDX-License-Identifier: GPL-3.0-or-later
#include "command_line.h"

#include <cstdio>
#include <exception>

#include "unimouse/errors.h"
#include "yaml_doc.h"

namespace unimouse {
namespace {

// CLI11 takes a misspelt command for a stray argument ("A subcommand is required") and answers
// `NAME --help` with the parent's help and exit code 0: walk the command words first, and name
// the first one that is not a command, with the nearest command's name
std::string UnknownCommand(CLI::App& app, int argc, char** argv) {
  CLI::App* current = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string token = argv[i];
    if (token == "--") break;
    if (token.size() > 1 && token[0] == '-') {
      // an option's value is not a command word
      const CLI::Option* option = current->get_option_no_throw(token);
      if (option != nullptr && option->get_items_expected_max() > 0) ++i;
      continue;
    }
    const std::vector<CLI::App*> commands = current->get_subcommands({});
    if (commands.empty()) break;
    CLI::App* next = nullptr;
    std::vector<std::string> names;
    for (CLI::App* command : commands) {
      names.push_back(command->get_name());
      if (command->get_name() == token) next = command;
    }
    if (next == nullptr) {
      const std::string near = NearestWord(token, names);
      const std::string where = current == &app ? "" : " of '" + current->get_name() + "'";
      return "unknown command '" + token + "'" + where +
             (near.empty() ? "" : "; did you mean '" + near + "'?");
    }
    current = next;
  }
  return "";
}

}  // namespace

CommandLine::CommandLine()
    : app_("unimouse " UNIMOUSE_VERSION ": a micromouse and mobile-robot simulator") {
  app_.require_subcommand(1);
  app_.set_version_flag("--version", UNIMOUSE_VERSION);
  app_.add_option("--plugin-path", plugin_path_,
                  "extra plugin directories, ':'-separated, searched before UNIMOUSE_PLUGIN_PATH "
                  "and the installed plugins");
}

void CommandLine::Add(CLI::App* command, std::function<int()> action) {
  commands_.emplace_back(command, std::move(action));
}

int CommandLine::Run(int argc, char** argv) {
  if (const std::string unknown = UnknownCommand(app_, argc, argv); !unknown.empty()) {
    std::fprintf(stderr, "unimouse: error: %s\n", unknown.c_str());
    return kExitBadInput;
  }
  try {
    app_.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app_.exit(e);
    return code == 0 ? kExitPassed : kExitBadInput;
  }
  try {
    for (const auto& [command, action] : commands_) {
      if (command->parsed()) return action();
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "unimouse: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unimouse: error: %s\n", e.what());
    return kExitRuntimeFault;
  }
  return kExitBadInput;
}

}  // namespace unimouse
