// SPDX-License-Identifier: GPL-3.0-or-later
// unimouse: a micromouse and mobile-robot simulator.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "commands.h"
#include "unimouse/errors.h"

int main(int argc, char** argv) {
  using namespace unimouse;
  CLI::App app{"unimouse " UNIMOUSE_VERSION ": a micromouse and mobile-robot simulator"};
  app.require_subcommand(1);
  app.set_version_flag("--version", UNIMOUSE_VERSION);
  std::string plugin_path;
  app.add_option("--plugin-path", plugin_path,
                 "extra plugin directories, ':'-separated, searched before UNIMOUSE_PLUGIN_PATH "
                 "and the installed plugins");

  RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "run a simulation headless and write a result");
  run_cmd->add_option("--robot", run.robot, "robot YAML file, or the name of a bundled robot")
      ->capture_default_str();
  run_cmd->add_option("--maze", run.maze, "maze file, a bundled maze's name, or none")
      ->capture_default_str();
  run_cmd->add_option("--duration", run.duration_s, "simulated seconds")->capture_default_str();
  run_cmd->add_option("--seed", run.seed, "seed of every random stream")->capture_default_str();
  run_cmd->add_option("--out", run.out_dir, "directory for result.json and other outputs")
      ->capture_default_str();

  std::string check_robot;
  CLI::App* check_cmd = app.add_subcommand("check", "validate a robot file without running it");
  check_cmd->add_option("robot", check_robot, "robot YAML file or bundled robot name")->required();

  CLI::App* plugins_cmd =
      app.add_subcommand("plugins", "list the component types found and their parameters");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitPassed : kExitBadInput;
  }

  run.plugin_path = plugin_path;
  try {
    if (run_cmd->parsed()) return RunCommand(run);
    if (check_cmd->parsed()) return CheckCommand(check_robot, plugin_path);
    if (plugins_cmd->parsed()) return PluginsCommand(plugin_path);
  } catch (const InputError& e) {
    std::fprintf(stderr, "unimouse: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const RuntimeFault& e) {
    std::fprintf(stderr, "unimouse: error: %s\n", e.what());
    return kExitRuntimeFault;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unimouse: error: %s\n", e.what());
    return kExitRuntimeFault;
  }
  return kExitBadInput;
}
