// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse mms`: runs a program written for the mms simulator as a child process, speaks the
// mms protocol with it over its stdin and stdout on the logic tier (MmsWorld), and writes
// result.json. Its stderr is passed through. Or the program runs elsewhere (an mms-arduino
// sketch on a board, a relay) and speaks over a pty, serial port or TCP, its log on lines that
// start "log ". docs/mms.md describes the statuses. maze.png shows what the program displayed.
#ifndef UNIMOUSE_MMS_MMS_RUN_H_
#define UNIMOUSE_MMS_MMS_RUN_H_

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mms_protocol.h"

namespace unimouse {

class Session;

struct MmsRunOptions {
  std::string maze = "japan2018";    ///< maze file or bundled maze name
  std::vector<std::string> program;  ///< the program and its arguments; or
  std::string program_dir;           ///< the program's working directory; "" for this one
  std::string port;                  ///< a board or relay: pty:LINK, serial:PATH@BAUD, tcp::PORT
  std::string out_dir = "out";
  MmsTiming timing;
  double time_limit_s = 600;        ///< the contest clock: the micromouse contest's 10 minutes
  double reply_timeout_s = 5;       ///< wall time the program has for each command line
  double connect_timeout_s = 60;    ///< wall time a --port peer has for its first line
  bool realtime = false;            ///< wait each move's contest time on the wall clock
  bool until_exit = false;          ///< keep running after the goal until the program exits
  bool end_on_crash = false;        ///< a move into a wall ends the run (contest rule)
  long max_commands = 10000000;     ///< command lines before the run is stopped
  bool physical = false;            ///< the physics tier: the moves on the simulated robot
  bool true_walls = false;          ///< physics tier: `wall*` from the maze, not the sensors
  bool strict_contacts = false;     ///< physics tier: a move that grazed a wall replies crash
  bool centre_goal = false;         ///< the maze's centre cells are the goal, as in mms
  std::string maze_class = "auto";  ///< physics tier: the maze built classic, half or by its size
  std::string robot = "unimouse";   ///< physics tier: robot file or bundled robot name
  uint64_t seed = 1;                ///< physics tier: the sensors' noise
  bool no_pictures = false;         ///< no maze.png and maze.svg
  /// physics tier: a live viewer, called after every simulated step (Session::SetStepWatcher),
  /// and once more when the run has ended, with its status and reason, before the run's record
  /// is written; it paces the run itself
  std::function<void(Session&)> watch;
  std::function<void(Session&, const std::string&)> watch_end;
};

/// Runs the program against the maze, writes out_dir/result.json, and returns the exit code:
/// 0 goal reached, 1 not reached (crash, contest time out, command limit; physics tier: the
/// robot stuck or off course), 2 bad input, 3 the program failed (exited early, crashed,
/// stopped sending commands) or the simulation did.
int RunMms(const MmsRunOptions& options);

}  // namespace unimouse

#endif  // UNIMOUSE_MMS_MMS_RUN_H_
