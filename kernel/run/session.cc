// SPDX-License-Identifier: GPL-3.0-or-later
#include "session.h"

#include <unistd.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <variant>

#include "install_paths.h"
#include "maze_explorer.h"
#include "maze_plot.h"
#include "result_record.h"
#include "sha256.h"
#include "transport_spec.h"
#include "unimouse/errors.h"
#include "unimouse/plugin_abi.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

// a scalar YAML node that says where it came from: a command-line option
YamlNode Scalar(const std::string& text, const std::string& option) {
  YamlNode node;
  node.kind = YamlNode::Kind::kScalar;
  node.scalar = text;
  node.location = {option, 0, 0};
  return node;
}

// seconds with the three decimals of a stopwatch
std::string Seconds3(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", seconds);
  return text;
}

// a scenario's value in the result, with its Lua type
nlohmann::json ValueJson(const ScenarioValue& value) {
  return std::visit([](const auto& v) { return nlohmann::json(v); }, value);
}

template <class Map>
nlohmann::json ValuesJson(const Map& values) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : values) out[name] = ValueJson(value);
  return out;
}

// the value a map of YAML scalars gives `key` last (a --link-set wins over --link), or ""
std::string LastScalar(const YamlNode& map, const std::string& key) {
  std::string value;
  for (const YamlEntry& entry : map.entries) {
    if (entry.first.scalar == key) value = entry.second.scalar;
  }
  return value;
}

// the default of a component type's string parameter, as its plugin declares it
std::string DefaultOf(const PluginRegistry& registry, const std::string& type,
                      const std::string& param) {
  const PluginRegistry::Entry* entry = registry.Find(type);
  for (int i = 0; entry != nullptr && i < entry->type->nparam; ++i) {
    const unimouse_param& p = entry->type->params[i];
    if (param == p.name && p.default_string != nullptr) return p.default_string;
  }
  return "";
}

// who drives the robot: a controller file, a firmware over a link (from --link or the robot
// file), both, or neither; each file the run started with its SHA-256
nlohmann::json DriverJson(const SessionOptions& options, const RobotSpec& robot,
                          const PluginRegistry& registry) {
  nlohmann::json driver = {{"controller", nullptr}, {"link", nullptr}};
  if (!options.controller.empty()) driver["controller"] = FileIdentity(options.controller);
  for (const ComponentSpec& c : robot.components) {
    if (c.type != "unimouse.link") continue;
    const std::string spec = LastScalar(c.params, "transport");
    const std::string profile = LastScalar(c.params, "profile");
    // a board's firmware is not on this PC
    const link::TransportSpec parsed = link::ParseTransportSpec(spec);
    driver["link"] = {
        {"transport", parsed.kind->scheme},
        {"spec", spec},
        {"profile", profile.empty() ? DefaultOf(registry, c.type, "profile") : profile},
        {"firmware",
         parsed.firmware.empty() ? nlohmann::json(nullptr) : FileIdentity(parsed.firmware)}};
  }
  return driver;
}

volatile std::sig_atomic_t interrupt_signal = 0;

void OnInterrupt(int signal) {
  // a second signal: the run did not reach a step boundary in time
  if (interrupt_signal != 0) ::_exit(kExitRuntimeFault);
  interrupt_signal = signal;
}

}  // namespace

ComponentSpec LinkComponent(const std::string& transport, const std::string& profile,
                            const std::vector<std::string>& sets) {
  ComponentSpec link;
  link.type = "unimouse.link";
  link.name = "link";
  link.location = {"--link " + transport, 0, 0};
  link.params.kind = YamlNode::Kind::kMap;
  link.params.location = link.location;
  const std::string option = link.location.file;
  link.params.entries.emplace_back(Scalar("transport", option), Scalar(transport, option));
  if (!profile.empty()) {
    const std::string where = "--firmware-profile " + profile;
    link.params.entries.emplace_back(Scalar("profile", where), Scalar(profile, where));
  }
  for (const std::string& set : sets) {
    const size_t eq = set.find('=');
    UNIMOUSE_THROW_UNLESS(eq != std::string::npos && eq > 0,
                          "--link-set " + set + ": write name=value");
    const std::string where = "--link-set " + set;
    link.params.entries.emplace_back(Scalar(set.substr(0, eq), where),
                                     Scalar(set.substr(eq + 1), where));
  }
  return link;
}

void InstallInterruptHandlers() {
  struct sigaction action = {};
  action.sa_handler = OnInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int InterruptSignal() { return interrupt_signal; }

std::string InterruptedBySignal() {
  if (interrupt_signal == 0) return "";
  return std::string("interrupted by ") + (interrupt_signal == SIGINT ? "SIGINT" : "SIGTERM");
}

void WriteErrorResult(const SessionOptions& options, const std::string& error, int exit_code,
                      const std::string& traceback) {
  nlohmann::json record = NewResultRecord("run");
  record.update(
      {{"status", "error"}, {"error", error}, {"exit_code", exit_code}, {"seed", options.seed}});
  if (!traceback.empty()) record["traceback"] = traceback;
  try {
    WriteResultRecord(options.out_dir, record);
  } catch (const std::exception&) {
    // an output directory that cannot be written: the error itself is the one to report
  }
}

std::unique_ptr<Session> Session::Open(const SessionOptions& options) {
  std::unique_ptr<Session> session(new Session(options));
  std::error_code ec;
  fs::remove(fs::path(options.out_dir) / "result.json", ec);
  try {
    session->Assemble();
  } catch (const std::exception& e) {
    // a run that could not start says so where its result would be
    const bool bad_input = dynamic_cast<const InputError*>(&e) != nullptr;
    const auto* script = dynamic_cast<const ScriptFault*>(&e);
    WriteErrorResult(options, e.what(), bad_input ? kExitBadInput : kExitRuntimeFault,
                     script != nullptr ? script->traceback() : "");
    throw;
  }
  return session;
}

Session::~Session() = default;

void Session::Assemble() {
  const SessionOptions& o = options_;
  UNIMOUSE_THROW_UNLESS(o.duration_s > 0 && std::isfinite(o.duration_s),
                        "--duration must be a positive number of seconds");
  robot_file_ = ResolveDataFile(o.robot, "robots/", ".yaml");
  robot_ = LoadRobotSpec(robot_file_);
  ApplyTraceOptions(o.trace, robot_);
  identity_["robot"] = robot_file_;
  identity_["robot_name"] = robot_.name;
  identity_["robot_sha256"] = FileSha256(robot_file_);
  UNIMOUSE_THROW_UNLESS((o.link_sets.empty() && o.firmware_profile.empty()) || !o.link.empty(),
                        "--link-set and --firmware-profile go with --link");
  if (!o.link.empty()) {
    robot_.components.push_back(
        LinkComponent(link::ResolveBundledFirmware(o.link, FirmwareDirectory()), o.firmware_profile,
                      o.link_sets));
  }

  // a scenario builds its own world
  ScenarioWorld world;
  duration_s_ = o.duration_s;
  if (!o.scenario.empty()) {
    std::map<std::string, std::string> overrides = Scenario::ParseOverrides(o.sets);
    scenario_file_ = ResolveDataFile(o.scenario, "scenarios/", ".lua");
    // a script stuck in C for good: the process ends, and its result says why
    const auto on_hang = [this](const std::string& why) {
      WriteErrorResult(options_, why, kExitRuntimeFault, "");
    };
    scenario_ = Scenario::Load(scenario_file_, overrides, o.seed, on_hang);
    if (o.maze_given) {
      // a scenario's maze is its parameter `maze`: --maze sets it, as --set maze= would
      UNIMOUSE_THROW_UNLESS(scenario_->params().contains("maze"),
                            "--maze " + o.maze + ": scenario '" + scenario_->name() +
                                "' builds its own world and has no maze parameter");
      UNIMOUSE_THROW_UNLESS(!overrides.contains("maze") || overrides["maze"] == o.maze,
                            "--maze " + o.maze + " and --set maze=" + overrides["maze"] +
                                " name different mazes: give one");
      overrides["maze"] = o.maze;
      scenario_ = Scenario::Load(scenario_file_, overrides, o.seed, on_hang);
    }
    scenario_sha256_ = FileSha256(scenario_file_);
    world = scenario_->BuildWorld();
    maze_ = std::move(world.maze);
    maze_file_ = world.maze_file;
    // a second beyond the limit lets the scenario give its own reason
    if (!o.duration_given && scenario_->time_limit_s() > 0) {
      duration_s_ = scenario_->time_limit_s() + 1;
    }
  } else {
    UNIMOUSE_THROW_UNLESS(o.sets.empty() && o.controller.empty(),
                          "--set and --controller go with --scenario");
    if (o.maze != "none") {
      maze_file_ = ResolveDataFile(o.maze, "mazes/", ".txt");
      maze_ = std::make_unique<Maze>(LoadMaze(maze_file_));
      if (!o.maze_class.empty()) {
        maze_->set_class(o.maze_class == "half" ? MazeClass::kHalfSize : MazeClass::kClassic);
      }
    }
  }
  SetMazeIdentity(identity_, maze_file_, maze_.get());
  UNIMOUSE_THROW_UNLESS(o.snapshot_on.empty() || scenario_,
                        "--snapshot-on watches a scenario's events: give --scenario");
  const PluginRegistry* registry = o.registry;
  if (registry == nullptr) {
    own_registry_.emplace();
    own_registry_->AddSearchPath(PluginSearchPath(o.plugin_path));
    registry = &*own_registry_;
  }

  // every message goes into the run's log, line by line, and to the console with its sim time
  fs::create_directories(o.out_dir);
  const std::string log_path = (fs::path(o.out_dir) / "log.txt").string();
  log_.reset(std::fopen(log_path.c_str(), "w"));
  UNIMOUSE_THROW_UNLESS(log_ != nullptr, log_path + ": cannot write the run's log");
  KernelOptions kernel_options;
  kernel_options.seed = o.seed;
  kernel_options.output_dir = o.out_dir;
  kernel_options.boxes = std::move(world.boxes);
  kernel_options.spawn = world.spawn;
  kernel_options.log_sink = [this](double time_s, int level, const std::string& component,
                                   const std::string& message) {
    const char* kind = level == UNIMOUSE_LOG_ERROR     ? "error: "
                       : level == UNIMOUSE_LOG_WARNING ? "warning: "
                                                       : "";
    if (options_.console) {
      std::fprintf(stderr, "[%9.3f s] %s: %s%s\n", time_s, component.c_str(), kind,
                   message.c_str());
    }
    std::fprintf(log_.get(), "%.6f\t%s\t%s%s\n", time_s, component.c_str(), kind, message.c_str());
    if (level == UNIMOUSE_LOG_WARNING) warnings_.push_back(component + ": " + message);
    std::fflush(log_.get());
  };
  kernel_ = Kernel::Create(robot_, maze_.get(), *registry, kernel_options);
  kernel_->AddReportListener([this](const std::string& component, const unimouse_report& report) {
    if (report.kind == UNIMOUSE_REPORT_MEASURE && report.name != nullptr) {
      measurements_[component][report.name] = report.value;
    } else {
      beliefs_.Apply(report);
    }
  });
  if (scenario_) scenario_->Attach(*kernel_, o.controller);
  identity_["driver"] = DriverJson(o, robot_, *registry);
  // what drives the robot is what its components declared, wherever they came from (--link or
  // the robot file); said at once, so that a run meant to test something does not pass quietly
  // doing nothing
  const bool firmware = kernel_->declared(UNIMOUSE_TRAIT_FIRMWARE);
  if (!scenario_ && !firmware && !o.driven_by_caller) {
    kernel_->Log(UNIMOUSE_LOG_WARNING, "run",
                 "nothing drives the robot (no --scenario, --controller or --link): it stands "
                 "still; `unimouse run` with no options runs the contest with the bundled "
                 "firmware");
  } else if (!o.controller.empty() && firmware) {
    kernel_->Log(UNIMOUSE_LOG_WARNING, "run",
                 "both --controller and a firmware link drive the robot: the firmware's "
                 "commands overwrite the controller's whenever they arrive");
  }

  // the pictures asked for; without any, final.png whenever the machine can draw
  if (o.pictures.Any() || o.only_asked_pictures) {
    pictures_ = std::make_unique<RunPictures>(*kernel_, o.pictures, &beliefs_, o.out_dir);
  } else {
    PictureOptions final_only = o.pictures;
    final_only.at_end = true;
    try {
      pictures_ = std::make_unique<RunPictures>(*kernel_, final_only, &beliefs_, o.out_dir);
    } catch (const RenderUnavailable& e) {
      no_pictures_ = e.what();
      pictures_ = std::make_unique<RunPictures>(*kernel_, o.pictures, &beliefs_, o.out_dir);
    }
  }
  pictures_->SetHudSource([this] { return hud(); });
  if (scenario_) {
    scenario_->SetPictureTaker(
        [this](const std::string& file, const std::string& camera, int width, int height) {
          return pictures_->Save(file, camera, width, height);
        });
    scenario_->SetOutputDirectory(o.out_dir);
    for (const auto& kind : o.snapshot_on) {
      scenario_->SnapshotOn(kind, o.pictures.camera, o.pictures.width, o.pictures.height);
    }
  }

  steps_ = std::llround(duration_s_ / kernel_->timestep_s());
  // a board lives on the wall clock, from --link or the robot file alike; firmware in lock-step
  // sets the pace itself
  pace_ = !o.paced_by_caller && (o.realtime || kernel_->declared(UNIMOUSE_TRAIT_WALL_CLOCK));
  pacer_ = std::make_unique<RealTimePacer>(kernel_->timestep_s());
  start_ = std::chrono::steady_clock::now();
}

void Session::Step() {
  if (Over()) return;
  try {
    kernel_->Step();
    pictures_->AfterStep();
  } catch (const RuntimeFault& e) {
    fault_ = e.what();
    return;
  }
  if (watcher_) watcher_(*this);
  // firmware in lock-step sets the pace itself, unless the wall clock was asked for to watch it
  if (pace_ && (options_.realtime || !kernel_->firmware_paced())) {
    pacer_->Wait(kernel_->state().step());
  }
}

bool Session::Over() const {
  return !fault_.empty() || !stopped_.empty() || InterruptSignal() != 0 ||
         kernel_->state().step() >= steps_ || (scenario_ && scenario_->finished());
}

std::vector<std::string> Session::hud() const { return scenario_ ? scenario_->hud() : shown_hud_; }

void Session::ShowDisplay(FirmwareBeliefs beliefs, std::vector<std::string> hud) {
  beliefs_ = std::move(beliefs);
  shown_hud_ = std::move(hud);
}

void Session::Stop(const std::string& why) {
  if (stopped_.empty()) stopped_ = why;
}

std::string Session::interruption() const {
  return stopped_.empty() ? InterruptedBySignal() : stopped_;
}

std::string Session::verdict() const {
  if (!fault_.empty()) return "error: " + fault_;
  if (!stopped_.empty()) return "interrupted: " + stopped_;
  if (InterruptSignal() != 0) return "interrupted";
  if (!scenario_) return "";
  const ScenarioOutcome& o = scenario_->outcome();
  return o.status + (o.reason.empty() ? "" : ": " + o.reason);
}

std::string Session::where() const {
  if (scenario_) return "in scenario " + scenario_->name();
  if (maze_) {
    return "in maze " + options_.maze + " (" + std::to_string(maze_->width()) + "x" +
           std::to_string(maze_->height()) + ")";
  }
  return "on an open floor";
}

// the maze as the firmware reported it on its debug channels: cells it knows (with their true
// walls dark), cells it visited, the walls it believes in, the path it last planned
void Session::DrawFirmwareMaze() {
  const Maze& maze = *maze_;
  WallKnowledge knowledge(maze);
  auto sense = [&](Cell c) {
    if (maze.Contains(c)) knowledge.Sense(maze, c);
  };
  for (const auto& [cell, walls] : beliefs_.walls) sense({cell.first, cell.second});
  for (const Cell& c : beliefs_.visited) sense(c);
  MazePicture picture;
  picture.maze = &maze;
  picture.knowledge = &knowledge;
  picture.beliefs = &beliefs_;
  picture.closed_path = DescribeRoute(beliefs_.path, maze.start_heading());
  const fs::path base = fs::path(options_.out_dir) / "maze";
  WriteMazePicture(picture, base.string() + ".png");
  WriteMazePicture(picture, base.string() + ".svg");
}

SessionResult Session::Finish(const nlohmann::json& extra) {
  UNIMOUSE_DEMAND(!finished_);
  finished_ = true;
  // a signal stops the run between two steps: what the result says, and exit code 3
  if (const std::string why = interruption(); !why.empty() && fault_.empty()) {
    interrupted_ = why + " at " + Seconds3(kernel_->state().data().time) + " s";
  }
  try {
    if (scenario_ && fault_.empty() && interrupted_.empty()) scenario_->Finish();
  } catch (const RuntimeFault& e) {
    fault_ = e.what();
  }
  pictures_->Finish();
  kernel_->Finish();
  // drawn only from what a firmware reported: no connection, no picture of its beliefs
  const bool firmware_maze =
      maze_ && kernel_->declared(UNIMOUSE_TRAIT_FIRMWARE) && !beliefs_.empty();
  if (firmware_maze) DrawFirmwareMaze();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();

  // the run's record is written whatever happened to the run
  const mjData& d = kernel_->state().data();
  const Pose2D pose = kernel_->world().RobotPose(d);
  nlohmann::json r = NewResultRecord("run");
  r.update(identity_);
  r["seed"] = options_.seed;
  r["duration_s"] = duration_s_;
  r["status"] = !fault_.empty() ? "fault" : !interrupted_.empty() ? "interrupted" : "completed";
  if (!fault_.empty()) r["error"] = fault_;
  if (!interrupted_.empty()) r["error"] = interrupted_;
  r["sim_time_s"] = d.time;
  r["steps"] = kernel_->state().step();
  r["wall_time_s"] = wall_s;
  r["real_time_factor"] = wall_s > 0 ? d.time / wall_s : 0.0;
  const TickTimes& t = kernel_->tick_times();
  r["wall_time_split_s"] = {{"physics", t.physics_s},
                            {"components", t.components_s},
                            {"firmware", t.firmware_s},
                            {"scenario", t.scenario_s}};
  r["firmware_paced"] = kernel_->firmware_paced();
  r["robot_pose"] = {{"x_m", pose.x_m}, {"y_m", pose.y_m}, {"yaw_rad", pose.yaw_rad}};
  r["collision_proxy_overflows"] = kernel_->world().proxy_overflows();
  SessionResult result;
  const bool ended = fault_.empty() && interrupted_.empty();
  result.exit_code = ended ? kExitPassed : kExitRuntimeFault;
  if (scenario_) {
    ScenarioOutcome outcome = scenario_->outcome();
    if (outcome.status == "running") {
      outcome.status = !fault_.empty() ? "error" : !interrupted_.empty() ? "interrupted" : "failed";
      outcome.reason = !fault_.empty() ? fault_
                       : !interrupted_.empty()
                           ? interrupted_
                           : "not decided when the run ended at " + Seconds3(d.time) + " s";
    }
    nlohmann::json records = nlohmann::json::object();
    for (const auto& [list, rows] : outcome.records) {
      for (const ScenarioRecord& row : rows) records[list].push_back(ValuesJson(row));
    }
    r["scenario"] = {{"name", scenario_->name()},
                     {"file", scenario_file_},
                     {"sha256", scenario_sha256_},
                     {"params", ValuesJson(scenario_->param_values())},
                     {"status", outcome.status},
                     {"reason", outcome.reason},
                     {"scores", ValuesJson(outcome.scores)},
                     {"records", records},
                     {"hud", scenario_->hud()}};
    if (!scenario_->traceback().empty()) r["scenario"]["traceback"] = scenario_->traceback();
    if (ended) result.exit_code = outcome.status == "passed" ? kExitPassed : kExitFailed;
  }
  if (pace_) r["real_time_pacing"] = pacer_->Report();
  if (pictures_->written() > 0) {
    r["pictures"] = {{"written", pictures_->written()}, {"renderer", pictures_->renderer()}};
  } else if (!no_pictures_.empty()) {
    r["pictures"] = {{"written", 0}, {"unavailable", no_pictures_}};
  }
  if (firmware_maze) r["firmware_maze"] = "maze.png";
  if (!measurements_.empty()) r["measurements"] = measurements_;
  r["warnings"] = warnings_;
  r["exit_code"] = result.exit_code;
  if (extra.is_object()) r.update(extra);
  WriteResultRecord(options_.out_dir, r);
  result.record = std::move(r);
  return result;
}

}  // namespace unimouse
