// SPDX-License-Identifier: GPL-3.0-or-later
// Scenarios: Lua 5.4 scripts that build a challenge's world, watch the run and decide pass or
// fail. A scenario file returns `sim.scenario { name, params, world, run, finish }`:
//
//   - params: names with defaults; `unimouse run --set name=value` overrides them;
//   - world(p): before physics exists, adds walls and boxes, loads a maze, places the robot;
//   - run(p): a coroutine resumed once per tick at the tick boundary; it waits on sim time
//     (sim.wait, sim.wait_until), reads the robot and signals, and ends with sim.pass/sim.fail;
//     handlers added with sim.on are called at the boundary before it resumes;
//   - finish(p, ended), optional: once the run is over, for last scores or a late decision.
//
// Sandboxed: no io, os, load, dofile or require; math.random is the run's seeded stream; print
// goes to the run's log; an instruction budget, one per scenario, stops a script that never
// yields, naming its file:line, and no pcall can catch it. Memory is bounded twice, through the
// state's allocator: what a script holds at once, and how much it may allocate between two
// yields (building strings is work the instruction count does not see). A script error stops the
// run with exit code 3, its Lua traceback kept. Every C++ function Lua calls crosses the Lua
// boundary of lua_call.h, and loading uses the Lua API only inside protected calls.
#ifndef UNIMOUSE_SCENARIO_SCENARIO_H_
#define UNIMOUSE_SCENARIO_SCENARIO_H_

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "kernel.h"
#include "lua_call.h"
#include "maze.h"
#include "rng.h"
#include "unimouse/errors.h"
#include "watchdog.h"
#include "world.h"

struct lua_State;
struct lua_Debug;

namespace unimouse {

class LuaCall;

/// The most memory a scenario's Lua state holds at once.
inline constexpr size_t kScenarioMemoryBytes = size_t{256} << 20;
/// The most a scenario may allocate in all between two calls from the host (two yields).
inline constexpr size_t kScenarioAllocationBytes = size_t{2} << 30;
/// Instructions a scenario may run between two calls from the host (two yields).
inline constexpr int kScenarioInstructionBudget = 20'000'000;
/// Instructions a scenario may run per simulated second once the run has started, on average
/// (beyond one budget): no script spends a whole budget at every tick.
inline constexpr double kScenarioInstructionsPerSecond = 100e6;

/// The most wall time one call into a scenario may take (work in C the budget cannot see).
inline constexpr double kScenarioCallWallTimeS = 10;

/// The scenario API's level: new functions carry the level they came with.
inline constexpr int kScenarioApiLevel = 5;

/// The most records (sim.record_add) a scenario reports in a run, all lists together.
inline constexpr size_t kMaxScenarioRecords = 10'000;
/// The most fields one record has.
inline constexpr size_t kMaxScenarioRecordFields = 32;
/// The longest text a record's field holds.
inline constexpr size_t kMaxScenarioRecordText_bytes = 1'000;
/// The most distinct scores (sim.score_set) a scenario reports in a run.
inline constexpr size_t kMaxScenarioScores = 1'000;
/// The most bytes a scenario writes to files (sim.file_append) in a run, all files together.
inline constexpr size_t kMaxScenarioFile_bytes = 64u << 20;
/// The most files a scenario writes in a run.
inline constexpr size_t kMaxScenarioFiles = 16;
/// The most events (sim.event) a scenario marks in a run; later ones are counted, not kept.
inline constexpr size_t kMaxScenarioEvents = 10'000;
/// The longest kind of an event: a word of lowercase letters, digits and _.
inline constexpr size_t kMaxScenarioEventKind_bytes = 32;
/// The longest text of an event, short of a log message; a longer one is cut, saying how long it
/// was.
inline constexpr size_t kMaxScenarioEventText_bytes = 500;

/// Returns every `sim.*` function with its signature, meaning and level, a line each.
std::string DescribeScenarioApi();

/// A script error: a RuntimeFault (exit 3) whose message is the error's first line, carrying
/// the whole Lua traceback.
class ScriptFault : public RuntimeFault {
 public:
  ScriptFault(const std::string& message, std::string traceback)
      : RuntimeFault(message), traceback_(std::move(traceback)) {}
  const std::string& traceback() const { return traceback_; }

 private:
  std::string traceback_;
};

/// What a scenario's world phase asked for.
struct ScenarioWorld {
  std::unique_ptr<Maze> maze;
  std::string maze_file;  ///< the file the maze was read from
  std::vector<StaticBox> boxes;
  std::optional<Pose2D> spawn;         ///< of the first robot
  std::map<int, Pose2D> robot_spawns;  ///< of others, by robot index (sim.robot_place)
};

/// A value as a scenario gave it, with its Lua type: a boolean, an integer, a float (a number
/// that is not an integer subtype, 1.0 included) or a string.
using ScenarioValue = std::variant<bool, int64_t, double, std::string>;

/// One record of a list a scenario reports (sim.record_add): field name -> value.
using ScenarioRecord = std::map<std::string, ScenarioValue>;

/// A moment of the run a scenario marks (sim.event): a run starts, the goal, a penalty.
struct ScenarioEvent {
  double time_s = 0;
  std::string kind;   ///< a word of lowercase letters, digits and _, at most 32
  std::string robot;  ///< the robot it concerns, "" for none
  std::string text;   ///< at most kMaxScenarioEventText_bytes, cut beyond
};

/// How a scenario ended.
struct ScenarioOutcome {
  std::string status = "running";  ///< passed, failed, or running (not decided)
  std::string reason;
  std::map<std::string, ScenarioValue> scores;  ///< each an integer or a float, as set
  /// The lists of records the scenario reported, by list name, each in the order added.
  std::map<std::string, std::vector<ScenarioRecord>> records;
};

class Scenario {
 public:
  /// Loads a scenario file with parameter overrides ("name" -> "value" from --set). Throws
  /// InputError for a missing file or a bad override (exit 2), RuntimeFault for a script error
  /// (exit 3). `on_hang`, if given, is the watchdog's expiry (see SetWatchdog), from loading on.
  /// Reads `--set` texts, "name=value" each, as overrides for Load; throws InputError for one
  /// without a name and an '='.
  static std::map<std::string, std::string> ParseOverrides(const std::vector<std::string>& sets);
  static std::unique_ptr<Scenario> Load(const std::string& path,
                                        const std::map<std::string, std::string>& overrides,
                                        uint64_t seed, Watchdog::Expiry on_hang = {});
  /// Runs a Lua file's top level in the scenario sandbox, starting nothing, and returns whether
  /// it returns a function: a controller (`--controller`) rather than a scenario. Throws
  /// ScriptFault for a script error, InputError for a file that cannot be read.
  static bool ReturnsFunction(const std::string& path);
  ~Scenario();

  const std::string& name() const { return name_; }
  /// Runs the world phase. Throws ScriptFault for a script error, InputError when a maze named
  /// by a parameter from the command line cannot be read.
  ScenarioWorld BuildWorld();
  /// Starts the run phase on a kernel: the coroutine runs at each tick boundary from now on.
  /// `controller`, if given, is a Lua file returning function(sim_time_s) called every tick
  /// after the scenario, with the same API, to drive the robot (tests, teaching).
  void Attach(Kernel& kernel, const std::string& controller = "");
  /// Same with a controller per robot of the kernel ("" for none): each controller's sim.*
  /// calls without a robot's name are about its own robot, and its signal names are its robot's.
  void Attach(Kernel& kernel, const std::vector<std::string>& controllers);
  /// The least number of robots the scenario runs with (its `robots` field; 1 by default).
  int min_robots() const { return min_robots_; }
  /// The names sim.robots() gives and sim.robot_* take, in the kernel's order; set before the
  /// world phase.
  void SetRobotNames(std::vector<std::string> names) { robot_names_ = std::move(names); }
  bool finished() const { return outcome_.status != "running"; }
  const ScenarioOutcome& outcome() const { return outcome_; }
  /// Parameters after overrides, as text.
  const std::map<std::string, std::string>& params() const { return param_text_; }
  /// Parameters after overrides, with their Lua types, for the result; a parameter of another
  /// type (a table) as its text.
  const std::map<std::string, ScenarioValue>& param_values() const { return param_values_; }
  /// The Lua type of each parameter's default: number, string or boolean.
  const std::map<std::string, std::string>& param_types() const { return declared_; }
  /// The scenario's time limit (parameter time_limit_s), or 0 for none.
  double time_limit_s() const { return time_limit_s_; }
  /// The lines a scenario shows on screen (sim.hud_set).
  const std::vector<std::string>& hud() const { return hud_; }
  /// The Lua traceback of the error that stopped the run; empty when none did.
  const std::string& traceback() const { return traceback_; }
  /// Takes a picture for sim.snapshot_save: file (relative to the run's output directory),
  /// camera, width, height; returns "" or why it could not.
  using PictureTaker = std::function<std::string(const std::string& file, const std::string& camera,
                                                 int width, int height)>;
  void SetPictureTaker(PictureTaker taker) { picture_taker_ = std::move(taker); }
  /// The run's output directory, where sim.file_append writes; none (the default): it writes
  /// nothing and says so.
  void SetOutputDirectory(std::string dir) { output_dir_ = std::move(dir); }
  /// Receives each event the scenario marks (sim.event), the first kMaxScenarioEvents of a run;
  /// the scenario logs each itself.
  using EventSink = std::function<void(const ScenarioEvent& event)>;
  void SetEventSink(EventSink sink) { event_sink_ = std::move(sink); }
  /// The events marked beyond kMaxScenarioEvents, which went nowhere.
  int64_t events_not_kept() const { return events_not_kept_; }
  /// What to do when one call into the scenario runs longer than `limit_s` of wall time, on
  /// the watchdog's thread, before the process ends with exit code 3 (watchdog.h). By default
  /// the limit is kScenarioCallWallTimeS and the reason goes to stderr.
  void SetWatchdog(double limit_s, Watchdog::Expiry expiry) {
    watchdog_.Configure(limit_s, std::move(expiry));
  }
  /// Saves a picture from `camera`, events/<kind>_<n>.png, each time the event `kind` happens
  /// (sim.on's kinds). Throws InputError for an unknown kind.
  void SnapshotOn(const std::string& kind, const std::string& camera, int width, int height);

  /// Once the run is over (decided, or out of time), calls the scenario's finish(params,
  /// {status, reason, time_s}) if it has one: it may add scores and decide an undecided run.
  /// Throws RuntimeFault on a script error.
  void Finish();

 private:
  static constexpr int kNoRef = -2;  // LUA_NOREF, checked in scenario.cc
  // the text and chunk name LoadChunk compiles next
  struct Chunk {
    std::string text;
    std::string name;
  };

  Scenario() = default;
  // the scenario whose Lua state `L` is, or a thread of it
  static Scenario& Of(lua_State* L);
  void Tick();
  // calls the function under its `nargs` arguments, leaving `nresults` results; a Lua error
  // throws Throw's fault. A fresh instruction budget for each call.
  void Call(int nargs, int nresults, const char* what);
  // calls the body `kStep` (see lua_call.h) as a Lua function on the `nargs` values on top, as
  // Call does: how the host uses the Lua API under protection
  template <int (*kStep)(LuaCall&)>
  void CallStep(int nargs, int nresults, const char* what);
  void ResetBudget();
  // runs the function under the `nargs` values on top of `thread` (lua_pcall with `handler`, or
  // lua_resume for the run coroutine), under the script's limits
  // `what` names the stage for the watchdog
  int RunScript(lua_State* thread, int nargs, int nresults, int handler, const char* what,
                int* nres = nullptr);
  // the error of a failed RunScript on top of `thread`: a memory error carries no message of
  // its own, so it is named by the limit it met
  std::string ErrorOf(lua_State* thread, int status) const;
  // counts `instructions` more, throwing the budget's error (placed at the script's line from
  // stack `level` up) once it is spent
  void Spend(lua_State* L, int level, int64_t instructions);
  // the budget's error once instructions or allocations are spent, else ""; a first call after
  // the allocations ran out places it at the script's line from stack `level` up
  const std::string& Spent(lua_State* L, int level);
  // keeps and logs a Lua error's traceback, then throws it as a ScriptFault whose message is its
  // first line (file:line)
  [[noreturn]] void Throw(const std::string& traceback, const char* what);
  // rethrows the ScriptFault being handled as an InputError when the input is at fault: a value
  // from the command line, or an unknown key given to a sim.* function while loading
  [[noreturn]] void RethrowWhileLoading(const ScriptFault& fault) const;

  // the host's steps and hooks, bodies run through the Lua boundary (lua_call.h)
  static int OpenSandbox(LuaCall& call);
  static int LoadChunk(LuaCall& call);
  static int KeepStages(LuaCall& call);
  static int ApplyOverrides(LuaCall& call);
  static int Traceback(LuaCall& call);
  static int SpendInstructions(LuaCall& call);
  static void CountInstructions(lua_State* L, lua_Debug* ar);

  LuaMemory memory_{kScenarioMemoryBytes, kScenarioAllocationBytes};
  Watchdog watchdog_{kScenarioCallWallTimeS};
  lua_State* L_ = nullptr;
  std::string file_;
  std::string name_;
  Chunk chunk_;
  int env_ref_ = kNoRef;       // the sandbox
  int dispatch_ref_ = kNoRef;  // the prelude's event dispatcher
  int inspect_ref_ = kNoRef;   // the prelude's reader of a scenario's table
  int apply_ref_ = kNoRef;     // the prelude's setter of overrides
  int params_ref_ = kNoRef;    // parameters after overrides
  int world_ref_ = kNoRef;     // the stages, nil when absent
  int run_ref_ = kNoRef;
  int finish_ref_ = kNoRef;
  int coroutine_ref_ = kNoRef;                    // the run coroutine
  std::vector<std::pair<int, int>> controllers_;  // robot index, controller function
  int current_robot_ = 0;  // the robot sim.* calls are about while a controller runs
  int min_robots_ = 1;
  std::vector<std::string> robot_names_;
  lua_State* coroutine_ = nullptr;
  bool started_ = false;
  bool finish_called_ = false;
  Kernel* kernel_ = nullptr;
  ScenarioWorld world_;
  ScenarioOutcome outcome_;
  std::map<std::string, std::string> declared_;   // parameter name -> its Lua type
  std::map<std::string, std::string> overrides_;  // --set, checked against declared_
  std::string bad_input_;    // why a value from the command line could not be used, if it could not
  std::string unknown_key_;  // the last unknown key a sim.* table argument was given, if one was
  std::map<std::string, std::string> param_text_;
  std::map<std::string, ScenarioValue> param_values_;
  size_t record_count_ = 0;  // all lists together
  // each list's field types (LUA_TNUMBER...), which every record of the list keeps
  std::map<std::string, std::map<std::string, int>> record_fields_;
  double time_limit_s_ = 0;
  std::vector<std::string> hud_;
  RngStream rng_;                 // math.random
  int64_t instructions_ = 0;      // since the host last called into Lua
  int64_t run_instructions_ = 0;  // since the run started
  std::string budget_error_;      // once the budget is spent: what every later hook raises
  std::unique_ptr<std::vector<Cell>> maze_goals_;  // of the maze the world loaded
  Cell maze_start_;
  std::string traceback_;
  std::vector<std::pair<double, std::string>> firmware_lines_;  // not yet handed to events
  // a firmware's restarts not yet handed to events: when, its count, which robot's
  struct Restart {
    double time_s;
    int count;
    int robot;
  };
  std::vector<Restart> firmware_restarts_;
  PictureTaker picture_taker_;
  std::string output_dir_;
  // the files sim.file_append has opened, by name, and the bytes written to all of them
  std::map<std::string, std::unique_ptr<std::ofstream>> files_;
  size_t file_bytes_ = 0;
  EventSink event_sink_;
  size_t events_kept_ = 0;  // sim.event's, up to kMaxScenarioEvents
  int64_t events_not_kept_ = 0;

  friend struct ScenarioApi;
};

}  // namespace unimouse

#endif  // UNIMOUSE_SCENARIO_SCENARIO_H_
