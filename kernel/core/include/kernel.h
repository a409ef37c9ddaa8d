// SPDX-License-Identifier: GPL-3.0-or-later
// The kernel: a world, the robot's components bound to it, and the one tick that advances them.
//
// Kernel::Step, the only place the tick order lives:
//   1. the boundary hook (scenario scripts): may move the robot or change signals
//   2. collision proxies follow the robot (see world.h)
//   3. mj_step1: kinematics, contacts and velocities for the current state
//   4. Sense of every due component, in YAML order; mjData is read-only
//   5. Actuate of every due component, in YAML order; writes controls
//   6. mj_step2: actuation, constraint forces, integration
#ifndef UNIMOUSE_CORE_KERNEL_H_
#define UNIMOUSE_CORE_KERNEL_H_

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact_watch.h"
#include "model.h"
#include "plugin_registry.h"
#include "robot_spec.h"
#include "state.h"

namespace unimouse {

/// Receives every log line at sim time time_s: level (UNIMOUSE_LOG_*), the component's name
/// and the message.
using LogSink = std::function<void(double time_s, int level, const std::string& component,
                                   const std::string& message)>;

/// Choices made per run rather than per robot.
/// Most warnings a component shows in a run; later ones are counted, and the count is logged
/// when the run finishes.
inline constexpr int kMaxWarningsShown = 100;
/// Most bytes of log lines (its own and its firmware's) a component shows in a run; later lines
/// are counted, not shown.
inline constexpr size_t kMaxLogShown_bytes = 1 << 20;
/// Longest message shown; a longer one is cut, saying how long it was.
inline constexpr size_t kMaxMessage_bytes = 1000;

struct KernelOptions {
  uint64_t seed = 1;
  std::string output_dir = ".";  ///< where components write their files
  std::optional<Pose2D> spawn;   ///< default: the maze's start, or the origin facing north
  LogSink log_sink;              ///< default: warnings and errors to stderr
  std::vector<StaticBox> boxes;  ///< more walls and obstacles, as a scenario adds
  /// false: components are created and bound but not started (no port, process or file is
  /// opened), as `unimouse check` does
  bool start_components = true;
  /// true: the robot file's own parameters may start a program or make a path, as if given on
  /// the command line (tests, and tools that wrote the file themselves); false for files from
  /// people the run does not trust
  bool trust_robot_file = false;
};

/// Wall time spent in each part of the tick since the last reset: where a run's time goes.
struct TickTimes {
  double scenario_s = 0;    ///< the boundary hook: scenario scripts
  double physics_s = 0;     ///< collision proxies, mj_step1, mj_step2
  double components_s = 0;  ///< every hook but those of the component that sets the pace
  double firmware_s = 0;    ///< the hooks of the component that set the pace: a link and the
                            ///< firmware it waits for in lock-step
};

/// Receives every typed report a component hands the host, with the component's name and the
/// robot it belongs to.
using ReportSink =
    std::function<void(const std::string& component, int robot, const unimouse_report&)>;

/// One robot of a run. With several, each has a distinct name: its components, signals, random
/// streams and physics names are then "name/..." and its files go to the output directory's
/// folder `name`; the only robot of a run has name "" and keeps the names of its file.
struct KernelRobot {
  RobotSpec spec;
  std::string name;
  std::optional<Pose2D> spawn;  ///< default: KernelOptions::spawn, else the maze's start
};

class Kernel {
 public:
  Kernel(const Kernel&) = delete;
  Kernel& operator=(const Kernel&) = delete;

  /// Builds the world, validates, creates and binds every component, and resets. Throws
  /// InputError with file:line:col.
  static std::unique_ptr<Kernel> Create(const RobotSpec& robot, const Maze* maze,
                                        const PluginRegistry& registry,
                                        const KernelOptions& options);
  /// Builds several robots in one world, each as above.
  static std::unique_ptr<Kernel> Create(const std::vector<KernelRobot>& robots, const Maze* maze,
                                        const PluginRegistry& registry,
                                        const KernelOptions& options);
  /// Same, with default options and the given seed.
  static std::unique_ptr<Kernel> Create(const RobotSpec& robot, const Maze* maze,
                                        const PluginRegistry& registry, uint64_t seed) {
    KernelOptions options;
    options.seed = seed;
    return Create(robot, maze, registry, options);
  }

  /// Returns to time 0: the robot at its spawn pose, fresh random streams, components reset.
  void Reset();
  /// Advances one physics step. Throws RuntimeFault when a component fails, MuJoCo reports an
  /// error, or physics diverges.
  void Step();
  /// Ends the run: every component's finish hook, so that nothing it holds is lost. Call it
  /// once, also after a RuntimeFault; a component failing here is reported, not thrown.
  void Finish();

  /// Logs a line as `source` at the current sim time, as components do.
  void Log(int level, const std::string& source, const std::string& message) {
    Emit(level, source, message);
  }

  /// Also hands every logged line to `listener` (a scenario's events), besides the log sink.
  void AddMessageListener(LogSink listener) { listeners_.push_back(std::move(listener)); }
  /// Hands every typed report (unimouse_report) to `listener`.
  void AddReportListener(ReportSink listener) { report_listeners_.push_back(std::move(listener)); }
  /// Whether a component said that the firmware sets the pace (lock-step) since the last reset.
  bool firmware_paced() const { return paced_count_ > 0; }
  /// Whether a component declared `trait` (UNIMOUSE_TRAIT_*) at bind.
  bool declared(int trait) const { return (model_.traits & trait) != 0; }
  /// Whether a component of robot `robot` declared `trait`.
  bool declared(int trait, int robot) const { return (model_.robot_traits[robot] & trait) != 0; }
  int robot_count() const { return static_cast<int>(model_.robot_names.size()); }
  /// A robot's name: "" for the only robot of a run.
  const std::string& robot_name(int robot) const { return model_.robot_names[robot]; }
  /// A robot's prefix of signal names: "" or "name/".
  const std::string& robot_prefix(int robot) const { return model_.robot_prefixes[robot]; }
  /// Returns where the wall time of the ticks since the last reset went.
  const TickTimes& tick_times() const { return tick_times_; }
  /// Each robot's contacts with walls and other robots since the last reset, as a person counts
  /// them (ContactWatch).
  const ContactWatch& contacts() const { return contacts_; }

  /// Runs at the start of every tick, before physics; scenario scripts live here.
  void SetBoundaryHook(std::function<void()> hook) { boundary_hook_ = std::move(hook); }

  const Model& model() const { return model_; }
  const mjModel& mj_model() const { return model_.mj(); }
  const World& world() const { return *model_.world; }
  /// Writable for placing the robot and moving the collision proxies.
  World& world() { return *model_.world; }
  State& state() { return *state_; }
  const State& state() const { return *state_; }
  double timestep_s() const { return model_.timestep_s(); }
  uint64_t seed() const { return seed_; }

 private:
  struct HookContext {
    Kernel* kernel;
    int component;
  };
  struct BindSession;

  struct StoredMessage {
    double time_s;
    int level;
    std::string source;
    std::string text;
  };

  explicit Kernel(const KernelOptions& options) : seed_(options.seed), options_(options) {}
  void BindComponent(int index);
  void StartComponent(int index);
  // runs one hook of component `index` with a fresh tick; `hook` is one of the type's pointers
  void RunHook(int index, void (*hook)(const void*, const unimouse_tick*));
  // runs one phase's hook of every due component; returns the wall time of the pace setter's
  double RunPhase(int64_t step,
                  void (*unimouse_component_type::*hook)(const void*, const unimouse_tick*));
  // applies the component's message budget, then stores and hands on what is shown
  void Emit(int level, const std::string& component, const std::string& message);
  void Store(int level, const std::string& component, const std::string& message);
  void ThrowIfFaulted();
  void ForgetSeenMessages();

  uint64_t seed_;
  KernelOptions options_;
  Model model_;
  std::unique_ptr<State> state_;
  // bind-time bookkeeping: which component writes, and first reads, each signal
  std::vector<int> signal_writer_;
  std::vector<int> signal_first_reader_;
  std::vector<std::vector<int>> signal_readers_;
  std::function<void()> boundary_hook_;
  std::vector<LogSink> listeners_;
  std::vector<ReportSink> report_listeners_;
  // the components that said their firmware sets the pace (lock-step), and how many they are
  std::vector<char> pace_setter_;
  int paced_count_ = 0;
  std::vector<std::string> output_dirs_;  // per robot: where its components write
  TickTimes tick_times_;
  ContactWatch contacts_{0};
  std::string fault_;
  // the run's messages, oldest first; what each component has already been shown of them
  std::deque<StoredMessage> messages_;
  std::vector<unimouse_message> message_views_;
  std::vector<size_t> message_cursor_;
  // what each source has shown and held back since the last reset
  struct MessageBudget {
    int warnings_shown = 0;
    size_t log_shown_bytes = 0;
    bool warnings_full = false;  // later warnings are held back
    bool log_full = false;       // later log lines are held back
    uint64_t held_back = 0;
  };
  std::map<std::string, MessageBudget> message_budgets_;
};

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_KERNEL_H_
