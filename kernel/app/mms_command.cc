// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse mms`: its options, and the viewer of its physics tier
#include "mms_command.h"

#include <memory>
#include <string>

#include "command_line.h"
#include "mms_run.h"
#include "session.h"
#include "transport_spec.h"
#include "viewer.h"

namespace unimouse {

void AddMmsCommand(CommandLine& cli) {
  auto mms = std::make_shared<MmsRunOptions>();
  CLI::App* mms_cmd = cli.app().add_subcommand(
      "mms", "run a program written for the mms simulator on the maze (docs/mms.md)");
  mms_cmd->add_option("--maze", mms->maze, "maze file or bundled maze name")->capture_default_str();
  mms_cmd->add_option("--out", mms->out_dir, "directory for result.json")->capture_default_str();
  mms_cmd
      ->add_option("--cell-time-s", mms->timing.cell_time_s,
                   "contest seconds per cell moved (a half-step costs half)")
      ->capture_default_str();
  mms_cmd
      ->add_option("--turn-time-s", mms->timing.turn_time_s,
                   "contest seconds per 90 degree turn (45 degrees cost half)")
      ->capture_default_str();
  mms_cmd->add_option("--time-limit-s", mms->time_limit_s, "the contest clock's limit")
      ->capture_default_str();
  mms_cmd
      ->add_option("--reply-timeout-s", mms->reply_timeout_s,
                   "wall seconds the program has to send each command line")
      ->capture_default_str();
  mms_cmd->add_option("--max-commands", mms->max_commands, "command lines before the run stops")
      ->capture_default_str();
  mms_cmd->add_flag("--realtime", mms->realtime, "wait each move's contest time on the wall clock");
  mms_cmd->add_flag("--until-exit", mms->until_exit,
                    "keep answering after the goal until the program exits or time runs out");
  mms_cmd->add_flag("--end-on-crash", mms->end_on_crash,
                    "a move into a wall ends the run (mms itself only replies crash)");
  mms_cmd->add_flag("--no-pictures", mms->no_pictures,
                    "no maze.png or maze.svg of what the program displayed");
  mms_cmd->add_option("program", mms->program, "the program and its arguments, after --");
  mms_cmd->add_option("--program-dir", mms->program_dir,
                      "the program's working directory (mms's Directory setting)");
  mms_cmd->add_option("--port", mms->port,
                      std::string("instead of a program: a board or relay speaking the "
                                  "protocol on ") +
                          link::TransportUsages(/*boards_only=*/true) +
                          ", its log on lines starting 'log '");
  mms_cmd
      ->add_option("--connect-timeout-s", mms->connect_timeout_s,
                   "wall seconds a --port peer has for its first command line")
      ->capture_default_str();
  mms_cmd->add_flag("--physical", mms->physical,
                    "the physics tier: each move driven on the simulated robot in MuJoCo, the "
                    "walls read by its sensors, the contest clock simulated time");
  mms_cmd->add_flag("--strict-contacts", mms->strict_contacts,
                    "with --physical: a move or turn carried out that grazed a wall replies crash "
                    "(by default ack, the contact counted in the result: an mms program takes "
                    "crash for a move that did not happen)");
  mms_cmd
      ->add_option("--maze-class", mms->maze_class,
                   "with --physical: the maze built classic (180 mm cells), half (90 mm) or auto "
                   "(half above 16 x 16), as the micromouse scenario's maze_class")
      ->capture_default_str();
  mms_cmd->add_flag("--centre-goal", mms->centre_goal,
                    "the maze's centre cells are the goal, as mms has it, instead of the goal "
                    "the maze file marks");
  mms_cmd->add_flag("--true-walls", mms->true_walls,
                    "with --physical: wall queries answered from the maze, not the sensors");
  mms_cmd->add_option("--robot", mms->robot, "with --physical: robot file or bundled robot name")
      ->capture_default_str();
  mms_cmd->add_option("--seed", mms->seed, "with --physical: the sensors' noise")
      ->capture_default_str();
  struct View {
    bool on = false;
    int frames = 0;
  };
  auto view = std::make_shared<View>();
  mms_cmd->add_flag("--view", view->on,
                    "with --physical: watch the robot in a window (the keys of run --view)");
  mms_cmd->add_option("--view-frames", view->frames,
                      "close the window after so many frames, saving the last as view.png");

  cli.Add(mms_cmd, [mms, view] {
    // the window opens with the robot's first step, so that a run without a display still
    // leaves its result.json
    std::unique_ptr<Viewer> viewer;
    MmsRunOptions options = *mms;
    if (view->on) {
      options.watch = [&](Session& session) {
        if (!viewer) {
          const std::string program = mms->program.empty() ? mms->port : mms->program[0];
          viewer = std::make_unique<Viewer>("unimouse: mms " + program, mms->out_dir, view->frames);
        }
        viewer->Watch(session);
      };
      options.watch_end = [&](Session& session, const std::string& ending) {
        if (viewer) viewer->Linger(session, ending);
      };
    }
    InstallInterruptHandlers();
    return RunMms(options);
  });
}

}  // namespace unimouse
