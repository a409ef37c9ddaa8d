// SPDX-License-Identifier: GPL-3.0-or-later
// A run as a library object: the robot, its firmware link, a scenario, the pictures, pacing and
// the record of the run, assembled from options. The command line, the viewer, benchmarks and
// tests all run through it:
//
//   auto session = Session::Open(options);   // throws InputError (exit 2), RuntimeFault (3)
//   while (!session->Over()) session->Step();
//   const RunRecord record = session->Finish();  // result.json written, however it ended
#ifndef UNIMOUSE_RUN_SESSION_H_
#define UNIMOUSE_RUN_SESSION_H_

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "firmware_beliefs.h"
#include "kernel.h"
#include "maze.h"
#include "plugin_registry.h"
#include "real_time_pacer.h"
#include "robot_spec.h"
#include "run_pictures.h"
#include "run_record.h"
#include "run_recording.h"
#include "scenario.h"
#include "trace_options.h"

namespace unimouse {

/// Makes SIGINT and SIGTERM end every run at its next step boundary: Over() is then true and
/// the result says "interrupted" (exit code 3). A second signal, for a run that cannot reach a
/// step boundary, ends the process at once with exit code 3.
void InstallInterruptHandlers();

/// The signal that asked runs to stop, or 0.
int InterruptSignal();

/// "interrupted by SIGINT" (or SIGTERM) once a signal asked runs to stop, else "".
std::string InterruptedBySignal();

/// One robot of a run with several, and what drives it: `unimouse run --robot A [--link ...]
/// --robot B ...`, each option about the robot before it.
struct SessionRobot {
  std::string robot = "unimouse";  ///< robot file or bundled robot name
  std::string name;                ///< "" the robot file's name, made distinct ("unimouse-2")
  std::string link;                ///< transport spec; "" none
  std::vector<std::string> link_sets;
  std::string firmware_profile;
  std::string controller;  ///< Lua controller file; "" none
  std::string start;  ///< "X,Y,H": a cell and a heading (N, E, S or W); "" as the scenario says
};

/// Most robots in one run.
inline constexpr int kMaxRobots = 8;

/// Everything a run is made of; what `unimouse run` takes, parsed.
struct SessionOptions {
  std::string robot = "unimouse";  ///< robot file or bundled robot name
  std::string maze =
      "japan2018";          ///< maze file, bundled name, or "none"; a scenario builds its own
  bool maze_given = false;  ///< the maze was named: a scenario runs in it (its `maze` parameter)
  double duration_s = 10;   ///< simulated seconds
  bool duration_given = false;  ///< false: a scenario's time limit (+1 s) decides
  uint64_t seed = 1;
  std::string out_dir = "out";
  std::string plugin_path;                   ///< extra plugin directories, ':'-separated
  const PluginRegistry* registry = nullptr;  ///< default: the plugins on the search path
  std::string link;                          ///< transport spec (transport_spec.h); "" none
  std::vector<std::string> link_sets;        ///< link parameters, "name=value"
  std::string firmware_profile;  ///< what the firmware expects ("unimousesim-0.1"); "" default
  TraceOptions trace;            ///< the trace loggers' rate and signals, or no trace
  std::string record = "light";  ///< the recording, run.mcap: off, light or full (docs/replay.md)
  std::string maze_class;  ///< without a scenario: "classic" or "half" builds the maze so; "" its
                           ///< size's class
  bool realtime = false;   ///< pace to the wall clock, even a firmware in lock-step (to watch)
  bool paced_by_caller = false;          ///< a viewer paces the run itself
  std::string scenario;                  ///< scenario file or bundled name; "" for none
  std::vector<std::string> sets;         ///< scenario parameters, "name=value"
  std::string controller;                ///< Lua controller file; "" for none
  PictureOptions pictures;               ///< pictures asked for
  std::vector<std::string> snapshot_on;  ///< scenario events that take a picture
  /// false: final.png whenever the machine can draw, though no picture was asked for
  bool only_asked_pictures = false;
  bool console = true;    ///< log lines also to stderr, with their sim time (detail with verbose)
  bool verbose = false;   ///< the console shows detail too (the firmware's reports, cell by cell)
  bool progress = false;  ///< a progress line on stderr (a terminal), rewritten in place
  bool driven_by_caller = false;  ///< the caller writes the robot's inputs between steps
  std::string start;              ///< the robot's start, as SessionRobot::start
  /// Two or more: every robot of the run, in place of robot, link, link_sets,
  /// firmware_profile, controller and start above.
  std::vector<SessionRobot> robots;
};

/// Returns the firmware link's component as a robot file would declare it, from the command
/// line (`--link`, `--firmware-profile`, `--link-set name=value`); its values are checked when
/// it is bound, as a robot file's are, and a later `--link-set` of a name wins.
ComponentSpec LinkComponent(const std::string& transport, const std::string& profile,
                            const std::vector<std::string>& sets);

/// Writes the result.json of a run that could not start (status "error"): why, the exit code,
/// and the traceback of a script error. An output directory that cannot be written is left
/// alone: the error itself is the one to report.
void WriteErrorResult(const SessionOptions& options, const std::string& error, int exit_code,
                      const std::string& traceback = "");

class ConsoleProgress;

class Session {
 public:
  /// Assembles a run and writes nothing but its log until it ends. A previous result.json in
  /// the output directory is removed first; when assembling fails, a result.json saying why is
  /// written before the error is thrown: InputError (exit 2) or RuntimeFault (exit 3).
  static std::unique_ptr<Session> Open(const SessionOptions& options);
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session();

  /// Advances one tick, with its pictures, paced to the wall clock where asked. A fault (a
  /// component, the scenario, the firmware or MuJoCo) ends the run: Over() is then true.
  void Step();
  /// Whether the run is over: out of time, decided by the scenario, faulted, or interrupted.
  bool Over() const;
  /// Ends the run once: the scenario's finish, the last pictures, every component's finish, the
  /// maze as the firmware saw it; writes result.json atomically and returns its record.
  /// `view`: what a viewer's window showed of the run, for the record.
  RunRecord Finish(std::optional<ViewRecord> view = std::nullopt);

  Kernel& kernel() { return *kernel_; }
  /// The first robot's file.
  const RobotSpec& robot() const { return robots_.front().spec; }
  /// What the firmware reported of the maze so far.
  const FirmwareBeliefs& beliefs() const { return beliefs_; }
  /// The HUD lines: the scenario's, or what a driver showed (ShowDisplay); else none.
  std::vector<std::string> hud() const;
  /// For a run driven by its caller (the mms physics tier): what the driver displays in place
  /// of a firmware's reports and a scenario's HUD. The pictures and the viewer draw it.
  void ShowDisplay(FirmwareBeliefs beliefs, std::vector<std::string> hud);
  /// Ends the run at this step boundary, as a signal would (status "interrupted", exit code 3),
  /// saying why: e.g. the viewer's window was closed.
  void Stop(const std::string& why);
  /// Why the run was interrupted (Stop, or a signal), or "" while it was not.
  std::string interruption() const;
  /// Calls `watcher` after every step from now on: a live viewer of a run that its caller steps
  /// (the mms physics tier) draws, paces and may Stop the run there.
  void SetStepWatcher(std::function<void(Session&)> watcher) { watcher_ = std::move(watcher); }
  /// The scenario's status and reason, or "" without a scenario.
  std::string verdict() const;
  /// Where the run takes place, for a console line: "in scenario x", "in maze y (16x16)".
  std::string where() const;

 private:
  explicit Session(const SessionOptions& options);
  void Assemble();
  void LoadRobots();
  void PlaceRobots(ScenarioWorld& world);
  void LogContacts();
  void CheckReportedCell(int robot, int x, int y);
  std::vector<std::string> RobotNames() const;
  void DrawFirmwareMaze();
  // the recording (run_recording.h): opened before the robots are built, fed at every step
  // boundary, closed after the result with the run's files attached
  void OpenRecording();
  void Record(const std::function<void(RunRecording&)>& write);
  void CloseRecording(const RunRecord& record, const nlohmann::json& result_json);

  // a robot of the run, as loaded, and what happened to it
  struct Robot {
    SessionRobot options;
    std::string file;
    std::string sha256;  // of the file, as the run read it
    RobotSpec spec;
    std::string name;  // as sim.robots() and the result give it
    std::optional<Pose2D> start;
    int64_t restarts = 0;  // times its firmware started over inside the run (the link's reports)
    DriverRecord driver;
    bool lost_reported = false;  // its firmware's cell and its own were seen to differ
    // the latest of each value its firmware reported, and whether the recording has them
    std::map<std::string, double> firmware_values;
    bool firmware_values_recorded = true;
  };
  std::vector<Robot> robots_;

  SessionOptions options_;
  std::optional<PluginRegistry> own_registry_;
  std::unique_ptr<Scenario> scenario_;
  std::string scenario_file_;
  std::string scenario_sha256_;
  std::unique_ptr<Maze> maze_;
  std::string maze_file_;
  std::optional<MazeRecord> maze_record_;  // with its hash, for the record
  double duration_s_ = 0;
  int64_t steps_ = 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> log_{nullptr, &std::fclose};
  std::unique_ptr<Kernel> kernel_;
  FirmwareBeliefs beliefs_;
  bool beliefs_recorded_ = true;  // whether the recording has beliefs_ as they are
  std::vector<std::string> recorded_hud_;
  // what components measured over the run (UNIMOUSE_REPORT_MEASURE), by component and name
  std::map<std::string, std::map<std::string, double>> measurements_;
  std::vector<std::string> warnings_;  // every warning logged, "component: text", for the record
  std::unique_ptr<RunPictures> pictures_;
  std::unique_ptr<RealTimePacer> pacer_;
  std::unique_ptr<ConsoleProgress> progress_;
  size_t logged_contacts_ = 0;
  std::unique_ptr<RunRecording> recording_;
  // a sample of the recording, and what changed since the last one
  void RecordSample();
  void AttachInputs();
  bool pace_ = false;
  std::string fault_;
  std::string interrupted_;  // by which signal, when
  std::string stopped_;      // why the caller stopped the run
  std::vector<std::string> shown_hud_;
  std::function<void(Session&)> watcher_;
  std::string no_pictures_;  // why not even final.png could be drawn
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace unimouse

#endif  // UNIMOUSE_RUN_SESSION_H_
