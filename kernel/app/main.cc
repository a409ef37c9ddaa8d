// SPDX-License-Identifier: GPL-3.0-or-later
// unimouse: a micromouse and mobile-robot simulator.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>

#include "batch.h"
#include "commands.h"
#include "firmware_command.h"
#include "fit_commands.h"
#include "install_paths.h"
#include "maze_commands.h"
#include "mms_run.h"
#include "plugin_registry.h"
#include "scenario.h"
#include "transport_spec.h"
#include "unimouse/errors.h"
#include "viewer.h"
#include "yaml_doc.h"

namespace {

// the link plugin's own words for its transports (its `transport` parameter), so that this help
// lists exactly the transports the installed link has
std::string LinkHelp() {
  const std::string fallback = "connect firmware (`unimouse plugins` lists the transports)";
  try {
    unimouse::PluginRegistry registry;
    registry.AddSearchPath(unimouse::PluginSearchPath(""));
    const unimouse::PluginRegistry::Entry* link = registry.Find("unimouse.link");
    for (int i = 0; link != nullptr && i < link->type->nparam; ++i) {
      const unimouse_param& p = link->type->params[i];
      if (std::string(p.name) == "transport" && p.doc != nullptr) {
        return std::string("connect firmware: ") + p.doc;
      }
    }
  } catch (const std::exception&) {
    // a broken plugin is reported when a command loads it, not in the help
  }
  return fallback;
}

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
      const std::string near = unimouse::NearestWord(token, names);
      const std::string where = current == &app ? "" : " of '" + current->get_name() + "'";
      return "unknown command '" + token + "'" + where +
             (near.empty() ? "" : "; did you mean '" + near + "'?");
    }
    current = next;
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace unimouse;
  // a firmware or a reader that closes its end of a pipe is an error to report, not the end of
  // the process
  std::signal(SIGPIPE, SIG_IGN);
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
  run_cmd->add_option("--seed", run.seed, "seed of every random stream")
      ->capture_default_str()
      // an unsigned parse would take -1 as 18446744073709551615
      ->check([](const std::string& text) {
        return text.find_first_not_of("0123456789") == std::string::npos
                   ? std::string()
                   : "the seed is a whole number, 0 or more";
      });
  run_cmd->add_option("--out", run.out_dir, "directory for result.json and other outputs")
      ->capture_default_str();
  run_cmd->add_option("--scenario", run.scenario,
                      "challenge to run: a scenario file, the name of a bundled one, or none "
                      "for the robot alone (without --scenario, --set, --controller and --link "
                      "the run is the contest driven by the bundled firmware)");
  run_cmd->add_option("--set", run.sets, "scenario parameter, name=value (repeatable)");
  run_cmd->add_option("--controller", run.controller,
                      "Lua file returning function(time_s) that drives the robot through sim.*");
  run_cmd->add_flag("--realtime", run.realtime,
                    "pace the simulation to the wall clock, even a firmware in lock-step, to "
                    "watch it (a board or a program on a link, from --link or the robot file, "
                    "is paced anyway until it turns lock-step on)");
  run_cmd->add_option("--link", run.link, LinkHelp());
  run_cmd->add_option("--link-set", run.link_sets,
                      "a link parameter, name=value, as `unimouse plugins` lists them for "
                      "unimouse.link (repeatable), e.g. --link-set failsafe_s=0");
  run_cmd->add_option("--firmware-profile", run.firmware_profile,
                      "what the firmware expects: unimouse (this project's library, the "
                      "default) or unimousesim-0.1 (built against the original UnimouseSim's "
                      "library: 1.0 m ToF scale, commands held while silent, no extensions)");

  run_cmd->add_option("--trace-period", run.trace_period_s,
                      "seconds between the rows of the trace (trace.csv, the robot file's "
                      "unimouse.logger, every 10 ms in the bundled robot); 0 for no trace");
  run_cmd->add_option("--trace-signals", run.trace_signals,
                      "the signals the trace records, comma-separated, instead of the robot "
                      "file's list");

  // pictures: none of these changes what is run
  run_cmd->add_option("--camera", run.camera, "camera of the pictures: top, chase or free")
      ->capture_default_str();
  run_cmd->add_option("--snapshot-size", run.snapshot_size, "size of the pictures, WIDTHxHEIGHT")
      ->capture_default_str();
  run_cmd->add_option("--snapshot-every", run.snapshot_every,
                      "a picture every so much sim time (1s, 250ms): snapshots/<time>s.png");
  run_cmd->add_option("--snapshot-at", run.snapshot_at,
                      "a picture at this sim time, e.g. 12.5 (repeatable)");
  run_cmd->add_option("--snapshot-on", run.snapshot_on,
                      "a picture at each scenario event: cell_entered, wall_contact, "
                      "gate_crossed, firmware_log (repeatable): events/<event>_<n>.png");
  run_cmd->add_flag("--snapshot-end", run.snapshot_end,
                    "final.png when the run ends, or exit 2 if the machine cannot draw (without "
                    "this flag final.png is taken whenever the machine can)");
  run_cmd->add_flag("--no-pictures", run.no_pictures, "not even final.png");
  run_cmd->add_option("--frames-fps", run.frames_fps,
                      "frames/NNNNNN.png at this many frames per sim second");
  run_cmd->add_option("--video", run.video, "an MP4 of the run in the output directory (ffmpeg)");
  run_cmd->add_option("--video-fps", run.video_fps, "frames per sim second of the video")
      ->capture_default_str();
  run_cmd->add_flag("--view", run.view,
                    "watch in a live 3D window: orbit, zoom, pause, step, speed, follow (press H)");
  run_cmd->add_option("--view-frames", run.view_frames,
                      "close the window after so many frames, saving the last as view.png");

  CheckOptions check;
  CLI::App* check_cmd =
      app.add_subcommand("check", "validate robot files and scenarios without running them");
  check_cmd
      ->add_option("files", check.targets,
                   "robot YAML files, scenario or controller .lua files, bundled robot or "
                   "scenario names, or directories (every .yaml and .lua inside). A robot's "
                   "components are created and bound; a scenario is loaded and its world built "
                   "around the bundled robot; a controller (a file that returns a function) is "
                   "loaded. Nothing is started or written. Each is reported; the exit code is the "
                   "worst")
      ->required();
  check_cmd->add_option("--set", check.sets,
                        "scenario parameter, name=value (repeatable), as `run --set` takes it");

  FitOptions fit_options;
  CLI::App* fit_cmd = app.add_subcommand(
      "fit", "fit a robot file's motor constants to a robot's sysid logs (docs/calibrate.md)");
  fit_cmd->add_option("robot", fit_options.robot, "robot YAML file, or the name of a bundled robot")
      ->required();
  fit_cmd->add_option("logs", fit_options.logs, "CSV logs of the sysid test pattern")->required();
  fit_cmd->add_option("--out", fit_options.out_dir, "directory for the fitted robot file")
      ->capture_default_str();
  FitOptions compare_options;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare", "replay a robot's sysid log on a robot file and say how far apart they are");
  compare_cmd->add_option("robot", compare_options.robot, "robot YAML file, or a bundled robot")
      ->required();
  compare_cmd->add_option("logs", compare_options.logs, "CSV logs of the sysid test pattern")
      ->required();

  CLI::App* plugins_cmd =
      app.add_subcommand("plugins", "list the component types found and their parameters");

  bool schema_markdown = false;
  CLI::App* schema_cmd = app.add_subcommand(
      "robot-schema", "list every key a robot file may give and every component's parameters");
  schema_cmd->add_flag("--markdown", schema_markdown,
                       "print the reference of docs/robots.md instead");

  CLI::App* api_cmd =
      app.add_subcommand("scenario-api", "list the sim.* functions scenarios can call");

  bool scenarios_markdown = false;
  CLI::App* scenarios_cmd = app.add_subcommand(
      "scenarios", "list the bundled scenarios and the parameters --set can change");
  scenarios_cmd->add_flag("--markdown", scenarios_markdown,
                          "print the table of docs/scenarios.md instead");

  MazeOptions maze;
  CLI::App* maze_cmd = app.add_subcommand(
      "maze", "maze tools: show, check, solve, explore, plot, convert, generate");
  maze_cmd->require_subcommand(1);
  auto with_files = [&](CLI::App* cmd) {
    cmd->add_option("mazes", maze.files,
                    "maze files, bundled maze names, or directories searched for *.txt")
        ->required();
  };
  auto with_outputs = [&](CLI::App* cmd) {
    cmd->add_flag("--json", maze.json, "print JSON instead of text");
    cmd->add_option("--csv", maze.csv, "write a one-line-per-maze summary to this CSV file");
  };
  CLI::App* show_cmd = maze_cmd->add_subcommand("show", "print mazes with size, start and goal");
  with_files(show_cmd);
  show_cmd->add_flag("--json", maze.json, "print JSON instead of text");
  CLI::App* check_cmd_maze = maze_cmd->add_subcommand("check", "validate maze files");
  with_files(check_cmd_maze);
  check_cmd_maze->add_flag("--strict", maze.strict,
                           "treat warnings (open perimeter, unreachable goal) as errors");
  with_outputs(check_cmd_maze);
  CLI::App* solve_cmd = maze_cmd->add_subcommand(
      "solve", "shortest paths by the modified and the traditional flood fill");
  with_files(solve_cmd);
  with_outputs(solve_cmd);
  solve_cmd
      ->add_option("--tie", maze.tie_rule,
                   "traditional flood fill tie rule: compass:<NESW order>, "
                   "relative:<FLRB order> or straight:<NESW order>")
      ->capture_default_str();
  CLI::App* explore_cmd =
      maze_cmd->add_subcommand("explore", "Adachi method 0 exploration, trip by trip");
  with_files(explore_cmd);
  with_outputs(explore_cmd);
  explore_cmd->add_option("--cell-time", maze.cell_time_s, "seconds per cell moved")
      ->capture_default_str();
  explore_cmd->add_option("--turn-time", maze.turn_time_s, "seconds per 90 degree turn")
      ->capture_default_str();
  explore_cmd->add_option("--plots", maze.plot_dir,
                          "write a PNG and an SVG of every trip into this directory");
  CLI::App* plot_cmd = maze_cmd->add_subcommand(
      "plot", "a top-down picture of a maze and its shortest path, PNG or SVG");
  plot_cmd->add_option("maze", maze.files, "maze file or bundled maze name")->required();
  plot_cmd->add_option("--out", maze.out, "FILE.png or FILE.svg")->required();
  plot_cmd->add_option("--path", maze.path, "modified (blue), traditional (orange), both or none")
      ->capture_default_str();
  plot_cmd->add_option("--tie", maze.tie_rule, "tie rule of the traditional flood fill")
      ->capture_default_str();
  plot_cmd->add_flag("--costs", maze.costs, "write each cell's distance to the goal in it");
  CLI::App* convert_cmd = maze_cmd->add_subcommand(
      "convert", "read a maze in any format (text, .num, binary .maz) and write the text format");
  convert_cmd->add_option("maze", maze.files, "maze file")->required();
  convert_cmd->add_option("--out", maze.out, "file to write instead of printing");
  CLI::App* generate_cmd = maze_cmd->add_subcommand(
      "generate", "a random maze under the classic rules, in the text format");
  generate_cmd->add_option("--size", maze.size, "WIDTHxHEIGHT")->capture_default_str();
  generate_cmd->add_option("--seed", maze.seed, "random seed")->capture_default_str();
  generate_cmd->add_option("--loops", maze.loops, "share of inner walls removed, 0 to 1")
      ->capture_default_str();
  generate_cmd->add_option("--out", maze.out, "file to write instead of printing");

  MmsRunOptions mms;
  CLI::App* mms_cmd = app.add_subcommand(
      "mms", "run a program written for the mms simulator on the maze (docs/mms.md)");
  mms_cmd->add_option("--maze", mms.maze, "maze file or bundled maze name")->capture_default_str();
  mms_cmd->add_option("--out", mms.out_dir, "directory for result.json")->capture_default_str();
  mms_cmd
      ->add_option("--cell-time-s", mms.timing.cell_time_s,
                   "contest seconds per cell moved (a half-step costs half)")
      ->capture_default_str();
  mms_cmd
      ->add_option("--turn-time-s", mms.timing.turn_time_s,
                   "contest seconds per 90 degree turn (45 degrees cost half)")
      ->capture_default_str();
  mms_cmd->add_option("--time-limit-s", mms.time_limit_s, "the contest clock's limit")
      ->capture_default_str();
  mms_cmd
      ->add_option("--reply-timeout-s", mms.reply_timeout_s,
                   "wall seconds the program has to send each command line")
      ->capture_default_str();
  mms_cmd->add_option("--max-commands", mms.max_commands, "command lines before the run stops")
      ->capture_default_str();
  mms_cmd->add_flag("--realtime", mms.realtime, "wait each move's contest time on the wall clock");
  mms_cmd->add_flag("--until-exit", mms.until_exit,
                    "keep answering after the goal until the program exits or time runs out");
  mms_cmd->add_flag("--end-on-crash", mms.end_on_crash,
                    "a move into a wall ends the run (mms itself only replies crash)");
  mms_cmd->add_flag("--no-pictures", mms.no_pictures,
                    "no maze.png or maze.svg of what the program displayed");
  mms_cmd->add_option("program", mms.program, "the program and its arguments, after --");
  mms_cmd->add_option("--program-dir", mms.program_dir,
                      "the program's working directory (mms's Directory setting)");
  mms_cmd->add_option("--port", mms.port,
                      std::string("instead of a program: a board or relay speaking the "
                                  "protocol on ") +
                          unimouse::link::TransportUsages(/*boards_only=*/true) +
                          ", its log on lines starting 'log '");
  mms_cmd
      ->add_option("--connect-timeout-s", mms.connect_timeout_s,
                   "wall seconds a --port peer has for its first command line")
      ->capture_default_str();
  mms_cmd->add_flag("--physical", mms.physical,
                    "the physics tier: each move driven on the simulated robot in MuJoCo, the "
                    "walls read by its sensors, the contest clock simulated time");
  mms_cmd->add_flag("--strict-contacts", mms.strict_contacts,
                    "with --physical: a move or turn carried out that grazed a wall replies crash "
                    "(by default ack, the contact counted in the result: an mms program takes "
                    "crash for a move that did not happen)");
  mms_cmd
      ->add_option("--maze-class", mms.maze_class,
                   "with --physical: the maze built classic (180 mm cells), half (90 mm) or auto "
                   "(half above 16 x 16), as the micromouse scenario's maze_class")
      ->capture_default_str();
  mms_cmd->add_flag("--centre-goal", mms.centre_goal,
                    "the maze's centre cells are the goal, as mms has it, instead of the goal "
                    "the maze file marks");
  mms_cmd->add_flag("--true-walls", mms.true_walls,
                    "with --physical: wall queries answered from the maze, not the sensors");
  mms_cmd->add_option("--robot", mms.robot, "with --physical: robot file or bundled robot name")
      ->capture_default_str();
  mms_cmd->add_option("--seed", mms.seed, "with --physical: the sensors' noise")
      ->capture_default_str();
  bool mms_view = false;
  int mms_view_frames = 0;
  mms_cmd->add_flag("--view", mms_view,
                    "with --physical: watch the robot in a window (the keys of run --view)");
  mms_cmd->add_option("--view-frames", mms_view_frames,
                      "close the window after so many frames, saving the last as view.png");

  FirmwareBuildOptions firmware;
  CLI::App* firmware_cmd =
      app.add_subcommand("firmware", "build a sketch written against the Arduino library");
  firmware_cmd->require_subcommand(1);
  CLI::App* firmware_build_cmd = firmware_cmd->add_subcommand(
      "build",
      "build a sketch for the PC (a program and a module, each run in lock-step by --link) or "
      "for the emulated board (an image for --link), docs/firmware.md");
  firmware_build_cmd->add_option("sketch", firmware.sketch, "sketch folder or .ino file")
      ->required();
  firmware_build_cmd->add_option(
      "--out", firmware.out_dir,
      "directory for the built files (default: the sketch's folder; the build tree goes "
      "in its .unimouse-build)");
  firmware_build_cmd
      ->add_option("--board", firmware.board, "pc, or mega2560 for the emulated board")
      ->capture_default_str();
  firmware_build_cmd->add_option("--name", firmware.name,
                                 "name of the built files (default: the sketch's)");

  batch::BatchOptions batch_run;
  std::string batch_out, batch_job_id;
  std::vector<std::string> batch_dirs;
  CLI::App* batch_cmd = app.add_subcommand(
      "batch",
      "many runs from a manifest: submissions x scenarios x mazes x seeds (docs/batch.md)");
  batch_cmd->require_subcommand(1);
  CLI::App* batch_run_cmd = batch_cmd->add_subcommand(
      "run", "run a manifest's jobs here, -j at a time, resuming where an earlier run stopped");
  batch_run_cmd->add_option("manifest", batch_run.manifest, "the manifest (YAML)")->required();
  batch_run_cmd->add_option("-j,--jobs", batch_run.workers, "jobs at once (default: one per core)")
      ->check(CLI::PositiveNumber);
  batch_run_cmd->add_option("--out", batch_run.out_dir, "directory for the jobs and results")
      ->capture_default_str();
  batch_run_cmd->add_flag("--force", batch_run.force, "run again the jobs already done");
  CLI::App* batch_plan_cmd = batch_cmd->add_subcommand(
      "plan", "write jobs.txt (a command line per job, for GNU parallel) and slurm-array.sh");
  batch_plan_cmd->add_option("manifest", batch_run.manifest, "the manifest (YAML)")->required();
  batch_plan_cmd->add_option("--out", batch_out, "directory for the plan, the jobs and results")
      ->required();
  CLI::App* batch_collect_cmd = batch_cmd->add_subcommand(
      "collect", "merge job directories into results.csv, results.json, summary.csv, junit.xml");
  batch_collect_cmd->add_option("dirs", batch_dirs, "directories holding job directories")
      ->required();
  batch_collect_cmd->add_option("--out", batch_out,
                                "directory for the results (default: the first directory)");
  CLI::App* batch_job_cmd = batch_cmd->add_subcommand(
      "job",
      "run one job of a manifest under its limits and write its job.json (what every line of a "
      "plan runs)");
  batch_job_cmd->add_option("manifest", batch_run.manifest, "the manifest (YAML)")->required();
  batch_job_cmd->add_option("id", batch_job_id, "the job's id: submission/scenario/maze/seed-N")
      ->required();
  batch_job_cmd->add_option("--out", batch_out, "the batch's directory (the job's is DIR/jobs/ID)")
      ->required();

  if (const std::string unknown = UnknownCommand(app, argc, argv); !unknown.empty()) {
    std::fprintf(stderr, "unimouse: error: %s\n", unknown.c_str());
    return kExitBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitPassed : kExitBadInput;
  }

  run.plugin_path = plugin_path;
  try {
    run.duration_given = run_cmd->get_option("--duration")->count() > 0;
    run.maze_given = run_cmd->get_option("--maze")->count() > 0;
    if (run_cmd->parsed()) {
      // the main job: no challenge and no driver chosen, so the contest with the bundled
      // micromouse firmware; the robot, the maze, the duration, the seed, the pacing and the
      // pictures change how it runs, not what runs. An open floor has no contest, and
      // `--scenario none` asks for the robot alone
      bool chosen = run.maze == "none";
      for (const char* option : {"--scenario", "--set", "--controller", "--link"}) {
        chosen = chosen || run_cmd->get_option(option)->count() > 0;
      }
      if (run.scenario == "none") run.scenario.clear();
      if (!chosen) {
        run.scenario = "micromouse";
        run.sets = {"end_on_log=done"};
        run.link = link::BundledFirmwareSpec(link::FirmwareHost::kInProcess, FirmwareDirectory(),
                                             "micromouse");
      }
      return RunCommand(run);
    }
    if (batch_cmd->parsed()) {
      // every job runs this very program
      const std::string program = std::filesystem::read_symlink("/proc/self/exe").string();
      batch_run.program = program;
      batch_run.version = UNIMOUSE_VERSION;
      if (batch_run_cmd->parsed()) return batch::RunBatch(batch_run);
      if (batch_plan_cmd->parsed()) return batch::PlanBatch(batch_run.manifest, batch_out, program);
      if (batch_collect_cmd->parsed()) {
        return batch::CollectBatch(batch_dirs, batch_out, UNIMOUSE_VERSION);
      }
      if (batch_job_cmd->parsed()) {
        return batch::RunBatchJob(batch_run.manifest, batch_job_id, batch_out, program,
                                  UNIMOUSE_VERSION);
      }
    }
    if (mms_cmd->parsed()) {
      // the window opens with the robot's first step, so that a run without a display still
      // leaves its result.json
      std::unique_ptr<Viewer> viewer;
      if (mms_view) {
        mms.watch = [&](Session& session) {
          if (!viewer) {
            const std::string program = mms.program.empty() ? mms.port : mms.program[0];
            viewer =
                std::make_unique<Viewer>("unimouse: mms " + program, mms.out_dir, mms_view_frames);
          }
          viewer->Watch(session);
        };
        mms.watch_end = [&](Session& session, const std::string& ending) {
          if (viewer) viewer->Linger(session, ending);
        };
      }
      InstallInterruptHandlers();
      return RunMms(mms);
    }
    if (firmware_build_cmd->parsed()) return FirmwareBuild(firmware);
    if (check_cmd->parsed()) {
      check.plugin_path = plugin_path;
      return CheckCommand(check);
    }
    if (fit_cmd->parsed()) {
      fit_options.plugin_path = plugin_path;
      return FitCommand(fit_options);
    }
    if (compare_cmd->parsed()) {
      compare_options.plugin_path = plugin_path;
      return CompareCommand(compare_options);
    }
    if (plugins_cmd->parsed()) return PluginsCommand(plugin_path);
    if (schema_cmd->parsed()) return RobotSchemaCommand(schema_markdown, plugin_path);
    if (scenarios_cmd->parsed()) return ScenariosCommand(scenarios_markdown);
    if (api_cmd->parsed()) {
      std::fputs(DescribeScenarioApi().c_str(), stdout);
      return kExitPassed;
    }
    if (show_cmd->parsed()) return MazeShow(maze);
    if (check_cmd_maze->parsed()) return MazeCheck(maze);
    if (solve_cmd->parsed()) return MazeSolve(maze);
    if (explore_cmd->parsed()) return MazeExplore(maze);
    if (plot_cmd->parsed()) return MazePlot(maze);
    if (convert_cmd->parsed()) return MazeConvert(maze);
    if (generate_cmd->parsed()) return MazeGenerate(maze);
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
